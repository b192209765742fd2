"""The barcode reading study of the report's Fig. 4.3 and 4.5, on the batch engine.

Robots of the ``seed`` profile wander a maze (``seed-maze`` by default) under the exploration
controller :class:`mazesim.controllers.Explore`; every barcode crossing the simulator reports
(the ground truth, :attr:`mazesim.Simulator.last_crossing`) is one reading, and each decoder
fed the same sensor stream is judged on it:

- *right*: the decoder returned the crossed checkpoint and direction within
  :data:`MATCH_STEPS` control steps of the crossing;
- *wrong*: it returned another checkpoint or the other direction;
- *missed*: it returned "no valid read", or nothing.

A decoder's valid reads that match no crossing (the robot turned back on a code) are counted as
*spurious*, as a share of the same N. One setting is an obstacle threshold (volts) and a wheel
speed (rad/s); :func:`run_study` runs each threshold at the default speed and each speed at the
default threshold, with the same seeds for every setting. Robots start in random open cells of
the maze (never on a code) facing a random way, so the first N crossings spread over the
maze's checkpoints and both directions.

The controller and the decoders see the simulator over a *link* (:mod:`mazesim.barcode.link`):
``lockstep``, every control step (mazesim's way, the default), or ``ros``, a node that wakes up
every one to three steps as the report's unsynchronised ROS node did, losing the samples in
between.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, cast

import numpy as np
import numpy.typing as npt

import mazesim
from mazesim._core import BatchSimulator, RobotProfile, World
from mazesim._toml import dump_toml, load_toml
from mazesim.barcode.codebook import CodeBook
from mazesim.barcode.decoders import DECODERS, Reading, make_decoder
from mazesim.barcode.link import UnsyncedLink, check_link
from mazesim.barcode.odometry import WheelEncoders, barcode_sensor_index
from mazesim.barcode.reader import BatchBarcodeReader
from mazesim.controllers import Explore
from mazesim.errors import InvalidArgumentError, MazesimError, _known_name, _shown

__all__ = [
    "DEFAULT_ENVS",
    "DEFAULT_READINGS",
    "DEFAULT_SPEED",
    "DEFAULT_SPEEDS",
    "DEFAULT_THRESHOLD",
    "DEFAULT_THRESHOLDS",
    "MATCH_STEPS",
    "StudyResult",
    "Tally",
    "random_start_worlds",
    "run_setting",
    "run_study",
]

#: Readings (barcode crossings) per setting, as in the report.
DEFAULT_READINGS = 200
#: Obstacle thresholds in volts of the report's Fig. 4.3 (about 11 cm down to 6 cm).
DEFAULT_THRESHOLDS = (1.2, 1.4, 1.6, 1.8, 2.0)
#: Wheel speeds in rad/s of the speed study (Fig. 4.5): a quarter to all of the motor limit.
DEFAULT_SPEEDS = (1.57, 3.14, 4.71, 6.28)
#: The threshold of the speed study, volts (about 9 cm).
DEFAULT_THRESHOLD = 1.4
#: The speed of the threshold study, rad/s: half the motor limit, as Alg. 1 drives.
DEFAULT_SPEED = 3.14
#: Robots wandering at once.
DEFAULT_ENVS = 64
#: The most robots of a study (each has its own world copy, decoders and tallies in Python).
MAX_ENVS = 65_536
#: Largest gap in control steps between a crossing and the read that answers it (over the
#: ``ros`` link, plus the node's longest period: its decoder hears of the floor later).
MATCH_STEPS = 4
#: Simulated time per robot after which a setting gives up waiting for readings, seconds.
MAX_SECONDS = 3600.0

#: Called as ``progress(done, total)`` with the readings gathered so far over all settings.
Progress = Callable[[int, int], None]


@dataclass(frozen=True)
class Tally:
    """One decoder's outcome in one setting.

    Attributes:
        decoder: The decoder's name.
        threshold_v: The obstacle threshold of the exploration controller, volts.
        speed: The wheel speed of the exploration controller, rad/s.
        readings: N, the crossings judged.
        right: Crossings read as the right checkpoint and direction.
        wrong: Crossings read as another checkpoint or direction.
        missed: Crossings with no valid read.
        spurious: Valid reads that answer no crossing.
    """

    decoder: str
    threshold_v: float
    speed: float
    readings: int
    right: int
    wrong: int
    missed: int
    spurious: int

    def share(self, count: int) -> float:
        """A count as a share of the readings, in [0, 1]."""
        return count / self.readings if self.readings else 0.0

    def to_json(self, key: str) -> dict[str, Any]:
        """The tally as a JSON object of shares, led by the setting's ``key``."""
        value = self.threshold_v if key == "threshold_v" else self.speed
        return {
            "decoder": self.decoder,
            key: value,
            "right": self.share(self.right),
            "wrong": self.share(self.wrong),
            "missed": self.share(self.missed),
            "spurious": self.share(self.spurious),
            "readings": self.readings,
        }


