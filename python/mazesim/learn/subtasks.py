"""The four lower-level sub-tasks of the report's section 4.1: their states, ends and rewards.

========  =========================  ======  ==================================================
number    name                       phases  what it does
========  =========================  ======  ==================================================
0 (CC)    Corridors and Corners      1       follows the corridor it is in, round its corners
1 (R)     Right turn on a door       3       drives to the next opening on its right and turns in
2 (L)     Left turn on a door        3       drives to the next opening on its left and turns in
3 (F)     Going forward on a door    3       drives straight through the door ahead
========  =========================  ======  ==================================================

**State.** Corridors and Corners sees the distance state of :mod:`mazesim.learn.discretise`
(4096 values). The door sub-tasks add a phase, the robot's heading change since the sub-task
began in three bins (the core's ``navigator::door``), and see ``distance_state + 4096 * phase``
(12288 values):

- the turns: 0 while the robot has turned less than 30 degrees towards its side, 1 up to 60
  degrees, 2 beyond. Without it the middle of a crossing looks the same before and after a right
  turn (open on all sides), and a table could not tell "turn now" from "the turn is done".
- Going forward: 0 when the heading is more than 5 degrees right of where it began, 1 within
  5 degrees, 2 more than 5 degrees left. Inside a door the side sensors see nothing to steer by.

**Distance phases** (``door_distance``, ``mazesim train --door-distance``). A navigator
trained so also counts, in its door sub-tasks' phase, how far its odometry has carried it ahead of
where the sub-task began (along the heading it began with) in six bins (:data:`DISTANCE_EDGES`:
below 12 cm, 12-18, 18-22, 22-26, 26-30 and beyond 30 cm): the phase is
``heading_phase + 3 * distance_bin`` (18 phases, :data:`DISTANCE_PHASES`). A door lies 20-28 cm
ahead of a door sub-task's training start, so a table can learn to drive on to it and turn there
without seeing it: a robot whose sensors see no wall from a corridor's middle (the e-puck's own
infra-red sensors, or the Sharp ones at dark walls) finds its doors so. Which a navigator uses
follows from its tables' shape (:func:`door_distance_of`).

**Odometry.** The phases and the ends use what the robot's wheel odometry knows: the heading
change and the displacement since the sub-task began. The core's navigator
(:class:`mazesim._core.Navigator`) takes them from the poses a :class:`mazesim.BatchSimulator`
reports, which stand in for noise-free wheel odometry (they differ from it only when a wheel
slips against a wall).

**Actions.** The door sub-tasks choose among all 12 primitive actions. Corridors and Corners
chooses among the 11 that do not reverse (:data:`SUBTASK_ACTIONS`): it follows corridors forward
and turns round on the spot in a dead end. With ``99`` (backward) it could learn, in the few
states its sensors cannot tell apart, to drive forward and back in front of a wall for ever; in
training runs with other seeds or noise streams it did, and then reached the goal of only 30-50 %
of unseen mazes. Its table keeps the ``99`` column (never updated) so that all tables share one
shape.

**Ends**:

- Corridors and Corners never ends by itself; a checkpoint event or the goal ends it.
- Right / Left turn: done when the heading is within 10 degrees of 90 degrees to that side of the
  heading at the start and the robot has driven :data:`TURN_EXIT_DISTANCE` (8 cm) towards the new
  heading since it last entered phase 2.
- Going forward: done when the robot is :data:`FORWARD_DISTANCE` (40 cm) ahead of where it began
  (through the door it was about to enter, just into the next cell) within 10 degrees of its
  heading.
- A door sub-task gives up after :data:`MAX_DOOR_STEPS` control steps (12.8 s at the navigator's
  64 ms step) or a heading change of more than 150 degrees; Corridors and Corners then drives on.

A checkpoint event (a barcode crossed) ends whatever runs and asks the higher level again.

**Rewards** (training only; they may read the maze, the robot never does):

- Corridors and Corners: ``10 * (metres driven forward along the robot's heading)`` per step,
  ``-0.02`` a step and ``-2`` per step in contact with a wall. Driving a corridor at cruise speed
  earns 0.02 a step; turning on the spot or dithering between two states loses 0.02 a step.
- Door sub-tasks: ``10 * (metres of progress along the door's path)`` per step, where the path runs
  from the start to the door's centre, then 25 cm into the target opening (progress along each leg
  is clipped to the leg); for Going forward also ``2 * (radians the heading error shrank)``;
  ``-0.03`` a step; ``-2`` per step in contact; at the end ``+5`` when the
  robot has really entered the target opening (its centre at least 4 cm past the door's centre
  that way and within 8 cm of the opening's centre line) and ``-5`` when it has not, or turned
  round. Running out of steps only cuts the episode short (the value of where it stopped still
  counts), so the step cost alone teaches that dithering does not pay.
"""

from __future__ import annotations

import math
from enum import IntEnum

import numpy as np
import numpy.typing as npt

from mazesim.actions import ACTION_CODES
from mazesim.batch import CONTROL_STEP_MS, cruise_step_length
from mazesim.errors import InvalidArgumentError
from mazesim.learn.discretise import NUM_STATES

