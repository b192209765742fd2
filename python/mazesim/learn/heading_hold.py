"""Holding the heading on the maze's grid where no sensor sees a wall (``--hold-heading``).

A robot whose sensors see walls only within a few cm (the e-puck's own infra-red, the Sharp
sensors on dark walls) drives down a corridor's middle seeing nothing: the lower level's state is
then the blind one (:data:`mazesim.learn.subtasks.BLIND_STATE`) whatever its heading, and a
plain "drive forward" (``--blind-forward``) keeps whatever heading the robot had when it last saw
a wall. A few degrees off carries it across a junction into the wrong branch, and a turn at a
corner that the table had begun on the spot is left half done as soon as the wall goes out of
sight.

With ``hold_heading``, "Corridors and Corners" in the blind state follows this rule instead of
its table, in training (exploring too) and after it:

- a robot that was turning on the spot (``aa`` or ``bb``) keeps turning the same way until its
  heading is within :data:`HOLD_TOLERANCE` of a multiple of 90 degrees, so it finishes the turn
  it began;
- otherwise it steers back onto the nearest multiple of 90 degrees with a gentle turn (``11`` or
  ``55``) while it is more than :data:`HOLD_TOLERANCE` off, and drives forward (``00``) within it.

The heading is the odometry's (the poses the navigator is given). mazesim's mazes have their walls
along the world's axes, so in the simulator the grid is the world frame; the dead-reckoning
navigator of the ROS node and :meth:`mazesim.learn.tables.TrainedPolicy.act` measure the heading
from where the episode began, so the robot must start facing along a corridor (as every built-in
world's start does).

Example:
    >>> import numpy as np
    >>> from mazesim.learn.heading_hold import hold_actions
    >>> yaw = np.radians([0.0, 10.0, -10.0, 100.0, 30.0])
    >>> previous = np.array([0, 0, 0, 0, 10])
    >>> hold_actions(yaw, previous).tolist()  # forward, right, left, right, keep spinning left
    [0, 1, 5, 1, 10]
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from mazesim.actions import action_index

__all__ = ["HOLD_TOLERANCE", "grid_error", "hold_actions"]

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
