"""Recording runs frame by frame: one episode (:class:`EpisodeRecorder`) or one simulator.

An :class:`EpisodeRecorder` collects the frames of one episode (pose, readings, contact,
checkpoint event, and the ray lengths it works out from the pose) and what the controller did
from each; :class:`FleetRecorder` does this for every robot of a :class:`mazesim.Simulator`
stepped by a command (``mazesim demo``, ``mazesim webots run``), one track each (a run of one
robot when the world holds one), and returns the :class:`RecordedRun`. The recorder of the
hierarchical navigator is :mod:`mazesim.replay.navigator`. A run whose walls a Webots supervisor
changes is told of each change (``follow``): the run holds the walls from that frame on, and the
rays recorded from then meet them.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from mazesim._core import RobotProfile, Simulator, World
from mazesim._sizes import index_array, number_array
from mazesim.learn import qlearning
from mazesim.learn.discretise import NUM_LEVELS, NUM_SENSORS, distances_and_levels
from mazesim.replay.run import Decision, RecordedEpisode, RecordedRun, RunRobot
from mazesim.sensor_rays import SensorRays

if TYPE_CHECKING:
    from mazesim.learn.higher import HigherLevel

__all__ = [
    "EpisodeRecorder",
    "FleetRecorder",
    "reading_scale",
    "table_levels",
]


def reading_scale(robot: RobotProfile) -> float:
    """How finely a robot's readings are stored: millivolts for volts, whole raw values else."""
    return 1000.0 if robot.distance_sensor_unit == "volts" else 1.0


def table_levels(
    robot: RobotProfile, readings: npt.NDArray[np.float64]
) -> npt.NDArray[np.int64] | None:
    """Table 4.1 levels of the frames' readings for a robot with the report's six Sharp sensors
    (volts), else None."""
    if robot.distance_sensor_unit != "volts" or len(robot.distance_sensor_names) != NUM_SENSORS:
        return None
    return distances_and_levels(readings[:, :NUM_SENSORS])[1]


