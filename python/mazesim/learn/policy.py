"""The navigator of the report's Alg. 5: both levels together, for N robots at once.

Each control step, for every robot (:meth:`HierarchicalPolicy.act`):

1. if a checkpoint was crossed (``checkpoint != 0``), the higher level chooses the sub-task
   (:mod:`mazesim.learn.higher`), which starts there;
2. the core's navigator (:class:`mazesim._core.Navigator`) does the rest: the sensor distances
   become levels and a state (Table 4.1), the running sub-task's odometry advances, a door
   sub-task that ended (or gave up) hands over to "Corridors and Corners", the chosen sub-task
   begins, and the running sub-task's table gives the action (greedy among the actions the
   sub-task may take, :data:`mazesim.learn.subtasks.SUBTASK_ACTIONS`; a turn on the spot kept
   rather than reversed in "Corridors and Corners"; with ``hold_heading``, its blind state holds
   the heading on the grid).

Alg. 5 runs "Corridors and Corners" on every step without a checkpoint; here a door sub-task the
higher level chose keeps running until its own end (its turn needs more than the one step on the
code), then "Corridors and Corners" takes over, as in the report.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._core import Navigator, RobotProfile
from mazesim._sizes import index_array, number_array, whole_array
from mazesim.actions import ACTION_CODES, WHEEL_SPEED_FRACTIONS
from mazesim.errors import InvalidArgumentError
from mazesim.learn.discretise import NUM_SENSORS, volts_to_cm
from mazesim.learn.higher import HigherLevel
from mazesim.learn.lower import lower_table_shape
from mazesim.learn.subtasks import CONTROL_STEP_MS
from mazesim.odometry import advance

__all__ = ["Chooser", "DeadReckoningNavigator", "HierarchicalPolicy", "StepRecord"]

#: Picks sub-tasks for robots at a checkpoint event: ``(envs, higher states) -> sub-tasks``.
Chooser = Callable[[npt.NDArray[np.int64], npt.NDArray[np.int64]], npt.NDArray[np.int64]]


class StepRecord:
    """What the navigator saw and did in its last step, for traces (arrays of N)."""

    def __init__(self, num_envs: int) -> None:
        self.levels = np.zeros((num_envs, NUM_SENSORS), dtype=np.int64)
        self.distances_cm = np.zeros((num_envs, NUM_SENSORS), dtype=np.float64)
        self.state = np.zeros(num_envs, dtype=np.int64)
        self.subtask = np.zeros(num_envs, dtype=np.int64)
        self.phase = np.zeros(num_envs, dtype=np.int64)
        self.action = np.zeros(num_envs, dtype=np.int64)
        self.event = np.zeros(num_envs, dtype=np.int64)
        self.chosen = np.full(num_envs, -1, dtype=np.int64)
        self.ended = np.zeros(num_envs, dtype=bool)

    def decisions(self) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]:
        """The robots the higher level chose a sub-task for in this step, and those sub-tasks."""
        robots = np.flatnonzero(self.chosen >= 0)
        return robots, self.chosen[robots]


class HierarchicalPolicy:
    """Alg. 5 for N robots: lower-level tables, a higher level, and a sub-task per robot.

    Args:
        lower_q: The stacked lower-level tables, shape :func:`lower_table_shape` (with or
            without ``door_distance``: the sub-tasks' phases follow the shape).
        higher: The higher level (its tables for the robots' worlds).
        world_of_env: (N,) each robot's world in ``higher``.
        chooser: Picks sub-tasks at events; by default the higher level's greedy choice.
        hold_heading: "Corridors and Corners" holds its heading on the grid where no sensor sees
            a wall, as a navigator trained with ``--hold-heading`` does
            (:attr:`mazesim.learn.tables.TrainedPolicy.hold_heading`).
    """

    def __init__(
        self,
        lower_q: npt.NDArray[np.float64],
        higher: HigherLevel,
        world_of_env: npt.ArrayLike,
        chooser: Chooser | None = None,
        hold_heading: bool = False,
    ) -> None:
        door_distance = lower_q.ndim == 3 and lower_q.shape[1] == lower_table_shape(True)[1]
        if lower_q.shape != lower_table_shape(door_distance):
            raise InvalidArgumentError(
                f"expected lower-level tables of shape {lower_table_shape()} (or "
                f"{lower_table_shape(True)}, with door_distance), found {lower_q.shape}"
            )
        self.lower_q = lower_q
        #: Whether the door sub-tasks' phases count the distance (the tables' shape says).
        self.door_distance = door_distance
        self.higher = higher
        worlds = len(higher.checkpoint_ids)
        self.world_of_env = index_array(world_of_env, "world_of_env", worlds).ravel()
        self.num_envs = self.world_of_env.size
        self.chooser = chooser
        self.hold_heading = hold_heading
        self.navigator = Navigator(
            np.ascontiguousarray(number_array(lower_q, "lower_q")), self.num_envs, hold_heading
        )
        self.record = StepRecord(self.num_envs)

    def reset(self, envs: npt.ArrayLike, poses: npt.ArrayLike) -> None:
        """Starts robots ``envs`` afresh, in "Corridors and Corners", at their poses."""
        robots = np.ascontiguousarray(index_array(envs, "envs", self.num_envs).ravel())
        self.navigator.reset(robots, np.ascontiguousarray(number_array(poses, "poses")))

    def subtask_arrays(self) -> dict[str, npt.NDArray[Any]]:
        """Each robot's running sub-task as :meth:`mazesim.BatchSimulator.run` takes them
        (``subtasks``); hand them back with :meth:`set_subtask_arrays` after the run."""
        return self.navigator.subtask_arrays()

    def set_subtask_arrays(self, arrays: dict[str, npt.NDArray[Any]]) -> None:
        """Sets each robot's running sub-task from :meth:`subtask_arrays` after a run."""
        self.navigator.set_subtask_arrays(arrays)

    def act(
        self,
        observations: npt.ArrayLike,
        poses: npt.ArrayLike,
        events: npt.ArrayLike,
    ) -> npt.NDArray[np.int64]:
        """One step of Alg. 5 for every robot.

        Args:
            observations: (N, W) batch observations (Sharp volts first).
            poses: (N, 3) poses, the odometry of the sub-tasks.
            events: (N,) checkpoint events of the last step (+id, -id, 0).

        Returns:
            (N,) action indices.
        """
        rows = np.asarray(observations)
        return self.act_on_distances(volts_to_cm(rows[:, :NUM_SENSORS]), poses, events)

    def act_on_distances(
        self,
        distances_cm: npt.ArrayLike,
        poses: npt.ArrayLike,
        events: npt.ArrayLike,
    ) -> npt.NDArray[np.int64]:
        """:meth:`act` from the six distances in cm of each robot, ``(N, 6)``."""
        pose_rows = np.ascontiguousarray(number_array(poses, "poses"))
        event = whole_array(events, "events")
        record = self.record
        record.distances_cm = np.ascontiguousarray(
            number_array(distances_cm, "distances_cm", inf_means="nothing in range")
        ).reshape(-1, NUM_SENSORS)
        record.event = event
        record.chosen[:] = -1
        at_event = np.flatnonzero(event != 0)
        if at_event.size:
            states = self.higher.states(self.world_of_env[at_event], event[at_event])
            known = states >= 0
            robots, states = at_event[known], states[known]
            if robots.size:
                if self.chooser is None:
                    chosen = self.higher.choose(states)
                else:
                    chosen = self.chooser(robots, states)
                record.chosen[robots] = chosen
        step = self.navigator.decide(record.distances_cm, pose_rows, record.chosen.copy())
        record.levels = step["levels"]
        record.state = step["state"]
        record.subtask = step["subtask"]
        record.phase = step["phase"]
        record.ended = step["ended"]
        record.action = step["action"]
        return record.action


class DeadReckoningNavigator:
    """Alg. 5 for one robot that reports only its distances and checkpoints (as over ROS).

    The sub-tasks' odometry is dead-reckoned from the wheel speeds of the actions this navigator
    chose, each held for one control step of ``control_step_ms`` (set it to the step of the
    simulator or robot that runs the actions).

    Args:
        lower_q: The stacked lower-level tables.
        higher: The higher level (one world).
        control_step_ms: How long each action runs.
        hold_heading: Hold the heading where blind (the core's ``navigator::heading_hold``), on the
            grid of the dead-reckoned frame, whose heading 0 is the episode's start.
    """

    def __init__(
        self,
        lower_q: npt.NDArray[np.float64],
        higher: HigherLevel,
        control_step_ms: float = CONTROL_STEP_MS,
        hold_heading: bool = False,
    ) -> None:
        robot = RobotProfile.builtin("seed")
        self.policy = HierarchicalPolicy(
            lower_q, higher, np.zeros(1, dtype=np.int64), hold_heading=hold_heading
        )
        self.step_seconds = control_step_ms / 1000.0
        self.speeds = WHEEL_SPEED_FRACTIONS * robot.max_wheel_speed
        self.wheel_radius = robot.wheel_radius
        self.axle_length = robot.axle_length
        self.pose = np.zeros((1, 3), dtype=np.float64)
        self.policy.reset([0], self.pose)

    def reset(self) -> None:
        """Starts a new episode."""
        self.pose[:] = 0.0
        self.policy.reset([0], self.pose)

    def act(self, distances_cm: npt.ArrayLike, checkpoint: int) -> str:
        """The action code for six distances in cm (front, back, left, right, left-front,
        right-front) and the checkpoint event of the last step (+id, -id or 0)."""
        distances = number_array(
            distances_cm, "distances_cm", inf_means="nothing in range"
        ).reshape(1, NUM_SENSORS)
        action = int(
            self.policy.act_on_distances(distances, self.pose, np.array([int(checkpoint)]))[0]
        )
        left, right = self.speeds[action] * (self.wheel_radius * self.step_seconds)
        advance(self.pose, [left], [right], self.axle_length)
        return ACTION_CODES[action]
