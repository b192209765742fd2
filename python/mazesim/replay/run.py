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
a writer writes the oldest version that holds its run, and a reader accepts its own version and
every older minor version of its major version and refuses a newer one, major or minor, with
:class:`RunFormatError` naming the version to upgrade to: every minor version so far adds fields
an older reader would misread by ignoring them (a 1.2 reader would draw a 1.3 run's profile file
robot named ``e-puck`` as the built-in e-puck). ``docs/watching.md`` describes
every field.

A run of several robots (a world's ``[[robots]]``, a Webots world of several robots) is version
1.1: the run's ``robots`` lists every robot (:class:`RunRobot`), each episode's own fields are
robot 0's, and its ``robots`` holds the tracks of the others, each with the fields of an episode.
A run of one robot is written as version 1.0, byte for byte as before. A run in which robots
join or leave the world (a Webots supervisor imports or removes them) is version 1.2: a robot of
the run's ``robots`` is in the world from its ``from_frame`` to its ``until_frame`` only (its
track holds a frame for every frame of the episode, standing still where it is not). A run of
a robot whose profile is no built-in one (a profile file's) is version 1.3: the run holds that
profile's TOML text (``robot_profile``, a robot's ``profile_toml``), so it replays with that
profile even after the file changes or is gone. A run in which the walls change while it runs
(a Webots supervisor moves, imports or removes them) is version 1.4: an episode's ``walls``
lists each change, the frame from which the walls are as it gives them (boxes), the run's
world's walls before the first.
"""

from __future__ import annotations

import gzip
import json
import os
import zlib
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._atomic import atomic_file
from mazesim._core import RobotProfile, World, robot_profile_names
from mazesim._paths import found_kind, read_input, utf8_text
from mazesim._sizes import number_array
from mazesim.errors import InvalidArgumentError, MazesimError, RunFormatError, _shown
from mazesim.replay.run_fields import RunFields

__all__ = [
    "FORMAT_NAME",
    "FORMAT_VERSION",
    "Decision",
    "RecordedEpisode",
    "RecordedRun",
    "RunRobot",
    "load_run",
    "save_run",
]

#: The ``format`` field of every run file.
FORMAT_NAME = "mazesim-run"
#: The newest version this module writes and reads: ``(major, minor)``. A newer minor version adds
#: fields (and is refused by an older reader, which would misread it). Runs whose walls change are
#: 1.4 (an episode's ``walls``), runs of a profile file's robot 1.3 (the profile's TOML text),
#: runs in which robots join or leave 1.2 (the robots' ``from_frame`` and ``until_frame``), other
#: runs of several robots 1.1 (the ``robots`` fields), runs of one 1.0.
FORMAT_VERSION = (1, 4)
#: The version of a run of a robot whose profile is a profile file's.
OWN_PROFILE_VERSION = (1, 3)
#: The version of a run in which robots join or leave the world.
PRESENCE_VERSION = (1, 2)
#: The version of a run of several robots all in the world from its first frame to its last.
SEVERAL_ROBOTS_VERSION = (1, 1)
#: The version of a run of one robot, which needs none of 1.1's fields.
ONE_ROBOT_VERSION = (1, 0)
#: The most robots a run may hold: a world's limit (``mazesim_core::limits::MAX_ROBOTS``).
MAX_RUN_ROBOTS = 64
#: Positions are stored in units of 0.1 mm, headings in milliradians, ray lengths in mm.
POSITION_UNIT = 1e-4
YAW_UNIT = 1e-3
RAY_UNIT = 1e-3
WHEEL_SPEED_UNIT = 1e-2
#: The largest x or y of a run file, in its units: the worlds' limit, 1 km from the origin.
POSITION_BOUND = 1_000.0 / POSITION_UNIT
#: The largest yaw of a run file, in its units: the worlds' limit, 1000 radians.
YAW_BOUND = 1_000.0 / YAW_UNIT
#: The most lists and objects a run file may hold: 3 per frame (a frame's readings, rays and
#: wheel speeds) for over a million frames, hundreds of long episodes; counted before the JSON is
#: parsed, so that a small file inflating to millions of empty lists is refused at once.
MAX_RUN_CONTAINERS = 4 * 1024 * 1024
#: The most values (numbers, strings, lists) a run file may hold, counted likewise.
MAX_RUN_VALUES = 32 * 1024 * 1024
#: The most bytes of JSON a run file may hold (once decompressed): a 4,000-step episode takes a
#: few hundred kB, so this is hundreds of long episodes, and parsing it stays within a few GB.
MAX_RUN_BYTES = 256 * 1024 * 1024
#: The Table 4.1 levels of a frame: one per Sharp distance.
NUM_LEVELS = 6
#: The numbers of a wall box of an episode's ``walls``: centre x, y and size x, y (0.1 mm), yaw
#: (milliradians).
WALL_BOX_NUMBERS = 5
#: The most wall changes an episode may hold, and the most boxes one change may hold (a
#: world's limit on its walls, ``mazesim_core::limits``, is far below).
MAX_WALL_CHANGES = 1_000_000
MAX_WALL_BOXES = 1_000_000


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
        robots: The tracks of the run's other robots (robot 0's episode only).
        walls: Each change of the walls while the episode ran (a Webots supervisor moved,
            imported or removed some): the frame from which they stand so and the (N, 5) wall
            boxes (centre x, y, size x, y in m, yaw in rad), in frame order; before the first,
            the run's world's walls (robot 0's episode only).
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
    robots: list[RecordedEpisode] = field(default_factory=list)
    walls: list[tuple[int, npt.NDArray[np.float64]]] = field(default_factory=list)

    @property
    def frames(self) -> int:
        """The number of frames."""
        return len(self.poses)

    def walls_at(self, frame: int) -> npt.NDArray[np.float64] | None:
        """The wall boxes (N, 5) at ``frame`` when the walls changed by then, else None (the
        run's world's)."""
        boxes = None
        for start, changed in self.walls:
            if start > frame:
                break
            boxes = changed
        return boxes


def _reading_names(profile: RobotProfile) -> list[str]:
    return [*profile.distance_sensor_names, *profile.ground_sensor_names]


def written_profile(profile: RobotProfile | None) -> str | None:
    """The TOML text a run's file holds of ``profile``: None for a built-in profile, which its
    name alone says."""
    if profile is None:
        return None
    name = profile.name
    if name in robot_profile_names() and profile == RobotProfile.builtin(name):
        return None
    return profile.to_toml()


def _run_profile(name: str, own: RobotProfile | None) -> RobotProfile:
    """The profile a run's robot drove with: its own, or the built-in one of its name."""
    return own if own is not None else RobotProfile.builtin(name)