class EpisodeRecorder:
    """The frames of one episode, as they come.

    Args:
        world: The world (its walls stop the sensor rays).
        robot: The robot profile.
        number: The episode's number.
    """

    def __init__(self, world: World, robot: RobotProfile, number: int = 0) -> None:
        self.world = world
        self.robot = robot
        self.number = number
        self.codes = {int(c["id"]): str(c["code"]) for c in world.checkpoints()}  # type: ignore[call-overload]
        self.rays = SensorRays(world, robot, robot.distance_sensor_range)
        self.poses: list[tuple[float, float, float]] = []
        self.readings: list[npt.NDArray[np.float64]] = []
        self.ray_lengths: list[npt.NDArray[np.float64]] = []
        self.colliding: list[bool] = []
        self.events: list[int] = []
        self.actions: list[str] = []
        self.wheel_speeds: list[tuple[float, float]] = []
        self.subtasks: list[int] = []
        self.levels: list[npt.NDArray[np.int64]] = []
        self.decisions: list[Decision] = []
        #: Each change of the walls: the frame from which they stand so, and their boxes.
        self.walls: list[tuple[int, npt.NDArray[np.float64]]] = []
        self.finished = False

    def meet_walls(self, boxes: npt.ArrayLike) -> None:
        """The rays of the frames added from now on meet the wall boxes ``boxes`` (N, 5 or
        more: centre x, y, size x, y, yaw)."""
        self.rays = SensorRays(self.world, self.robot, self.robot.distance_sensor_range, boxes)

    def walls_changed(self, boxes: npt.ArrayLike) -> None:
        """The walls stand as ``boxes`` from the next frame on (a supervisor changed them);
        nothing changes when they stand as before (a change of the world's robots alone)."""
        array = number_array(boxes, "boxes")
        array = array.reshape(-1, array.shape[-1] if array.ndim == 2 else 5)[:, :5].copy()
        standing = self.walls[-1][1] if self.walls else self.world.wall_boxes()[:, :5]
        if array.shape == standing.shape and np.array_equal(array, standing):
            return
        if self.walls and self.walls[-1][0] == self.frames:
            self.walls.pop()
        self.walls.append((self.frames, array))
        self.meet_walls(array)

    @property
    def frames(self) -> int:
        """Frames recorded so far."""
        return len(self.poses)

    def add_frame(
        self,
        pose: Sequence[float],
        readings: npt.ArrayLike,
        colliding: bool = False,
        event: int = 0,
    ) -> None:
        """Adds the next frame: the pose, the readings (distance then ground sensors), whether
        the robot touches a wall, and the checkpoint event of the step that led here."""
        x, y, yaw = (float(v) for v in pose)
        self.poses.append((x, y, yaw))
        self.readings.append(
            number_array(
                readings, "readings", nan_means="no reading yet", inf_means="a reading out of range"
            ).ravel()
        )
        self.ray_lengths.append(self.rays.lengths((x, y, yaw)))
        self.colliding.append(bool(colliding))
        self.events.append(int(event))

    def set_action(
        self,
        code: str | None = None,
        wheel_speeds: tuple[float, float] | None = None,
        subtask: int | None = None,
        levels: npt.ArrayLike | None = None,
    ) -> None:
        """Records what the controller did from the last frame."""
        frame = self.frames - 1
        if code is not None:
            _pad(self.actions, frame, "")
            self.actions.append(code)
        if wheel_speeds is not None:
            _pad(self.wheel_speeds, frame, (0.0, 0.0))
            self.wheel_speeds.append((float(wheel_speeds[0]), float(wheel_speeds[1])))
        if subtask is not None:
            _pad(self.subtasks, frame, -1)
            self.subtasks.append(int(subtask))
        if levels is not None:
            _pad(self.levels, frame, np.zeros(NUM_SENSORS, dtype=np.int64))
            self.levels.append(index_array(levels, "levels", NUM_LEVELS).ravel())

    def add_decision(
        self, checkpoint_event: int, code: str, q_values: Sequence[float], chosen: int, greedy: bool
    ) -> Decision:
        """Records a higher-level choice made on the last frame's readings."""
        decision = Decision(
            number=len(self.decisions) + 1,
            frame=self.frames - 1,
            checkpoint=abs(int(checkpoint_event)),
            arrival=checkpoint_event > 0,
            code=code,
            q_values=[float(value) for value in q_values],
            chosen=int(chosen),
            greedy=bool(greedy),
        )
        self.decisions.append(decision)
        return decision

    def add_choice(self, higher: HigherLevel, world: int, event: int, chosen: int) -> Decision:
        """Records the choice ``chosen`` of a higher level at a checkpoint event of the last
        frame: the bars as read (backwards on a departure), the values of the sub-tasks in that
        state, and whether the choice was the highest-valued one.

        Args:
            higher: The higher level that chose.
            world: The robot's world in ``higher``.
            event: The checkpoint event (+id arrival, -id departure).
            chosen: The sub-task chosen.
        """
        state = int(higher.states(np.array([world]), np.array([event]))[0])
        table = higher.flat_q()
        best = int(qlearning.greedy(table, np.array([state]))[0])
        bars = self.codes.get(abs(event), "")
        return self.add_decision(
            event, bars if event > 0 else bars[::-1], table[state].tolist(), chosen, chosen == best
        )

    def episode(self, outcome: str = "") -> RecordedEpisode:
        """The recorded episode."""
        frames = self.frames
        readings = np.array(self.readings, dtype=np.float64).reshape(frames, -1)
        episode = RecordedEpisode(
            number=self.number,
            poses=np.array(self.poses, dtype=np.float64).reshape(frames, 3),
            readings=readings,
            rays=np.array(self.ray_lengths, dtype=np.float64).reshape(frames, -1),
            colliding=np.array(self.colliding, dtype=bool),
            events=np.array(self.events, dtype=np.int64),
            decisions=list(self.decisions),
            outcome=outcome,
            walls=list(self.walls),
        )
        if self.actions:
            episode.actions = _padded(self.actions, frames, "")
        if self.wheel_speeds:
            episode.wheel_speeds = np.array(_padded(self.wheel_speeds, frames, (0.0, 0.0)))
        if self.subtasks:
            episode.subtasks = np.array(_padded(self.subtasks, frames, -1), dtype=np.int64)
        if self.levels:
            zero = np.zeros(NUM_SENSORS, dtype=np.int64)
            episode.levels = np.array(_padded(self.levels, frames, zero), dtype=np.int64)
        else:
            episode.levels = table_levels(self.robot, readings)
        return episode