@dataclass
class StudyResult:
    """Tallies of every decoder by threshold (default speed) and by speed (default threshold)."""

    by_threshold: list[Tally] = field(default_factory=list)
    by_speed: list[Tally] = field(default_factory=list)
    readings: int = DEFAULT_READINGS
    seed: int = 0
    world: str = "seed-maze"
    default_threshold_v: float = DEFAULT_THRESHOLD
    default_speed: float = DEFAULT_SPEED
    link: str = "lockstep"

    def to_json(self) -> dict[str, Any]:
        """The documented JSON object: shares in [0, 1] per decoder and setting."""
        return {
            "by_threshold": [t.to_json("threshold_v") for t in self.by_threshold],
            "by_speed": [t.to_json("speed") for t in self.by_speed],
            "readings": self.readings,
            "seed": self.seed,
            "world": self.world,
            "robot": "seed",
            "default_threshold_v": self.default_threshold_v,
            "default_speed": self.default_speed,
            "link": self.link,
        }


def _open_cells(world: World) -> list[tuple[float, float]]:
    """Centres of the cells reachable from the start cell that hold no checkpoint."""
    maze = world.cell_maze()
    if maze is None:
        return []
    rows = int(cast(int, maze["rows"]))
    cols = int(cast(int, maze["cols"]))
    size = float(cast(float, maze["cell_size"]))
    origin_x, origin_y = cast("tuple[float, float]", maze["origin"])
    horizontal = np.asarray(maze["horizontal"], dtype=bool)
    vertical = np.asarray(maze["vertical"], dtype=bool)
    start_col, start_row = cast("tuple[int, int]", maze["start"])
    seen = {(int(start_col), int(start_row))}
    queue = list(seen)
    while queue:
        col, row = queue.pop()
        moves = (
            (col, row - 1, horizontal[row, col]),
            (col, row + 1, horizontal[row + 1, col]),
            (col - 1, row, vertical[row, col]),
            (col + 1, row, vertical[row, col + 1]),
        )
        for next_col, next_row, wall in moves:
            if not wall and 0 <= next_col < cols and 0 <= next_row < rows:
                if (next_col, next_row) not in seen:
                    seen.add((next_col, next_row))
                    queue.append((next_col, next_row))
    centres = {
        (col, row): (origin_x + (col + 0.5) * size, origin_y + (rows - row - 0.5) * size)
        for col, row in seen
    }
    for checkpoint in world.checkpoints():
        x, y = cast("tuple[float, float]", checkpoint["center"])
        col = math.floor((x - origin_x) / size)
        row = rows - 1 - math.floor((y - origin_y) / size)
        centres.pop((col, row), None)
    return [centres[key] for key in sorted(centres)]


def random_start_worlds(world: World, count: int, seed: int) -> list[World]:
    """Copies of a cell-maze world, each starting in a random open cell facing a random way.

    Cells holding a checkpoint are left out, so no robot starts on a code. A world without a cell
    maze is returned ``count`` times as it is.
    """
    cells = _open_cells(world)
    if not cells:
        return [world] * count
    layout = load_toml(world.to_toml(), source=world.name)
    if "start" in layout:
        return [world] * count
    rng = np.random.default_rng(seed)
    worlds = []
    for _ in range(count):
        x, y = cells[int(rng.integers(len(cells)))]
        yaw = float(rng.uniform(-math.pi, math.pi))
        layout["start"] = {"x": x, "y": y, "yaw": yaw}
        worlds.append(World.from_toml(dump_toml(layout), source=f"{world.name} (random start)"))
    return worlds


