"""A slow reference of the navigator's step, in numpy, for tests: what the core's navigator
(``mazesim_core::navigator``, ``mazesim._core.Navigator``) and its multi-step call compute, written
out array by array: the sub-tasks' phases and ends (:class:`SubTaskTracker`), the blind rule of
``--hold-heading`` (:func:`hold_actions`), the turn on the spot kept (:func:`hold_spins`) and the
left-right mirror image (:func:`mirrored_states`). Tests check the core against it bit for bit.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim.actions import ACTION_CODES, WHEEL_SPEED_FRACTIONS, action_index
from mazesim.learn.discretise import NUM_LEVELS, NUM_SENSORS, NUM_STATES, SENSOR_ORDER
from mazesim.learn.subtasks import (
    DISTANCE_EDGES,
    FORWARD_DISTANCE,
    FORWARD_PHASE_ANGLE,
    GIVE_UP_ANGLE,
    HEADING_TOLERANCE,
    MAX_DOOR_STEPS,
    MAX_PHASES,
    TARGET_TURN,
    TURN_EXIT_DISTANCE,
    TURN_PHASE_ANGLES,
    SubTask,
)
from mazesim.odometry import wrap_angle

_SPIN_RIGHT = ACTION_CODES.index("aa")
_SPIN_LEFT = ACTION_CODES.index("bb")


def hold_spins(
    actions: npt.NDArray[np.int64],
    previous: npt.NDArray[np.int64],
    where: npt.NDArray[np.bool_],
) -> npt.NDArray[np.int64]:
    """``actions`` with a turn on the spot kept where ``where`` is true: a robot that turned one
    way on the spot in its last step and would turn the other way now keeps turning as before."""
    reverses = where & (
        ((previous == _SPIN_RIGHT) & (actions == _SPIN_LEFT))
        | ((previous == _SPIN_LEFT) & (actions == _SPIN_RIGHT))
    )
    return np.where(reverses, previous, actions)


def heading_phases(subtasks: npt.ArrayLike, heading_change: npt.ArrayLike) -> npt.NDArray[np.int64]:
    """The phase of each robot from its sub-task and heading change (radians, CCW positive)."""
    kinds = np.asarray(subtasks, dtype=np.int64)
    change = np.asarray(heading_change, dtype=np.float64)
    turn = np.asarray(TARGET_TURN)[kinds]
    towards = change * np.sign(turn)
    turn_phase = np.searchsorted(np.asarray(TURN_PHASE_ANGLES), towards, side="right")
    forward_phase = (
        1
        + (change > FORWARD_PHASE_ANGLE).astype(np.int64)
        - (change < -FORWARD_PHASE_ANGLE).astype(np.int64)
    )
    phases = np.where(turn != 0.0, turn_phase, forward_phase)
    return np.where(kinds == SubTask.CORRIDOR, 0, phases).astype(np.int64)


def distance_bins(distances: npt.ArrayLike) -> npt.NDArray[np.int64]:
    """The distance bin (0 to 5, :data:`DISTANCE_EDGES`) of distances in metres ahead."""
    return np.searchsorted(
        np.asarray(DISTANCE_EDGES), np.asarray(distances, dtype=np.float64), side="right"
    ).astype(np.int64)


def subtask_states(distance_states: npt.ArrayLike, phases: npt.ArrayLike) -> npt.NDArray[np.int64]:
    """A sub-task's state: ``distance_state + 4096 * phase``."""
    return np.asarray(distance_states, dtype=np.int64) + NUM_STATES * np.asarray(
        phases, dtype=np.int64
    )