__all__ = [
    "BLIND_STATE",
    "COLLISION_PENALTY",
    "CONTROL_STEP_MS",
    "CORRIDOR_STEP_REWARD",
    "DOOR_FAILURE_REWARD",
    "DOOR_STEP_REWARD",
    "DISTANCE_EDGES",
    "DISTANCE_PHASES",
    "DOOR_SUCCESS_REWARD",
    "FORWARD_DISTANCE",
    "FORWARD_PHASE_ANGLE",
    "GIVE_UP_ANGLE",
    "HEADING_REWARD",
    "HEADING_TOLERANCE",
    "MAX_DOOR_STEPS",
    "MAX_PHASES",
    "NUM_PHASES",
    "NUM_SUBTASKS",
    "PROGRESS_REWARD",
    "SUBTASK_ACTIONS",
    "SUBTASK_CODES",
    "SUBTASK_NAMES",
    "TARGET_TURN",
    "TURN_EXIT_DISTANCE",
    "TURN_PHASE_ANGLES",
    "SubTask",
    "cruise_step_length",
    "door_distance_of",
    "phase_counts",
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
#: The actions each sub-task may take, ``(NUM_SUBTASKS, 12)``: all but ``99`` for Corridors
#: and Corners, all for the door sub-tasks.
SUBTASK_ACTIONS: npt.NDArray[np.bool_] = np.ones((NUM_SUBTASKS, len(ACTION_CODES)), dtype=bool)
SUBTASK_ACTIONS[0, ACTION_CODES.index("99")] = False
SUBTASK_ACTIONS.flags.writeable = False
#: Phases per sub-task.
NUM_PHASES: tuple[int, ...] = (1, 3, 3, 3)
#: The most phases of any sub-task (the stacked tables have ``4096 * MAX_PHASES`` rows).
MAX_PHASES = max(NUM_PHASES)
#: Edges (metres ahead of the sub-task's start, along the heading it began with) of the door
#: sub-tasks' distance bins, with ``door_distance``.
DISTANCE_EDGES: tuple[float, ...] = (0.12, 0.18, 0.22, 0.26, 0.30)
#: Phases per sub-task with ``door_distance``: the three heading phases in each distance bin.
DISTANCE_PHASES: tuple[int, ...] = (1,) + (MAX_PHASES * (len(DISTANCE_EDGES) + 1),) * 3
#: The distance state in which no sensor sees a wall (every level 3).
BLIND_STATE = NUM_STATES - 1
#: The heading change each sub-task aims at (radians, counter-clockwise positive).
TARGET_TURN: tuple[float, ...] = (0.0, -math.pi / 2.0, math.pi / 2.0, 0.0)
#: Turn towards its side (radians) at which a turn enters phase 1 and phase 2.
TURN_PHASE_ANGLES = (math.radians(30.0), math.radians(60.0))
#: Heading change (radians) beyond which "Going forward on a door" is in phase 0 or 2.
FORWARD_PHASE_ANGLE = math.radians(5.0)
#: Largest heading error (radians) at which a door sub-task may end.
HEADING_TOLERANCE = math.radians(10.0)
#: Metres driven towards the new heading after entering phase 2, to end a turn.
TURN_EXIT_DISTANCE = 0.08
#: Metres ahead of its start at which "Going forward on a door" ends.
FORWARD_DISTANCE = 0.40
#: Control steps after which a door sub-task gives up.
MAX_DOOR_STEPS = 200
#: Heading change (radians) after which a door sub-task gives up.
GIVE_UP_ANGLE = math.radians(150.0)
#: Reward per metre of progress.
PROGRESS_REWARD = 10.0
#: Reward of each control step spent in contact with a wall.
COLLISION_PENALTY = -2.0
#: Reward of each control step of Corridors and Corners, and of a door sub-task.
CORRIDOR_STEP_REWARD = -0.02
DOOR_STEP_REWARD = -0.03
#: Reward per radian by which "Going forward on a door" brings its heading back to where it began
#: (a potential: turning away and back again sums to nothing).
HEADING_REWARD = 2.0
#: Reward at the end of a door sub-task that entered its opening, and of one that did not.
DOOR_SUCCESS_REWARD = 5.0
DOOR_FAILURE_REWARD = -5.0


def phase_counts(door_distance: bool) -> tuple[int, ...]:
    """Phases per sub-task: :data:`NUM_PHASES`, or :data:`DISTANCE_PHASES` with distance."""
    return DISTANCE_PHASES if door_distance else NUM_PHASES


def door_distance_of(rows: int) -> bool:
    """Whether stacked tables of ``rows`` rows per sub-task count the distance in their phases.

    Raises:
        InvalidArgumentError: ``rows`` is neither ``4096 * 3`` nor ``4096 * 18``.
    """
    for door_distance in (False, True):
        if rows == NUM_STATES * max(phase_counts(door_distance)):
            return door_distance
    raise InvalidArgumentError(
        f"expected lower-level tables of {NUM_STATES * MAX_PHASES} rows per sub-task (heading "
        f"phases) or {NUM_STATES * max(DISTANCE_PHASES)} (with distance), found {rows}"
    )
