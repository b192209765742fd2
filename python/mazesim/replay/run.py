"""The recorded-run format: what a run did, step by step, for the replay, videos and plots.

A :class:`RecordedRun` holds the world (as its TOML text, so a run file stands alone), the robot,
the controller and one :class:`RecordedEpisode` per recorded episode: for every frame (frame 0 is
the start, frame ``t`` the state after ``t`` control steps) the pose, the sensor readings, the
distance each distance-sensor ray travels before it meets a wall, whether the robot touches a wall,
the checkpoint event of the step that led there, and what the controller did next (an action code
or wheel speeds, and for the hierarchical navigator the running sub-task and its Table 4.1 levels).
The hierarchical navigator's decisions at checkpoints are :class:`Decision` records.

On disk a run is one JSON object (``.json``, or gzip-compressed ``.json.gz``), never a pickle,
with numbers quantised to whole units (0.1 mm, milliradians, millivolts) so a 4,000-step episode
takes a few hundred kB. The format is versioned (:data:`FORMAT_VERSION`, ``"major.minor"``):
a reader accepts any minor version of its own major version, ignores fields it does not know,
and refuses a newer major version with :class:`RunFormatError`. ``docs/watching.md`` describes
every field.
"""

from __future__ import annotations

import gzip
import json
import os
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._atomic import atomic_file
from mazesim._core import RobotProfile, World
from mazesim.errors import MazesimIOError, RunFormatError

__all__ = [
    "FORMAT_NAME",
    "FORMAT_VERSION",
    "Decision",
    "RecordedEpisode",
    "RecordedRun",
    "load_run",
    "save_run",
]

#: The ``format`` field of every run file.
FORMAT_NAME = "mazesim-run"
#: The version this module writes: ``(major, minor)``. A newer minor version only adds fields.
FORMAT_VERSION = (1, 0)
#: Positions are stored in units of 0.1 mm, headings in milliradians, ray lengths in mm.
POSITION_UNIT = 1e-4
YAW_UNIT = 1e-3
RAY_UNIT = 1e-3
WHEEL_SPEED_UNIT = 1e-2


@dataclass
class Decision:
    """A choice of the higher level at a checkpoint event.

    Attributes:
        number: 1, 2, ... in the order of the episode (shown as ``D1``, ``D2``...).
        frame: The frame whose readings the choice was made on (the step that crossed the code
            led to it).
        checkpoint: The checkpoint's id.
        arrival: Whether the code was read in its own direction (arrival) or backwards
            (departure).
        code: The bars as the robot read them, in the order it crossed them (``"10110"``).
        q_values: The higher level's value of each sub-task in that state.
        chosen: The sub-task chosen (an index into the run's ``subtask_names``).
        greedy: Whether it was the highest-valued sub-task (False: an exploring choice).
    """

    number: int
    frame: int
    checkpoint: int
    arrival: bool
    code: str
    q_values: list[float]
    chosen: int
    greedy: bool

    def as_json(self) -> dict[str, Any]:
        """The decision as a JSON object."""
        return {
            "number": self.number,
            "frame": self.frame,
            "checkpoint": self.checkpoint,
            "direction": "arrival" if self.arrival else "departure",
            "code": self.code,
            "q_values": [round(float(value), 4) for value in self.q_values],
            "chosen": self.chosen,
            "greedy": self.greedy,
        }

    @staticmethod
    def from_json(values: dict[str, Any]) -> Decision:
        """Reads a decision written by :meth:`as_json`."""
        return Decision(
            number=int(values["number"]),
            frame=int(values["frame"]),
            checkpoint=int(values["checkpoint"]),
            arrival=values["direction"] == "arrival",
            code=str(values["code"]),
            q_values=[float(value) for value in values["q_values"]],
            chosen=int(values["chosen"]),
            greedy=bool(values["greedy"]),
        )


@dataclass
class RecordedEpisode:
    """One episode, frame by frame (``F`` frames; frame 0 is the start).

    Attributes:
        number: The episode's number in its run.
        poses: (F, 3) x, y (m) and yaw (rad).
        readings: (F, S) the distance sensors, then the ground sensors, in the robot's units.
        rays: (F, D) how far each distance sensor's ray reaches before a wall (m, capped at
            the sensor's range).
        colliding: (F,) whether the robot touches a wall.
        events: (F,) the checkpoint event of the step into the frame (+id arrival, -id
            departure, 0 none).
        actions: The action code taken from each frame (``""`` after the last), or None.
        wheel_speeds: (F, 2) wheel speeds (rad/s) set from each frame, or None.
        subtasks: (F,) the sub-task that chose the action from each frame (-1: none), or None.
        levels: (F, 6) Table 4.1 levels of the six Sharp distances, or None.
        decisions: The higher level's choices.
        outcome: How the episode ended (``"goal reached"``, ``"out of time"``...).
    """

    number: int
    poses: npt.NDArray[np.float64]
    readings: npt.NDArray[np.float64]
    rays: npt.NDArray[np.float64]
    colliding: npt.NDArray[np.bool_]
    events: npt.NDArray[np.int64]
    actions: list[str] | None = None
    wheel_speeds: npt.NDArray[np.float64] | None = None
    subtasks: npt.NDArray[np.int64] | None = None
    levels: npt.NDArray[np.int64] | None = None
    decisions: list[Decision] = field(default_factory=list)
    outcome: str = ""

    @property
    def frames(self) -> int:
        """The number of frames."""
        return len(self.poses)


