"""The four lower-level sub-tasks of the report's section 4.1: their states, ends and rewards.

========  =========================  ======  ==================================================
number    name                       phases  what it does
========  =========================  ======  ==================================================
0 (CC)    Corridors and Corners      1       follows the corridor it is in, round its corners
1 (R)     Right turn on a door       2       drives to the next opening on its right and turns in
2 (L)     Left turn on a door        2       drives to the next opening on its left and turns in
3 (F)     Going forward on a door    1       drives straight through the door ahead
========  =========================  ======  ==================================================

**State.** A sub-task sees the distance state of :mod:`mazesim.hrl.discretise` (4096 values). The
two turns add a phase: 0 until the robot has turned 45 degrees towards its side since the
sub-task began, 1 after; their state is ``distance_state + 4096 * phase`` (8192 values). Without
it, the middle of a crossing looks the same before and after a right turn (open on all sides), and
a table could not tell "turn now" from "the turn is done, drive on".

**Odometry.** The ends use what the robot's wheel odometry knows: the heading change and the
displacement since the sub-task began. :class:`SubTaskTracker` takes them from the poses a
:class:`mazesim.BatchSimulator` reports, which stand in for noise-free wheel odometry (they differ
from it only when a wheel slips against a wall).

**Ends** (:meth:`SubTaskTracker.update`):

- Corridors and Corners never ends by itself; a checkpoint event or the goal ends it.
- Right / Left turn: done when the turn phase has begun, the heading is within 20 degrees of 90
  degrees to that side of the heading at the start, and the robot has driven
  :data:`TURN_EXIT_DISTANCE` (8 cm) towards the new heading since the phase began.
- Going forward: done when the robot is :data:`FORWARD_DISTANCE` (40 cm) ahead of where it began
  (through the door it was about to enter, just into the next cell) within 20 degrees of its
  heading.
- A door sub-task gives up after :data:`MAX_DOOR_STEPS` control steps or a heading change of more
  than 150 degrees; control then returns to Corridors and Corners.

A checkpoint event (a barcode crossed) ends whatever runs and asks the higher level again.

**Rewards** (training only; they may read the maze, the robot never does):

- Corridors and Corners: ``10 * (metres driven forward along the robot's heading)`` per step,
  ``-2`` per step in contact with a wall. Driving a corridor at cruise speed earns 0.02 a step.
- Door sub-tasks: ``10 * (metres of progress along the door's path)`` per step, where the path runs
  from the start to the door's centre, then 25 cm into the target opening (progress along each leg
  is clipped to the leg); ``-0.01`` a step; ``-2`` per step in contact; at the end ``+5`` when the
  robot has really entered the target opening (its centre at least 4 cm past the door's centre
  that way and within 8 cm of the opening's centre line) and ``-5`` when it has not or gave up.
"""

from __future__ import annotations

import math
from enum import IntEnum

import numpy as np
import numpy.typing as npt

from mazesim.hrl.discretise import NUM_STATES

__all__ = [
    "COLLISION_PENALTY",
    "FORWARD_DISTANCE",
    "HEADING_TOLERANCE",
    "MAX_DOOR_STEPS",
    "NUM_PHASES",
    "NUM_SUBTASKS",
    "PROGRESS_REWARD",
    "SUBTASK_CODES",
    "SUBTASK_NAMES",
    "TURN_EXIT_DISTANCE",
    "TURN_PHASE_ANGLE",
    "SubTask",
    "SubTaskTracker",
    "subtask_states",
]


class SubTask(IntEnum):
    """The lower-level sub-tasks, numbered as their tables are stored."""

    CORRIDOR = 0
    RIGHT = 1
    LEFT = 2
    FORWARD = 3


#: The report's names of the sub-tasks, by number.
SUBTASK_NAMES: tuple[str, ...] = (
    "Corridors and Corners",
    "Right turn on a door",
    "Left turn on a door",
    "Going forward on a door",
)
#: Short names for traces and tables.
SUBTASK_CODES: tuple[str, ...] = ("CC", "R", "L", "F")
NUM_SUBTASKS = len(SUBTASK_NAMES)
#: Phases per sub-task (the turns have two).
NUM_PHASES: tuple[int, ...] = (1, 2, 2, 1)
#: Turn of the heading (radians) after which a turn sub-task is in its second phase.
TURN_PHASE_ANGLE = math.radians(45.0)
#: Largest heading error (radians) at which a door sub-task may end.
HEADING_TOLERANCE = math.radians(20.0)
#: Metres driven towards the new heading after the turn phase began, to end a turn.
TURN_EXIT_DISTANCE = 0.08
#: Metres ahead of its start at which "Going forward on a door" ends.
FORWARD_DISTANCE = 0.40
#: Control steps after which a door sub-task gives up.
MAX_DOOR_STEPS = 170
#: Heading change (radians) after which a door sub-task gives up.
GIVE_UP_ANGLE = math.radians(150.0)
#: Reward per metre of progress.
PROGRESS_REWARD = 10.0
#: Reward of each control step spent in contact with a wall.
COLLISION_PENALTY = -2.0
#: Reward of each control step of a door sub-task.
DOOR_STEP_REWARD = -0.01
#: Reward at the end of a door sub-task that entered its opening, and of one that did not.
DOOR_SUCCESS_REWARD = 5.0
DOOR_FAILURE_REWARD = -5.0