class SubTaskTracker:
    """The running sub-task of N robots, with the odometry its phase and end read.

    Args:
        num_envs: Number of robots.
        door_distance: Whether the door sub-tasks' phases also count the distance driven
            (:data:`DISTANCE_PHASES`).

    Attributes:
        phase: Each robot's phase: its heading phase, plus 3 times its distance bin with
            ``door_distance``.
    """

    def __init__(self, num_envs: int, door_distance: bool = False) -> None:
        self.num_envs = num_envs
        self.door_distance = door_distance
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
        self.phase[flags] = heading_phases(self.subtask[flags], 0.0)
        self.turn_point[flags] = pose_rows[flags, :2]

    def update(self, poses: npt.ArrayLike) -> tuple[npt.NDArray[np.bool_], npt.NDArray[np.bool_]]:
        """Follows one control step of every robot.

        Args:
            poses: (N, 3) poses after the step.

        Returns:
            ``(done, gave_up)``: (N,) bool, the door sub-tasks that reached their end, and those
            that gave up (turned round, or ran out of steps: see :attr:`out_of_steps`). Corridors
            and Corners is never in either.
        """
        pose_rows = np.asarray(poses, dtype=np.float64)
        self.heading_change += wrap_angle(pose_rows[:, 2] - self.previous_yaw)
        self.previous_yaw = pose_rows[:, 2].copy()
        self.steps += 1
        turn = np.asarray(TARGET_TURN)[self.subtask]
        is_turn = turn != 0.0
        phase = heading_phases(self.subtask, self.heading_change)
        entering = is_turn & (phase == 2) & (self.heading_phase != 2)
        self.turn_point[entering] = pose_rows[entering, :2]
        if self.door_distance:
            heading = np.stack([np.cos(self.start[:, 2]), np.sin(self.start[:, 2])], axis=1)
            driven = np.einsum("ij,ij->i", pose_rows[:, :2] - self.start[:, :2], heading)
            bins = distance_bins(driven)
            self.phase = np.where(
                self.subtask == SubTask.CORRIDOR, 0, phase + MAX_PHASES * bins
            ).astype(np.int64)
        else:
            self.phase = phase

        target_heading = self.start[:, 2] + turn
        direction = np.stack([np.cos(target_heading), np.sin(target_heading)], axis=1)
        aligned = np.abs(self.heading_change - turn) <= HEADING_TOLERANCE
        turned_out = np.einsum("ij,ij->i", pose_rows[:, :2] - self.turn_point, direction)
        ahead = np.einsum("ij,ij->i", pose_rows[:, :2] - self.start[:, :2], direction)
        turn_done = is_turn & (phase == 2) & aligned & (turned_out >= TURN_EXIT_DISTANCE)
        forward_done = (self.subtask == SubTask.FORWARD) & aligned & (ahead >= FORWARD_DISTANCE)
        door = self.subtask != SubTask.CORRIDOR
        gave_up = door & (
            (self.steps >= MAX_DOOR_STEPS) | (np.abs(self.heading_change) > GIVE_UP_ANGLE)
        )
        done = (turn_done | forward_done) & ~gave_up
        return done, gave_up

    def arrays(self) -> dict[str, npt.NDArray[Any]]:
        """The tracker's state by name, for the core's multi-step call
        (``BatchSimulator.run(..., subtasks=...)``), which follows the sub-tasks step by step
        as :meth:`update` does and writes the arrays in place. With ``door_distance`` the core
        writes back the heading phase alone (it computes the distance bin from each pose): the
        next :meth:`update` counts the distance again.
        """
        return {
            "subtask": self.subtask,
            "start": self.start,
            "previous_yaw": self.previous_yaw,
            "heading_change": self.heading_change,
            "steps": self.steps,
            "phase": self.phase,
            "turn_point": self.turn_point,
        }

    @property
    def heading_phase(self) -> npt.NDArray[np.int64]:
        """(N,) each robot's heading phase alone (:func:`heading_phases`)."""
        return self.phase % MAX_PHASES

    @property
    def out_of_steps(self) -> npt.NDArray[np.bool_]:
        """(N,) bool: door sub-tasks that have used up :data:`MAX_DOOR_STEPS`."""
        return (self.subtask != SubTask.CORRIDOR) & (self.steps >= MAX_DOOR_STEPS)

    def states(self, distance_states: npt.ArrayLike) -> npt.NDArray[np.int64]:
        """Each robot's state in its running sub-task's table."""
        return subtask_states(distance_states, self.phase)


#: Largest heading error (radians) from the grid at which the blind rule drives straight on.
HOLD_TOLERANCE = float(np.radians(3.0))

_QUARTER_TURN = np.pi / 2.0
_FORWARD = action_index("00")
_GENTLE_RIGHT = action_index("11")
_GENTLE_LEFT = action_index("55")
_SPINS = np.array([action_index("aa"), action_index("bb")])