@dataclass
class RunRobot:
    """One robot of a run of several robots.

    Attributes:
        name: Its name in the world.
        profile: Its robot profile's name.
        own_profile: Its profile itself when the run was given it (a profile file's), which the
            run's file then holds; None: the built-in profile ``profile`` names.
        from_frame: The first frame it is in the world: that of its import, for a robot a
            supervisor imported after the start (it stands still at its import pose before).
        until_frame: The last frame it is in the world, that of its removal, which holds
            where it was then, or None: to the end (a robot a supervisor removed stands still
            there after).
    """

    name: str
    profile: str
    from_frame: int = 0
    until_frame: int | None = None
    own_profile: RobotProfile | None = None

    @property
    def always_present(self) -> bool:
        """Whether it is in the world from the first frame to the last."""
        return self.from_frame == 0 and self.until_frame is None

    def present(self, frame: int) -> bool:
        """Whether it is in the world at ``frame``."""
        return self.from_frame <= frame and (self.until_frame is None or frame <= self.until_frame)

    def as_json(self) -> dict[str, Any]:
        """Its entry of the run's ``robots``."""
        values: dict[str, Any] = {
            "name": self.name,
            "profile": self.profile,
            "sensor_names": self.sensor_names(),
        }
        own = written_profile(self.own_profile)
        if own is not None:
            values["profile_toml"] = own
        if self.from_frame:
            values["from_frame"] = self.from_frame
        if self.until_frame is not None:
            values["until_frame"] = self.until_frame
        return values

    @property
    def robot_profile(self) -> RobotProfile:
        """The robot's profile."""
        return _run_profile(self.profile, self.own_profile)

    def sensor_names(self) -> list[str]:
        """Names of its readings' columns: the distance sensors, then the ground sensors."""
        return _reading_names(self.robot_profile)