def _judge(
    name: str,
    truths: list[tuple[int, int, int]],
    reads: list[tuple[int, int, Reading]],
    threshold_v: float,
    speed: float,
    window: int = MATCH_STEPS,
) -> Tally:
    """Matches a decoder's reads to the crossings, robot by robot, nearest in time first, at
    most ``window`` control steps apart."""
    by_env: dict[int, list[tuple[int, int, Reading]]] = {}
    for order, (step, env, reading) in enumerate(reads):
        by_env.setdefault(env, []).append((step, order, reading))
    used: set[int] = set()
    right = wrong = missed = 0
    for step, env, signed in truths:
        candidates = [
            (abs(read_step - step), order, reading)
            for read_step, order, reading in by_env.get(env, [])
            if order not in used and abs(read_step - step) <= window
        ]
        if not candidates:
            missed += 1
            continue
        _, order, reading = min(candidates, key=lambda c: (c[0], c[1]))
        used.add(order)
        if not reading.valid:
            missed += 1
        elif reading.signed_id == signed:
            right += 1
        else:
            wrong += 1
    last_step = truths[-1][0] if truths else 0
    spurious = sum(
        1
        for order, (step, _, reading) in enumerate(reads)
        if order not in used and reading.valid and step <= last_step
    )
    return Tally(name, threshold_v, speed, len(truths), right, wrong, missed, spurious)


def run_setting(
    world: World,
    threshold_v: float,
    speed: float,
    decoders: Sequence[str] = tuple(DECODERS),
    readings: int = DEFAULT_READINGS,
    seed: int = 0,
    envs: int = DEFAULT_ENVS,
    progress: Callable[[int], None] | None = None,
    link: str = "lockstep",
) -> list[Tally]:
    """Runs one setting until ``readings`` crossings are judged; one tally per decoder.

    Raises:
        UnknownNameError: An unknown link.
        InvalidArgumentError: A bad count, threshold or speed, or a world without checkpoints.
        MazesimError: Fewer crossings than asked for within :data:`MAX_SECONDS` per robot.
    """
    check_link(link)
    if readings < 1 or not 1 <= envs <= MAX_ENVS:
        raise InvalidArgumentError(
            f"expected at least one reading and 1 to {MAX_ENVS} robots, found {readings} and {envs}"
        )
    if not (math.isfinite(threshold_v) and threshold_v > 0.0):
        raise InvalidArgumentError(f"expected a positive threshold in volts, found {threshold_v}")
    robot = RobotProfile.builtin("seed")
    if not (math.isfinite(speed) and 0.0 < speed <= robot.max_wheel_speed):
        raise InvalidArgumentError(
            f"expected a wheel speed in (0, {robot.max_wheel_speed}] rad/s, found {speed}"
        )
    book = CodeBook.from_world(world)
    step_ms = world.basic_time_step_ms
    batch = BatchSimulator(
        random_start_worlds(world, envs, seed),
        robot="seed",
        seeds=[(seed * 1_000_003 + index) % 2**64 for index in range(envs)],
        noise=True,
        control_step_ms=step_ms,
    )
    observations, poses, colliding, crossings = batch.output_buffers()
    batch.observe(observations, poses, colliding, crossings)
    distance_width = batch.distance_width
    ground_column = distance_width + barcode_sensor_index(robot)
    controller = Explore(threshold=threshold_v, speed=speed, seed=seed)
    encoders = WheelEncoders(robot, envs, step_ms)
    readers = {
        name: BatchBarcodeReader([make_decoder(name, book) for _ in range(envs)], robot)
        for name in decoders
    }
    unsynced = UnsyncedLink(envs, seed) if link == "ros" else None
    window = MATCH_STEPS + (unsynced.longest_period if unsynced is not None else 0)
    actions = np.zeros((envs, 2), dtype=np.float32)
    truths: list[tuple[int, int, int]] = []
    reads: dict[str, list[tuple[int, int, Reading]]] = {name: [] for name in decoders}

    def feed(step: int, mask: npt.NDArray[np.bool_] | None = None) -> None:
        """Gives the decoders (of the robots in ``mask``) the barcode sensor's sample."""
        for name, reader in readers.items():
            ground = observations[:, ground_column]
            reads[name].extend(
                (step, env, reading)
                for env, reading in reader.update(ground, encoders.values, mask)
            )

    if unsynced is None:
        feed(0)  # the start, off every code
    max_steps = math.ceil(MAX_SECONDS * 1000.0 / step_ms)
    step = 0
    while True:
        step += 1
        if unsynced is None:
            actions = controller.batch(observations[:, :distance_width])
        else:
            # The nodes awake now read the sensors (their decoders get this sample) and send
            # new wheel speeds; the others' motors keep the last ones.
            awake = unsynced.tick()
            feed(step, awake)
            commands = controller.batch(observations[:, :distance_width], awake)
            actions[awake] = commands[awake]
        batch.step(actions, observations, poses, colliding, crossings)
        encoders.step(actions)
        if unsynced is None:
            feed(step)
        for env in np.flatnonzero(crossings):
            if len(truths) < readings:
                truths.append((step, int(env), int(crossings[env])))
                if progress is not None:
                    progress(len(truths))
        if len(truths) >= readings and step >= truths[-1][0] + window:
            break
        if step >= max_steps:
            raise MazesimError(
                f"only {len(truths)} of {readings} barcode crossings in {MAX_SECONDS:.0f} s "
                f"of {envs} robots in {_shown(world.name)} (threshold {threshold_v} V, "
                f"speed {speed} rad/s)"
            )
    return [_judge(name, truths, reads[name], threshold_v, speed, window) for name in decoders]