def grid_error(yaw: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Radians by which each heading lies left (positive) of the nearest multiple of 90 degrees,
    in ``[-pi/4, pi/4]``."""
    heading = np.asarray(yaw, dtype=np.float64)
    return heading - np.round(heading / _QUARTER_TURN) * _QUARTER_TURN


def hold_actions(yaw: npt.ArrayLike, previous: npt.ArrayLike) -> npt.NDArray[np.int64]:
    """The blind rule's action for each robot, from its odometry heading ``yaw`` (radians) and
    the action it took in its last step (``-1`` for none)."""
    error = grid_error(yaw)
    last = np.asarray(previous, dtype=np.int64)
    off = np.abs(error) > HOLD_TOLERANCE
    action = np.where(error > HOLD_TOLERANCE, _GENTLE_RIGHT, _FORWARD)
    action = np.where(error < -HOLD_TOLERANCE, _GENTLE_LEFT, action)
    spinning = off & np.isin(last, _SPINS)
    return np.where(spinning, last, action).astype(np.int64)


def _mirrored_actions() -> npt.NDArray[np.int64]:
    swapped = WHEEL_SPEED_FRACTIONS[:, ::-1]
    matches = np.all(np.isclose(swapped[:, None, :], WHEEL_SPEED_FRACTIONS[None, :, :]), axis=2)
    if not np.all(matches.sum(axis=1) == 1):
        raise AssertionError("every action needs exactly one mirror image")
    return np.argmax(matches, axis=1).astype(np.int64)


#: ``MIRRORED_ACTION[a]`` is the action with the wheel speeds of ``a`` swapped.
MIRRORED_ACTION: npt.NDArray[np.int64] = _mirrored_actions()
#: ``MIRRORED_SUBTASK[k]`` is the mirror image of sub-task ``k``.
MIRRORED_SUBTASK: npt.NDArray[np.int64] = np.array(
    [SubTask.CORRIDOR, SubTask.LEFT, SubTask.RIGHT, SubTask.FORWARD], dtype=np.int64
)

_SWAPPED_SENSOR = np.array(
    [
        SENSOR_ORDER.index(name.replace("left", "#").replace("right", "left").replace("#", "right"))
        for name in SENSOR_ORDER
    ]
)
_PLACE = NUM_LEVELS ** np.arange(NUM_SENSORS, dtype=np.int64)
_distance_states = np.arange(NUM_STATES, dtype=np.int64)
_levels = (_distance_states[:, None] // _PLACE) % NUM_LEVELS
#: ``_MIRRORED_DISTANCE_STATE[s]`` is the distance state with left and right swapped.
_MIRRORED_DISTANCE_STATE = _levels[:, _SWAPPED_SENSOR] @ _PLACE


def mirrored_states(states: npt.ArrayLike, subtasks: npt.ArrayLike) -> npt.NDArray[np.int64]:
    """Mirrors the states of the given sub-tasks (distance state plus 4096 times the phase).

    A turn's phase counts its progress towards its own side, so it stays; the heading phase of
    "Going forward on a door" tells right of straight (0) from left of it (2), so those two swap.
    A distance bin (``heading_phase + 3 * bin``, :data:`mazesim.learn.subtasks.DISTANCE_PHASES`)
    stays.
    """
    values = np.asarray(states, dtype=np.int64)
    phase = values // NUM_STATES
    forward = np.asarray(subtasks) == SubTask.FORWARD
    heading, distance_bin = phase % MAX_PHASES, phase // MAX_PHASES
    phase = np.where(forward, 2 - heading + MAX_PHASES * distance_bin, phase)
    return _MIRRORED_DISTANCE_STATE[values % NUM_STATES] + NUM_STATES * phase


def begin_subtask(policy: Any, robot: int, subtask: int) -> None:
    """Makes ``robot`` of a :class:`mazesim.learn.policy.HierarchicalPolicy` run ``subtask`` from
    where its running sub-task began (the start of a reset, say)."""
    arrays = policy.subtask_arrays()
    arrays["subtask"][robot] = subtask
    policy.set_subtask_arrays(arrays)