@dataclass
class RecordedRun:
    """A recorded run: the world, the robot, the controller and the episodes.

    Attributes:
        world: The world the run drove in.
        robot: The robot profile's name.
        own_profile: The robot's profile itself when the run was given it (a profile file's),
            which the run's file then holds; None: the built-in profile ``robot`` names.
        controller: What drove the robot (``"hrl"``, ``"avoid-collision"``, a controller file).
        seed: The run's seed.
        control_step_ms: The time between frames.
        episodes: The recorded episodes.
        subtask_names: The higher level's sub-tasks, in table order (hierarchical runs).
        reading_scale: Readings are stored as whole multiples of ``1 / reading_scale``.
        robots: Every robot of a run of several robots, robot 0 (``robot``) first; empty for a
            run of one robot. Each episode's ``robots`` then holds robots 1, 2... in this order.
    """

    world: World
    robot: str
    controller: str
    seed: int
    control_step_ms: float
    episodes: list[RecordedEpisode] = field(default_factory=list)
    subtask_names: list[str] = field(default_factory=list)
    reading_scale: float = 1.0
    robots: list[RunRobot] = field(default_factory=list)
    own_profile: RobotProfile | None = None

    @property
    def robot_profile(self) -> RobotProfile:
        """The robot's profile."""
        return _run_profile(self.robot, self.own_profile)

    def sensor_names(self) -> list[str]:
        """Names of the readings' columns: the distance sensors, then the ground sensors."""
        return _reading_names(self.robot_profile)

    def episode(self, index: int) -> RecordedEpisode:
        """Episode ``index``, counted from 0.

        Raises:
            InvalidArgumentError: The run has no such episode.
        """
        if not 0 <= index < len(self.episodes):
            raise InvalidArgumentError(
                f"expected an episode from 0 to {len(self.episodes) - 1}, found {index}"
            )
        return self.episodes[index]

    def as_json(self) -> dict[str, Any]:
        """The run as the JSON object of its file."""
        own = written_profile(self.own_profile)
        if any(episode.walls for episode in self.episodes):
            major, minor = FORMAT_VERSION
        elif own is not None or any(written_profile(r.own_profile) for r in self.robots):
            major, minor = OWN_PROFILE_VERSION
        elif not self.robots:
            major, minor = ONE_ROBOT_VERSION
        elif all(robot.always_present for robot in self.robots):
            major, minor = SEVERAL_ROBOTS_VERSION
        else:
            major, minor = PRESENCE_VERSION
        values: dict[str, Any] = {
            "format": FORMAT_NAME,
            "version": f"{major}.{minor}",
            "world": {"name": self.world.name, "toml": self.world.to_toml()},
            "robot": self.robot,
            **({"robot_profile": own} if own is not None else {}),
            "controller": self.controller,
            "seed": self.seed,
            "control_step_ms": self.control_step_ms,
            "sensor_names": self.sensor_names(),
            "subtask_names": list(self.subtask_names),
            "reading_scale": self.reading_scale,
            "episodes": [self._episode_json(episode) for episode in self.episodes],
        }
        if self.robots:
            values["robots"] = [robot.as_json() for robot in self.robots]
        return values

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
        if episode.robots:
            values["robots"] = [self._episode_json(track) for track in episode.robots]
        if episode.walls:
            values["walls"] = [
                [int(frame), _wall_boxes_json(boxes)] for frame, boxes in episode.walls
            ]
        return values