def run_study(
    world: World | None = None,
    readings: int = DEFAULT_READINGS,
    thresholds: Sequence[float] = DEFAULT_THRESHOLDS,
    speeds: Sequence[float] = DEFAULT_SPEEDS,
    decoders: Sequence[str] = tuple(DECODERS),
    seed: int = 0,
    envs: int = DEFAULT_ENVS,
    default_threshold_v: float = DEFAULT_THRESHOLD,
    default_speed: float = DEFAULT_SPEED,
    progress: Progress | None = None,
    link: str = "lockstep",
) -> StudyResult:
    """Runs the threshold study (at the default speed) and the speed study (at the default
    threshold); a setting in both is run once.

    Args:
        world: The maze; ``seed-maze`` by default.
        readings: Crossings judged per setting.
        thresholds: Obstacle thresholds in volts.
        speeds: Wheel speeds in rad/s.
        decoders: Decoder names (see :data:`mazesim.barcode.DECODERS`).
        seed: Seed of the starts, the sensor noise and the controller's choices.
        envs: Robots wandering at once.
        default_threshold_v: The threshold of the speed study.
        default_speed: The speed of the threshold study.
        progress: Called with the readings gathered so far and the total.
        link: How the controller and decoders see the simulator: ``lockstep`` or ``ros``
            (see :mod:`mazesim.barcode.link`).

    Raises:
        UnknownNameError: An unknown decoder name or link.
        InvalidArgumentError: Empty lists, bad values.
    """
    for name in decoders:
        _known_name(name, "decoder", sorted(DECODERS))
    check_link(link)
    if not decoders or not (thresholds or speeds):
        raise InvalidArgumentError("expected at least one decoder and one threshold or speed")
    world = mazesim.load_world("seed-maze") if world is None else world
    settings: list[tuple[float, float]] = []
    for threshold in thresholds:
        settings.append((float(threshold), float(default_speed)))
    for speed in speeds:
        settings.append((float(default_threshold_v), float(speed)))
    unique = list(dict.fromkeys(settings))
    total = readings * len(unique)
    done = 0
    tallies: dict[tuple[float, float], list[Tally]] = {}
    for threshold, speed in unique:

        def report(count: int, base: int = done) -> None:
            if progress is not None:
                progress(base + count, total)

        tallies[(threshold, speed)] = run_setting(
            world, threshold, speed, decoders, readings, seed, envs, report, link
        )
        done += readings
    result = StudyResult(
        readings=readings,
        seed=seed,
        world=world.name,
        default_threshold_v=float(default_threshold_v),
        default_speed=float(default_speed),
        link=link,
    )
    for threshold in thresholds:
        result.by_threshold.extend(tallies[(float(threshold), float(default_speed))])
    for speed in speeds:
        result.by_speed.extend(tallies[(float(default_threshold_v), float(speed))])
    return result