def _pad(values: list[Any], length: int, filler: object) -> None:
    """Appends ``filler`` to ``values`` until it is ``length`` long."""
    values.extend([filler] * (length - len(values)))


def _padded(values: list[Any], length: int, filler: object) -> list[Any]:
    """``values`` cut or padded with ``filler`` to ``length``."""
    return [*values[:length], *([filler] * max(0, length - len(values)))]


class FleetRecorder:
    """Records every robot of a world, one :class:`EpisodeRecorder` each.

    Call :meth:`capture` (or :meth:`capture_simulator` for one simulator of every robot) at the
    start and after every step, and :meth:`acted` with each robot's wheel speeds.

    Args:
        world: The world (its walls stop the sensor rays).
        robots: Each robot's name and profile, in the world's order.
        controller: What drives the robots.
        seed: The run's seed.
        control_step_ms: The time between frames.
    """

    def __init__(
        self,
        world: World,
        robots: Sequence[tuple[str, RobotProfile]],
        controller: str,
        seed: int,
        control_step_ms: float,
    ) -> None:
        self.world = world
        self.robots = list(robots)
        self.controller = controller
        self.seed = seed
        self.control_step_ms = float(control_step_ms)
        self.recorders = [EpisodeRecorder(world, profile) for _, profile in self.robots]
        #: Each robot's first frame in the world and its last (None: to the end).
        self.presence: list[tuple[int, int | None]] = [(0, None)] * len(self.robots)
        #: The world whose walls the frames meet now (:meth:`follow`).
        self._followed = world

    def follow(self, world: World) -> None:
        """Records the walls of ``world`` from the next frame on, when it is not the world
        followed (a supervisor moved, imported or removed walls): every robot's rays meet
        them from then on."""
        if world is not self._followed:
            self._followed = world
            boxes = world.wall_boxes()
            for recorder in self.recorders:
                recorder.walls_changed(boxes)

    @staticmethod
    def of_simulator(simulator: Simulator, controller: str, seed: int) -> FleetRecorder:
        """A recorder of every robot of one simulator."""
        robots = [
            (name, simulator.robot_profile(index))
            for index, name in enumerate(simulator.robot_names)
        ]
        return FleetRecorder(
            simulator.world, robots, controller, seed, float(simulator.control_step_ms)
        )

    def capture(
        self,
        index: int,
        pose: Sequence[float],
        readings: npt.ArrayLike,
        colliding: bool = False,
        event: int = 0,
    ) -> None:
        """Adds robot ``index``'s next frame (see :meth:`EpisodeRecorder.add_frame`)."""
        self.recorders[index].add_frame(pose, readings, colliding, event)

    def capture_simulator(self, simulator: Simulator) -> None:
        """Adds a frame of every robot of ``simulator`` as it is now."""
        for index, recorder in enumerate(self.recorders):
            state = simulator.robot_state(index)
            readings = np.concatenate(
                (
                    simulator.distance_sensors(robot_index=index),
                    simulator.ground_sensors(robot_index=index),
                )
            )
            event = int(state["last_crossing"]) if recorder.frames else 0
            recorder.add_frame(state["pose"], readings, bool(state["colliding"]), event)

    def join(
        self, name: str, profile: RobotProfile, pose: Sequence[float], readings: npt.ArrayLike
    ) -> None:
        """Adds a robot that joins the world now (a Webots supervisor imported it), before the
        frame of this moment is captured: it stands at ``pose`` reading ``readings`` in every
        frame before, as a run's robots share one frame per step, and is in the world from
        this frame on."""
        recorder = EpisodeRecorder(self.world, profile)
        if self._followed is not self.world:
            recorder.meet_walls(self._followed.wall_boxes())
        for _ in range(self.recorders[0].frames):
            recorder.add_frame(pose, readings, False)
            recorder.set_action(wheel_speeds=(0.0, 0.0))
        self.robots.append((name, profile))
        self.recorders.append(recorder)
        self.presence.append((recorder.frames, None))

    def leave(self, index: int) -> None:
        """Notes that robot ``index`` left the world now (a Webots supervisor removed it),
        before the frame of this moment is captured: that frame, its last, holds where it
        was, and it stands still there in the later ones, out of the world."""
        first, last = self.presence[index]
        if last is None:
            self.presence[index] = (first, max(first, self.recorders[index].frames))

    def acted(self, index: int, left: float, right: float) -> None:
        """Records the wheel speeds robot ``index`` set from its last frame."""
        self.recorders[index].set_action(wheel_speeds=(left, right))

    def run(self, outcome: str = "") -> RecordedRun:
        """The recorded run: robot 0's track as the episode, the others' in its ``robots``
        (a run of one robot when the world holds one). Each robot's rays stop at the other
        robots' bodies as well as at the walls."""
        if len(self.recorders) > 1:
            self._cut_rays_at_robots()
        episode = self.recorders[0].episode(outcome)
        # The walls' changes are the run's, held by robot 0's episode alone.
        episode.robots = [
            replace(recorder.episode(outcome), walls=[]) for recorder in self.recorders[1:]
        ]
        profile = self.robots[0][1]
        return RecordedRun(
            world=self.world,
            robot=profile.name,
            controller=self.controller,
            seed=self.seed,
            control_step_ms=self.control_step_ms,
            episodes=[episode],
            reading_scale=max(reading_scale(robot) for _, robot in self.robots),
            own_profile=profile,
            robots=(
                [
                    RunRobot(name, robot.name, first, last, own_profile=robot)
                    for (name, robot), (first, last) in zip(self.robots, self.presence)
                ]
                if len(self.robots) > 1
                else []
            ),
        )

    def _cut_rays_at_robots(self) -> None:
        """Shortens every recorded ray to where it first meets another robot's body (a disc of
        its radius), frame by frame."""
        frames = min(recorder.frames for recorder in self.recorders)
        poses = [np.array(recorder.poses[:frames]) for recorder in self.recorders]
        for index, recorder in enumerate(self.recorders):
            lengths = np.array(recorder.ray_lengths[:frames], dtype=np.float64)
            origins = [recorder.rays.origins(tuple(pose)) for pose in poses[index]]
            origin_x = np.array([origin[0] for origin in origins]).reshape(lengths.shape)
            origin_y = np.array([origin[1] for origin in origins]).reshape(lengths.shape)
            angles = np.array([origin[2] for origin in origins]).reshape(lengths.shape)
            cos_ray, sin_ray = np.cos(angles), np.sin(angles)
            for other, (_, profile) in enumerate(self.robots):
                if other == index:
                    continue
                first, last = self.presence[other]
                there = np.zeros((frames, 1), dtype=bool)
                there[first : frames if last is None else last + 1] = True
                rel_x = origin_x - poses[other][:, :1]
                rel_y = origin_y - poses[other][:, 1:2]
                along = rel_x * cos_ray + rel_y * sin_ray
                apart = rel_x * rel_x + rel_y * rel_y - profile.body_radius**2
                room = along * along - apart
                entry = np.maximum(-along - np.sqrt(np.maximum(room, 0.0)), 0.0)
                meets = there & (room >= 0.0) & ((along <= 0.0) | (apart <= 0.0))
                lengths = np.where(meets & (entry < lengths), entry, lengths)
            recorder.ray_lengths[:frames] = list(lengths)