#: The heading change each sub-task aims at (radians, counter-clockwise positive).
TARGET_TURN: tuple[float, ...] = (0.0, -math.pi / 2.0, math.pi / 2.0, 0.0)


def subtask_states(
    distance_states: npt.ArrayLike, phases: npt.ArrayLike
) -> npt.NDArray[np.int64]:
    """A sub-task's state: ``distance_state + 4096 * phase``."""
    return np.asarray(distance_states, dtype=np.int64) + NUM_STATES * np.asarray(
        phases, dtype=np.int64
    )


def _wrap(angle: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """Angles wrapped to (-pi, pi]."""
    return np.asarray(-((-angle + math.pi) % (2.0 * math.pi) - math.pi), dtype=np.float64)


class SubTaskTracker:
    """The running sub-task of N robots, with the odometry its phase and end read.

    Args:
        num_envs: Number of robots.
    """

    def __init__(self, num_envs: int) -> None:
        self.num_envs = num_envs
        self.subtask = np.zeros(num_envs, dtype=np.int64)
        self.start = np.zeros((num_envs, 3), dtype=np.float64)
        self.previous_yaw = np.zeros(num_envs, dtype=np.float64)
        self.heading_change = np.zeros(num_envs, dtype=np.float64)
        self.steps = np.zeros(num_envs, dtype=np.int64)
        self.phase = np.zeros(num_envs, dtype=np.int64)
        self.turn_point = np.zeros((num_envs, 2), dtype=np.float64)

    def begin(self, mask: npt.ArrayLike, subtasks: npt.ArrayLike, poses: npt.ArrayLike) -> None:
        """Starts sub-tasks for the robots in ``mask`` at their current poses.

        Args:
            mask: (N,) bool, the robots that begin a sub-task.
            subtasks: (N,) or scalar sub-task numbers (read where ``mask`` is true).
            poses: (N, 3) poses x, y, yaw.
        """
        flags = np.asarray(mask, dtype=bool)
        pose_rows = np.asarray(poses, dtype=np.float64)
        chosen = np.broadcast_to(np.asarray(subtasks, dtype=np.int64), flags.shape)
        self.subtask[flags] = chosen[flags]
        self.start[flags] = pose_rows[flags]
        self.previous_yaw[flags] = pose_rows[flags, 2]
        self.heading_change[flags] = 0.0
        self.steps[flags] = 0
        self.phase[flags] = 0
        self.turn_point[flags] = pose_rows[flags, :2]

    def update(self, poses: npt.ArrayLike) -> tuple[npt.NDArray[np.bool_], npt.NDArray[np.bool_]]:
        """Follows one control step of every robot.

        Args:
            poses: (N, 3) poses after the step.

        Returns:
            ``(done, gave_up)``: (N,) bool, the door sub-tasks that reached their end, and those
            that gave up. Corridors and Corners is never in either.
        """
        pose_rows = np.asarray(poses, dtype=np.float64)
        self.heading_change += _wrap(pose_rows[:, 2] - self.previous_yaw)
        self.previous_yaw = pose_rows[:, 2].copy()
        self.steps += 1
        turn = np.asarray(TARGET_TURN)[self.subtask]
        is_turn = turn != 0.0
        entering = is_turn & (self.phase == 0) & (self.heading_change * np.sign(turn) >= TURN_PHASE_ANGLE)
        self.phase[entering] = 1
        self.turn_point[entering] = pose_rows[entering, :2]

        target_heading = self.start[:, 2] + turn
        direction = np.stack([np.cos(target_heading), np.sin(target_heading)], axis=1)
        aligned = np.abs(self.heading_change - turn) <= HEADING_TOLERANCE
        turned_out = np.einsum("ij,ij->i", pose_rows[:, :2] - self.turn_point, direction)
        ahead = np.einsum("ij,ij->i", pose_rows[:, :2] - self.start[:, :2], direction)
        turn_done = is_turn & (self.phase == 1) & aligned & (turned_out >= TURN_EXIT_DISTANCE)
        forward_done = (self.subtask == SubTask.FORWARD) & aligned & (ahead >= FORWARD_DISTANCE)
        door = self.subtask != SubTask.CORRIDOR
        gave_up = door & (
            (self.steps >= MAX_DOOR_STEPS) | (np.abs(self.heading_change) > GIVE_UP_ANGLE)
        )
        done = (turn_done | forward_done) & ~gave_up
        return done, gave_up

    def states(self, distance_states: npt.ArrayLike) -> npt.NDArray[np.int64]:
        """Each robot's state in its running sub-task's table."""
        return subtask_states(distance_states, self.phase)