#: What a NaN in a run being saved stands for: a number the saved text cannot hold, which
#: :func:`save_run` refuses naming its field when it reads the text back as :func:`load_run` does.
SAVED_AND_REFUSED = "a misfit the read-back check refuses, by field"


def _wall_boxes_json(boxes: npt.ArrayLike) -> list[list[int]]:
    """Wall boxes (N, 5 or more) as whole units: centre and size in 0.1 mm, yaw in mrad."""
    array = number_array(
        boxes, "boxes", nan_means=SAVED_AND_REFUSED, inf_means=SAVED_AND_REFUSED
    ).reshape(-1, WALL_BOX_NUMBERS)
    units = np.array([POSITION_UNIT] * 4 + [YAW_UNIT])
    whole: list[list[int]] = np.rint(array / units).astype(np.int64).tolist()
    return whole


def _whole(values: npt.ArrayLike, unit: float) -> list[Any]:
    """Values as whole multiples of ``unit`` (nested lists for 2-D arrays)."""
    array = number_array(values, "values", nan_means=SAVED_AND_REFUSED, inf_means=SAVED_AND_REFUSED)
    whole: list[Any] = np.rint(array / unit).astype(np.int64).tolist()
    return whole


def _subtask_letter(subtask: int) -> str:
    """One character per frame: ``"-"`` for none, else the sub-task's index."""
    return "-" if subtask < 0 else str(subtask)


def save_run(run: RecordedRun, path: str | os.PathLike[str]) -> None:
    """Writes a run file atomically (gzip-compressed when the name ends in ``.gz``).

    Raises:
        InvalidArgumentError: The run holds what :func:`load_run` would refuse (a NaN pose, an
            infinite wheel speed, a seed below 0): nothing is written, and a file already at
            ``path`` is kept, since a save must never leave a file its loader cannot read.
    """
    with np.errstate(invalid="ignore"):  # a NaN's cast is refused just below, by the reader
        values = run.as_json()
    try:
        run_from_json(values, os.fspath(path))
    except RunFormatError as refused:
        raise InvalidArgumentError(
            f"save_run: expected a run load_run reads back, found one it refuses ({refused}); "
            "nothing written"
        ) from None
    text = json.dumps(values, separators=(",", ":")).encode("utf-8")
    if os.fspath(path).endswith(".gz"):
        text = gzip.compress(text, mtime=0)
    with atomic_file(path) as handle:
        handle.write(text)


def load_run(path: str | os.PathLike[str]) -> RecordedRun:
    """Reads a run file written by :func:`save_run` (this or an older minor version of the format).

    The file (once decompressed) may hold at most :data:`MAX_RUN_BYTES` bytes of JSON; every
    field is checked before it is used.

    Raises:
        MazesimIOError: The file cannot be read.
        RunFormatError: It is not a run file, or of a newer version (major or minor), or too
            large, or a field is missing or malformed (the message names the field).
    """
    name = os.fspath(path)
    data = read_input(name, MAX_RUN_BYTES, "the run")
    too_large = RunFormatError(
        f"{name}: expected a run of at most {MAX_RUN_BYTES} bytes of JSON, found more"
    )
    try:
        if data[:2] == b"\x1f\x8b":
            data = _decompressed(data, MAX_RUN_BYTES, too_large, name)
        if len(data) > MAX_RUN_BYTES:
            raise too_large
        _check_structure(data, name)
        values = json.loads(utf8_text(data, name, "a mazesim run (JSON)", RunFormatError))
    except RecursionError:
        raise RunFormatError(
            f"{name}: expected a mazesim run (JSON), found deeper nesting than any run has"
        ) from None
    except (OSError, EOFError, zlib.error, json.JSONDecodeError) as error:
        kind = found_kind(data, ("a recorded run",)) if data.strip() else "an empty file"
        if kind is not None:  # another of mazesim's files: say which, and where it is taken
            raise RunFormatError(f"{name}: expected a mazesim run (JSON), found {kind}") from None
        raise RunFormatError(f"{name}: expected a mazesim run (JSON), found: {error}") from None
    return run_from_json(values, name)


