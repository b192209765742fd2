"""Left-right mirror symmetry of the robot, used to learn from each step twice.

The ``seed`` robot is symmetric about its centre line: mirroring a situation swaps the left and
right sensors (and left-front and right-front), swaps the wheels of every action (``11`` and
``55``, ``aa`` and ``bb``; ``00`` and ``99`` stay) and swaps the right and left turns. So every
transition ``(s, a, r, s')`` of a sub-task is also a transition ``(m(s), m(a), r, m(s'))`` of its
mirror sub-task, in the mirrored maze; training feeds both to the tables, which doubles the
experience and keeps "Right turn on a door" and "Left turn on a door" each other's mirror image.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from mazesim.actions import WHEEL_SPEED_FRACTIONS
from mazesim.learn.discretise import NUM_LEVELS, NUM_SENSORS, NUM_STATES, SENSOR_ORDER
from mazesim.learn.subtasks import MAX_PHASES, SubTask

__all__ = ["MIRRORED_ACTION", "MIRRORED_SUBTASK", "mirrored_states"]


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