@dataclass
class RecordedRun:
    """A recorded run: the world, the robot, the controller and the episodes.

    Attributes:
        world: The world the run drove in.
        robot: The robot profile's name.
        controller: What drove the robot (``"hrl"``, ``"avoid-collision"``, a controller file).
        seed: The run's seed.
        control_step_ms: The time between frames.
        episodes: The recorded episodes.
        subtask_names: The higher level's sub-tasks, in table order (hierarchical runs).
        reading_scale: Readings are stored as whole multiples of ``1 / reading_scale``.
    """

    world: World
    robot: str
    controller: str
    seed: int
    control_step_ms: float
    episodes: list[RecordedEpisode] = field(default_factory=list)
    subtask_names: list[str] = field(default_factory=list)
    reading_scale: float = 1.0

    @property
    def robot_profile(self) -> RobotProfile:
        """The robot's profile."""
        return RobotProfile.builtin(self.robot)

    def sensor_names(self) -> list[str]:
        """Names of the readings' columns: the distance sensors, then the ground sensors."""
        profile = self.robot_profile
        return [*profile.distance_sensor_names, *profile.ground_sensor_names]

    def as_json(self) -> dict[str, Any]:
        """The run as the JSON object of its file."""
        major, minor = FORMAT_VERSION
        return {
            "format": FORMAT_NAME,
            "version": f"{major}.{minor}",
            "world": {"name": self.world.name, "toml": self.world.to_toml()},
            "robot": self.robot,
            "controller": self.controller,
            "seed": self.seed,
            "control_step_ms": self.control_step_ms,
            "sensor_names": self.sensor_names(),
            "subtask_names": list(self.subtask_names),
            "reading_scale": self.reading_scale,
            "episodes": [self._episode_json(episode) for episode in self.episodes],
        }

    def _episode_json(self, episode: RecordedEpisode) -> dict[str, Any]:
        values: dict[str, Any] = {
            "number": episode.number,
            "outcome": episode.outcome,
            "frames": episode.frames,
            "x": _whole(episode.poses[:, 0], POSITION_UNIT),
            "y": _whole(episode.poses[:, 1], POSITION_UNIT),
            "yaw": _whole(episode.poses[:, 2], YAW_UNIT),
            "readings": _whole(episode.readings, 1.0 / self.reading_scale),
            "rays": _whole(episode.rays, RAY_UNIT),
            "contacts": np.flatnonzero(episode.colliding).tolist(),
            "events": [
                [int(frame), int(episode.events[frame])] for frame in np.flatnonzero(episode.events)
            ],
            "decisions": [decision.as_json() for decision in episode.decisions],
        }
        if episode.actions is not None:
            values["actions"] = list(episode.actions)
        if episode.wheel_speeds is not None:
            values["wheel_speeds"] = _whole(episode.wheel_speeds, WHEEL_SPEED_UNIT)
        if episode.subtasks is not None:
            values["subtasks"] = "".join(_subtask_letter(int(s)) for s in episode.subtasks)
        if episode.levels is not None:
            values["levels"] = ["".join(str(int(v)) for v in row) for row in episode.levels]
        return values


def _whole(values: npt.ArrayLike, unit: float) -> list[Any]:
    """Values as whole multiples of ``unit`` (nested lists for 2-D arrays)."""
    array = np.asarray(values, dtype=np.float64)
    whole: list[Any] = np.rint(array / unit).astype(np.int64).tolist()
    return whole


def _subtask_letter(subtask: int) -> str:
    """One character per frame: ``"-"`` for none, else the sub-task's index."""
    return "-" if subtask < 0 else str(subtask)


def save_run(run: RecordedRun, path: str | os.PathLike[str]) -> None:
    """Writes a run file atomically (gzip-compressed when the name ends in ``.gz``)."""
    text = json.dumps(run.as_json(), separators=(",", ":")).encode("utf-8")
    if os.fspath(path).endswith(".gz"):
        text = gzip.compress(text, mtime=0)
    with atomic_file(path) as handle:
        handle.write(text)