def _too_many_containers(name: str) -> RunFormatError:
    return RunFormatError(
        f"{name}: expected a run of at most {MAX_RUN_CONTAINERS} lists and objects, found more"
    )


def _containers(data: bytes) -> int:
    """The lists and objects of JSON text, counted by their brackets (those inside strings count
    too: the bound is only ever reached by files no recorder writes)."""
    return data.count(b"[") + data.count(b"{")


def _check_structure(data: bytes, name: str) -> None:
    """Refuses JSON with more lists and objects, or more values, than a run may hold, counting
    brackets and commas before anything is parsed."""
    containers = _containers(data)
    if containers > MAX_RUN_CONTAINERS:
        raise _too_many_containers(name)
    values = data.count(b",") + containers
    if values > MAX_RUN_VALUES:
        raise RunFormatError(
            f"{name}: expected a run of at most {MAX_RUN_VALUES} values, found about {values}"
        )


#: Bytes decompressed at a time: a file of too many lists is refused after the first pieces,
#: before the whole text is held.
_PIECE = 16 * 1024 * 1024


def _decompressed(data: bytes, largest: int, too_large: RunFormatError, name: str) -> bytes:
    """The gzip stream ``data`` decompressed, refused with ``too_large`` past ``largest`` bytes
    (a small file may expand a thousandfold), or as soon as it holds more lists and objects than
    a run may."""
    stream = zlib.decompressobj(wbits=16 + zlib.MAX_WBITS)
    pieces: list[bytes] = []
    size = containers = 0
    pending = data
    while not stream.eof:
        piece = stream.decompress(pending, _PIECE)
        pending = stream.unconsumed_tail
        if not piece and not pending:
            break
        size += len(piece)
        containers += _containers(piece)
        if size > largest:
            raise too_large
        if containers > MAX_RUN_CONTAINERS:
            raise _too_many_containers(name)
        pieces.append(piece)
    if not stream.eof:
        raise EOFError("the compressed file ends before its end")
    if stream.unused_data:  # a run is one gzip stream: what follows it is a damaged file
        raise zlib.error(
            f"{len(stream.unused_data)} bytes after the end of the compressed run, where a "
            "run file ends; the file was damaged or written into by something else"
        )
    return b"".join(pieces)


