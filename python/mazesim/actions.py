"""The report's twelve primitive actions: their codes and their wheel speeds.

This table is the single source of truth for the primitive actions; the gymnasium environments'
discrete action mode, the ROS bridge and the hierarchical learner all read it. An action is a pair
of wheel speeds given as fractions of the robot's motor limit (``max_wheel_speed`` of its profile,
6.28 rad/s on the e-puck), so it means the same thing on every robot. The codes are the report's
(section 4.1, Fig. 4.7); the speeds are mazesim's choice, built on the report's cruise speed of half
the motor limit (Alg. 1 drives at ``0.5 * MAX_SPEED``):

=====  ======  ===================  ==========  ==========  ======================
index  code    action               left        right       e-puck, rad/s
=====  ======  ===================  ==========  ==========  ======================
0      ``00``  forward              0.5         0.5         3.14, 3.14
1      ``11``  turn right, gentle   0.5         0.375       3.14, 2.355
2      ``22``  turn right           0.5         0.25        3.14, 1.57
3      ``33``  turn right, sharp    0.5         0.125       3.14, 0.785
4      ``44``  turn right, hard     0.5         0.0         3.14, 0.0
5      ``55``  turn left, gentle    0.375       0.5         2.355, 3.14
6      ``66``  turn left            0.25        0.5         1.57, 3.14
7      ``77``  turn left, sharp     0.125       0.5         0.785, 3.14
8      ``88``  turn left, hard      0.0         0.5         0.0, 3.14
9      ``aa``  spin right in place  0.25        -0.25       1.57, -1.57
10     ``bb``  spin left in place   -0.25       0.25        -1.57, 1.57
11     ``99``  backward             -0.25       -0.25       -1.57, -1.57
=====  ======  ===================  ==========  ==========  ======================

A turn of strength ``k`` (1 to 4) slows the inner wheel to ``(1 - k / 4)`` of the cruise speed, so
``44`` and ``88`` pivot about the stopped inner wheel. Spins and the backward move run at half the
cruise speed: on the e-puck a spin turns at about 1.24 rad/s, 4 degrees per 32 ms control step.
The index is the action's number in the environments' ``Discrete(12)`` action space.

Example:
    >>> from mazesim.actions import ACTION_CODES, wheel_speeds
    >>> ACTION_CODES[2]
    '22'
    >>> wheel_speeds("22", max_speed=6.28)
    (3.14, 1.57)
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from mazesim.errors import InvalidActionError, _bounded_number, _shown

__all__ = [
    "ACTIONS",
    "ACTION_CODES",
    "CRUISE_FRACTION",
    "WHEEL_SPEED_FRACTIONS",
    "PrimitiveAction",
    "action_index",
    "wheel_speeds",
]

#: The cruise wheel speed as a fraction of the motor limit (the report's ``0.5 * MAX_SPEED``).
CRUISE_FRACTION = 0.5


class PrimitiveAction(NamedTuple):
    """One primitive action: its code, what it does, and its wheel speeds as fractions of the
    motor limit (positive drives forward)."""

    code: str
    description: str
    left: float
    right: float


def _turn(strength: int, side: str) -> PrimitiveAction:
    """The turn of ``strength`` 1 (gentle) to 4 (hard) to ``side``."""
    inner = CRUISE_FRACTION * (1.0 - strength / 4.0)
    adjective = {1: ", gentle", 2: "", 3: ", sharp", 4: ", hard"}[strength]
    if side == "right":
        return PrimitiveAction(f"{strength}" * 2, f"turn right{adjective}", CRUISE_FRACTION, inner)
    return PrimitiveAction(f"{strength + 4}" * 2, f"turn left{adjective}", inner, CRUISE_FRACTION)


_SLOW = 0.5 * CRUISE_FRACTION

#: Every primitive action by code, in the order of the report's list (the discrete action index).
ACTIONS: dict[str, PrimitiveAction] = {
    action.code: action
    for action in (
        PrimitiveAction("00", "forward", CRUISE_FRACTION, CRUISE_FRACTION),
        *(_turn(k, "right") for k in range(1, 5)),
        *(_turn(k, "left") for k in range(1, 5)),
        PrimitiveAction("aa", "spin right in place", _SLOW, -_SLOW),
        PrimitiveAction("bb", "spin left in place", -_SLOW, _SLOW),
        PrimitiveAction("99", "backward", -_SLOW, -_SLOW),
    )
}

#: The twelve action codes; ``ACTION_CODES[i]`` is discrete action ``i``.
ACTION_CODES: tuple[str, ...] = tuple(ACTIONS)

#: (12, 2) read-only array of (left, right) wheel speeds as fractions of the motor limit, in the
#: order of :data:`ACTION_CODES`. Multiply by a robot's ``max_wheel_speed`` to get rad/s.
WHEEL_SPEED_FRACTIONS: npt.NDArray[np.float64] = np.array(
    [(action.left, action.right) for action in ACTIONS.values()], dtype=np.float64
)
WHEEL_SPEED_FRACTIONS.flags.writeable = False


def action_index(code: str) -> int:
    """Returns the discrete action index of an action code.

    Surrounding white space is ignored and the letters may be in either case (``"AA"``).

    Args:
        code: An action code such as ``"00"`` or ``"aa"``.

    Returns:
        The index of the code in :data:`ACTION_CODES` (0 to 11).

    Raises:
        InvalidActionError: The code is not one of :data:`ACTION_CODES`.
    """
    key = code.strip().lower() if isinstance(code, str) else None
    if key not in ACTIONS:
        raise InvalidActionError(
            f"expected an action code, one of {', '.join(ACTION_CODES)}; found {_shown(code)}"
        )
    return ACTION_CODES.index(key)


def wheel_speeds(code: str, max_speed: float) -> tuple[float, float]:
    """Returns the (left, right) wheel speeds in rad/s of a primitive action.

    Args:
        code: An action code such as ``"00"`` or ``"aa"`` (either case, white space ignored).
        max_speed: The robot's motor limit in rad/s (``RobotProfile.max_wheel_speed``; 6.28 on
            the e-puck).

    Returns:
        The left and right wheel speeds in rad/s.

    Raises:
        InvalidActionError: The code is not one of :data:`ACTION_CODES`.
        InvalidArgumentError: ``max_speed`` is NaN, infinite or below 0.

    Example:
        >>> wheel_speeds("aa", 6.28)
        (1.57, -1.57)
    """
    action = ACTIONS[ACTION_CODES[action_index(code)]]
    limit = _bounded_number("max_speed", max_speed, least=0.0)
    return action.left * limit, action.right * limit