def load_run(path: str | os.PathLike[str]) -> RecordedRun:
    """Reads a run file written by :func:`save_run` (this or an older minor version).

    Raises:
        MazesimIOError: The file cannot be read.
        RunFormatError: It is not a run file, or of a newer major version, or malformed.
    """
    name = os.fspath(path)
    try:
        with open(name, "rb") as handle:
            data = handle.read()
    except OSError as error:
        failure = MazesimIOError(f"{name}: cannot read the run: {error.strerror or error}")
        failure.filename = name
        raise failure from None
    try:
        if data[:2] == b"\x1f\x8b":
            data = gzip.decompress(data)
        values = json.loads(data.decode("utf-8"))
    except (OSError, EOFError, UnicodeDecodeError, json.JSONDecodeError) as error:
        raise RunFormatError(f"{name}: expected a mazesim run (JSON), found: {error}") from None
    return run_from_json(values, name)


def run_from_json(values: Any, source: str = "<run>") -> RecordedRun:
    """A run from the JSON object of a run file; ``source`` names it in errors.

    Raises:
        RunFormatError: Not a run, a newer major version, or a field missing or malformed.
    """
    if not isinstance(values, dict) or values.get("format") != FORMAT_NAME:
        found = values.get("format") if isinstance(values, dict) else type(values).__name__
        raise RunFormatError(f"{source}: expected format {FORMAT_NAME!r}, found {found!r}")
    version = str(values.get("version", ""))
    try:
        major = int(version.split(".")[0])
    except ValueError:
        raise RunFormatError(
            f"{source}: expected a version such as '1.0', found {version!r}"
        ) from None
    if major != FORMAT_VERSION[0]:
        newer = "a newer" if major > FORMAT_VERSION[0] else "an older"
        raise RunFormatError(
            f"{source}: this mazesim reads run format {FORMAT_VERSION[0]}.x; the file is "
            f"version {version} ({newer} format): "
            + ("upgrade mazesim to read it" if major > FORMAT_VERSION[0] else "record it again")
        )
    try:
        scale = float(values.get("reading_scale", 1.0))
        run = RecordedRun(
            world=World.from_toml(values["world"]["toml"], f"{source}: world"),
            robot=str(values["robot"]),
            controller=str(values["controller"]),
            seed=int(values["seed"]),
            control_step_ms=float(values["control_step_ms"]),
            subtask_names=[str(name) for name in values.get("subtask_names", [])],
            reading_scale=scale,
        )
        run.episodes = [_episode_from_json(episode, scale) for episode in values["episodes"]]
    except (KeyError, TypeError, ValueError, IndexError) as error:
        raise RunFormatError(
            f"{source}: a field is missing or malformed ({type(error).__name__}: {error})"
        ) from None
    return run


def _episode_from_json(values: dict[str, Any], reading_scale: float) -> RecordedEpisode:
    frames = int(values["frames"])
    poses = np.column_stack(
        [
            np.asarray(values["x"], dtype=np.float64) * POSITION_UNIT,
            np.asarray(values["y"], dtype=np.float64) * POSITION_UNIT,
            np.asarray(values["yaw"], dtype=np.float64) * YAW_UNIT,
        ]
    ).reshape(frames, 3)
    colliding = np.zeros(frames, dtype=bool)
    colliding[np.asarray(values["contacts"], dtype=np.int64)] = True
    events = np.zeros(frames, dtype=np.int64)
    for frame, event in values["events"]:
        events[int(frame)] = int(event)
    episode = RecordedEpisode(
        number=int(values["number"]),
        poses=poses,
        readings=np.asarray(values["readings"], dtype=np.float64).reshape(frames, -1)
        / reading_scale,
        rays=np.asarray(values["rays"], dtype=np.float64).reshape(frames, -1) * RAY_UNIT,
        colliding=colliding,
        events=events,
        outcome=str(values.get("outcome", "")),
        decisions=[Decision.from_json(decision) for decision in values.get("decisions", [])],
    )
    if "actions" in values:
        episode.actions = [str(code) for code in values["actions"]]
    if "wheel_speeds" in values:
        speeds = np.asarray(values["wheel_speeds"], dtype=np.float64) * WHEEL_SPEED_UNIT
        episode.wheel_speeds = speeds.reshape(frames, 2)
    if "subtasks" in values:
        episode.subtasks = np.array(
            [-1 if letter == "-" else int(letter) for letter in values["subtasks"]], dtype=np.int64
        )
    if "levels" in values:
        episode.levels = np.array(
            [[int(v) for v in row] for row in values["levels"]], dtype=np.int64
        ).reshape(frames, -1)
    return episode