def run_from_json(values: Any, source: str = "<run>") -> RecordedRun:
    """A run from the JSON object of a run file; ``source`` names it in errors.

    Raises:
        RunFormatError: Not a run, a newer version, or a field missing or malformed.
    """
    if not isinstance(values, dict) or values.get("format") != FORMAT_NAME:
        found = values.get("format") if isinstance(values, dict) else type(values).__name__
        raise RunFormatError(
            f"{source}: expected format {_shown(FORMAT_NAME)}, found {_shown(found)}"
        )
    version = str(values.get("version", ""))
    major_text, _, minor_text = version.partition(".")
    if not all(p.isdecimal() and len(p) <= 6 for p in (major_text, minor_text or "0")):
        raise RunFormatError(f"{source}: expected a version such as '1.0', found {_shown(version)}")
    found = (int(major_text), int(minor_text or "0"))
    if found[0] != FORMAT_VERSION[0] or found > FORMAT_VERSION:
        newer = found > FORMAT_VERSION
        raise RunFormatError(
            f"{source}: this mazesim reads run format {FORMAT_VERSION[0]}.0 to "
            f"{FORMAT_VERSION[0]}.{FORMAT_VERSION[1]}; the file is version {version} "
            f"({'a newer' if newer else 'an older'} format): "
            + (
                f"upgrade mazesim to one that reads run format {version}"
                if newer
                else "record it again"
            )
        )
    fields = RunFields(source)
    world = fields.get(values, "world", "world")
    toml = fields.text(fields.get(world, "toml", "world.toml"), "world.toml")
    robot, own_profile = _profile_from_json(fields, values, "robot", "robot_profile", "robot")
    subtask_names = fields.texts(
        fields.get(values, "subtask_names", "subtask_names", []), "subtask_names"
    )
    scale = fields.number(
        fields.get(values, "reading_scale", "reading_scale", 1.0), "reading_scale", 0.0, 1e9
    )
    run = RecordedRun(
        world=World.from_toml(toml, f"{source}: world"),
        robot=robot,
        controller=fields.text(fields.get(values, "controller", "controller"), "controller"),
        seed=fields.whole(fields.get(values, "seed", "seed"), "seed", 0, 2**64 - 1),
        control_step_ms=fields.number(
            fields.get(values, "control_step_ms", "control_step_ms"), "control_step_ms", 0.0, 1e6
        ),
        subtask_names=subtask_names,
        reading_scale=scale,
        own_profile=own_profile,
    )
    run.robots = _robots_from_json(fields, fields.get(values, "robots", "robots", []), robot)
    episodes = fields.get(values, "episodes", "episodes")
    if not isinstance(episodes, list):
        raise fields.fail("episodes", "a list of episodes", episodes)
    run.episodes = [
        _episode_from_json(fields, episode, f"episodes[{index}]", scale, len(subtask_names))
        for index, episode in enumerate(episodes)
    ]
    for index, episode in enumerate(run.episodes):
        if run.robots and len(episode.robots) != len(run.robots) - 1:
            raise fields.fail(
                f"episodes[{index}].robots",
                f"the tracks of the run's {len(run.robots) - 1} other robots",
                episodes[index].get("robots"),
            )
        for number, member in enumerate(run.robots):
            last = member.from_frame if member.until_frame is None else member.until_frame
            if last >= episode.frames:
                raise fields.fail(
                    f"robots[{number}]",
                    f"a robot present within the {episode.frames} frames of episodes[{index}]",
                    {"from_frame": member.from_frame, "until_frame": member.until_frame},
                )
    return run


def _profile_from_json(
    fields: RunFields, values: Any, name_key: str, toml_key: str, where: str
) -> tuple[str, RobotProfile | None]:
    """A run's robot profile: its name and, when the run holds it (version 1.3), the profile
    itself read from its TOML text; a name alone must be a built-in profile's."""
    toml_field = f"{where.rpartition('.')[0]}.{toml_key}".lstrip(".")
    text = fields.get(values, toml_key, toml_field, None)
    if text is None:
        return fields.text(fields.get(values, name_key, where), where, robot_profile_names()), None
    name = fields.text(fields.get(values, name_key, where), where)
    try:
        profile = RobotProfile.from_toml(
            fields.text(text, toml_field), f"{fields.source}: {toml_field}"
        )
    except MazesimError as refusal:
        raise RunFormatError(str(refusal)) from None
    return name, profile


def _robots_from_json(fields: RunFields, values: Any, robot: str) -> list[RunRobot]:
    """The run's ``robots`` (none, or 2 to :data:`MAX_RUN_ROBOTS`, the first of profile
    ``robot``)."""
    if not isinstance(values, list) or len(values) == 1 or len(values) > MAX_RUN_ROBOTS:
        raise fields.fail("robots", f"a list of 2 to {MAX_RUN_ROBOTS} robots (or none)", values)
    robots = []
    for index, entry in enumerate(values):
        where = f"robots[{index}]"
        profile, own_profile = _profile_from_json(
            fields, entry, "profile", "profile_toml", f"{where}.profile"
        )
        robots.append(
            RunRobot(
                name=fields.text(fields.get(entry, "name", f"{where}.name"), f"{where}.name"),
                profile=profile,
                own_profile=own_profile,
                from_frame=fields.whole(
                    fields.get(entry, "from_frame", f"{where}.from_frame", 0),
                    f"{where}.from_frame",
                    0,
                    2**40,
                ),
            )
        )
        until = fields.get(entry, "until_frame", f"{where}.until_frame", None)
        if until is not None:
            low = robots[-1].from_frame
            robots[-1].until_frame = fields.whole(until, f"{where}.until_frame", low, 2**40)
    if robots and robots[0].profile != robot:
        raise fields.fail(
            "robots[0].profile", f"the run's robot {_shown(robot)}", robots[0].profile
        )
    return robots


def _episode_from_json(
    fields: RunFields, values: Any, where: str, reading_scale: float, subtasks: int
) -> RecordedEpisode:
    """One episode; ``where`` names it in errors, ``subtasks`` is the number of sub-task names."""

    def get(key: str, *default: Any) -> Any:
        return fields.get(values, key, f"{where}.{key}", *default)

    frames = fields.whole(get("frames"), f"{where}.frames", 1, 2**40)
    poses = np.column_stack(
        [
            fields.table(get("x"), f"{where}.x", frames, bound=POSITION_BOUND) * POSITION_UNIT,
            fields.table(get("y"), f"{where}.y", frames, bound=POSITION_BOUND) * POSITION_UNIT,
            fields.table(get("yaw"), f"{where}.yaw", frames, bound=YAW_BOUND) * YAW_UNIT,
        ]
    )
    colliding = np.zeros(frames, dtype=bool)
    colliding[fields.indices(get("contacts"), f"{where}.contacts", frames)] = True
    events = np.zeros(frames, dtype=np.int64)
    crossings = get("events")
    if not isinstance(crossings, list):
        raise fields.fail(f"{where}.events", "a list of [frame, event] pairs", crossings)
    for index, pair in enumerate(crossings):
        field = f"{where}.events[{index}]"
        if not isinstance(pair, list) or len(pair) != 2:
            raise fields.fail(field, "a pair [frame, event]", pair)
        frame = fields.whole(pair[0], f"{field}[0]", 0, frames - 1)
        event = fields.whole(pair[1], f"{field}[1]", -65535, 65535)
        if event == 0:
            raise fields.fail(f"{field}[1]", "a checkpoint id, + or - (not 0)", event)
        events[frame] = event
    decisions = get("decisions", [])
    if not isinstance(decisions, list):
        raise fields.fail(f"{where}.decisions", "a list of decisions", decisions)
    episode = RecordedEpisode(
        number=fields.whole(get("number"), f"{where}.number", 0, 2**63 - 1),
        poses=poses,
        readings=fields.table(get("readings"), f"{where}.readings", frames, -1) / reading_scale,
        rays=fields.table(get("rays"), f"{where}.rays", frames, -1) * RAY_UNIT,
        colliding=colliding,
        events=events,
        outcome=fields.text(get("outcome", ""), f"{where}.outcome"),
        decisions=[
            _decision_from_json(fields, decision, f"{where}.decisions[{index}]", frames, subtasks)
            for index, decision in enumerate(decisions)
        ],
    )
    if "actions" in values:
        episode.actions = fields.texts(values["actions"], f"{where}.actions", frames)
    if "wheel_speeds" in values:
        speeds = fields.table(values["wheel_speeds"], f"{where}.wheel_speeds", frames, 2)
        episode.wheel_speeds = speeds * WHEEL_SPEED_UNIT
    if "subtasks" in values:
        letters = fields.text(values["subtasks"], f"{where}.subtasks")
        allowed = "-" + "0123456789"[: subtasks if subtasks else 10]
        if len(letters) != frames or letters.strip(allowed):
            raise fields.fail(
                f"{where}.subtasks",
                f"{frames} characters, each '-' or a sub-task index below {subtasks or 10}",
                letters,
            )
        episode.subtasks = np.array(
            [-1 if letter == "-" else int(letter) for letter in letters], dtype=np.int64
        )
    if "levels" in values:
        rows = fields.texts(values["levels"], f"{where}.levels", frames)
        if any(len(row) != NUM_LEVELS or row.strip("0123") for row in rows):
            raise fields.fail(
                f"{where}.levels", f"{frames} strings of {NUM_LEVELS} digits 0-3", values["levels"]
            )
        episode.levels = np.array([[int(v) for v in row] for row in rows], dtype=np.int64)
    if "robots" in values:
        tracks = values["robots"]
        if not isinstance(tracks, list) or len(tracks) > MAX_RUN_ROBOTS - 1:
            raise fields.fail(f"{where}.robots", "a list of the other robots' tracks", tracks)
        for index, track in enumerate(tracks):
            other = _episode_from_json(
                fields, track, f"{where}.robots[{index}]", reading_scale, subtasks
            )
            if other.frames != frames or other.robots or other.walls:
                raise fields.fail(f"{where}.robots[{index}]", f"a track of {frames} frames", track)
            episode.robots.append(other)
    if "walls" in values:
        episode.walls = _walls_from_json(fields, values["walls"], f"{where}.walls", frames)
    return episode


def _walls_from_json(
    fields: RunFields, values: Any, where: str, frames: int
) -> list[tuple[int, npt.NDArray[np.float64]]]:
    """An episode's ``walls``: [frame, boxes] pairs, frames rising within the episode's."""
    if not isinstance(values, list) or len(values) > MAX_WALL_CHANGES:
        raise fields.fail(
            where, f"a list of at most {MAX_WALL_CHANGES} [frame, wall boxes] pairs", values
        )
    changes: list[tuple[int, npt.NDArray[np.float64]]] = []
    for index, pair in enumerate(values):
        field = f"{where}[{index}]"
        if not isinstance(pair, list) or len(pair) != 2:
            raise fields.fail(field, "a pair [frame, wall boxes]", pair)
        low = changes[-1][0] + 1 if changes else 0
        frame = fields.whole(pair[0], f"{field}[0]", low, frames - 1)
        boxes = pair[1]
        expected = (
            f"a list of at most {MAX_WALL_BOXES} wall boxes, each [x, y, size x, size y, yaw] "
            "in whole 0.1 mm and milliradians, sizes not negative"
        )
        if not isinstance(boxes, list) or len(boxes) > MAX_WALL_BOXES:
            raise fields.fail(f"{field}[1]", expected, boxes)
        table = fields.table(boxes, f"{field}[1]", len(boxes), WALL_BOX_NUMBERS, POSITION_BOUND)
        if np.any(table[:, 2:4] < 0.0):
            raise fields.fail(f"{field}[1]", expected, boxes)
        units = np.array([POSITION_UNIT] * 4 + [YAW_UNIT])
        changes.append((frame, table * units))
    return changes


def _decision_from_json(
    fields: RunFields, values: Any, where: str, frames: int, subtasks: int
) -> Decision:
    """One decision, its frame within the episode's and its choice among ``subtasks``."""

    def get(key: str) -> Any:
        return fields.get(values, key, f"{where}.{key}")

    code = fields.text(get("code"), f"{where}.code")
    if code.strip("01"):
        raise fields.fail(f"{where}.code", "bars as a string of 0 and 1", code)
    q_values = get("q_values")
    greedy = get("greedy")
    if not isinstance(greedy, bool):
        raise fields.fail(f"{where}.greedy", "true or false", greedy)
    return Decision(
        number=fields.whole(get("number"), f"{where}.number", 0, 2**63 - 1),
        frame=fields.whole(get("frame"), f"{where}.frame", 0, frames - 1),
        checkpoint=fields.whole(get("checkpoint"), f"{where}.checkpoint", 1, 65535),
        arrival=fields.text(get("direction"), f"{where}.direction", ("arrival", "departure"))
        == "arrival",
        code=code,
        q_values=fields.table(
            q_values, f"{where}.q_values", len(q_values) if isinstance(q_values, list) else 0
        ).tolist(),
        chosen=fields.whole(
            get("chosen"), f"{where}.chosen", 0, subtasks - 1 if subtasks else 2**31
        ),
        greedy=greedy,
    )
