"""Wheel odometry: a differential-drive robot's pose dead-reckoned from how far each wheel rolled.

Between two readings a robot whose left wheel rolled ``left`` metres and right wheel ``right``
metres has driven ``(left + right) / 2`` along its heading and turned ``(right - left) / axle``
radians; the step is taken along the heading half-way through the turn (the midpoint rule, exact
for an arc to second order). What the pose is worth depends on what the wheel travel is measured
from: a controller that knows only its nominal wheel radius and axle length believes its wheels
are those, so a wheel worn 5 % smaller makes it overestimate every distance by 5 %.

Example:
    >>> import numpy as np
    >>> from mazesim.odometry import advance
    >>> pose = np.zeros((2, 3))
    >>> advance(pose, np.array([0.1, -0.01]), np.array([0.1, 0.01]), axle_length=0.1)
    >>> np.round(pose, 3).tolist()  # straight on; 0.2 radians on the spot
    [[0.1, 0.0, 0.0], [0.0, 0.0, 0.2]]
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from mazesim._sizes import number_array
from mazesim.errors import InvalidArgumentError, _shown

__all__ = ["advance", "wrap_angle"]


def wrap_angle(angle: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Angles (radians) wrapped into ``[-pi, pi)``.

    Raises:
        InvalidArgumentError: An angle is not finite (infinity has no direction: numpy's
            remainder would make it NaN with a warning).
    """
    array = number_array(angle, "angle", checked_after=True)
    if not np.isfinite(array).all():
        found = float(array[~np.isfinite(array)].flat[0])
        raise InvalidArgumentError(f"expected finite angles in radians, found {_shown(found)}")
    return (array + np.pi) % (2.0 * np.pi) - np.pi


def advance(
    pose: npt.NDArray[np.float64],
    left: npt.ArrayLike,
    right: npt.ArrayLike,
    axle_length: float,
) -> None:
    """Moves each robot's ``pose`` ((N, 3) x, y, yaw; in place) by its wheels' travel.

    Args:
        pose: The poses to advance, in metres and radians.
        left: (N,) metres the left wheels rolled since the poses were last advanced.
        right: (N,) metres the right wheels rolled.
        axle_length: Distance between the wheels, in metres.

    Raises:
        InvalidArgumentError: A travel is not finite, or the axle length not more than 0: the
            poses are left as they were.
    """
    left_travel = number_array(left, "left", checked_after=True)
    right_travel = number_array(right, "right", checked_after=True)
    for travel in (left_travel, right_travel):
        if not np.all(np.isfinite(travel)):
            found = travel[~np.isfinite(travel)].flat[0]
            raise InvalidArgumentError(f"expected finite wheel travels in metres, found {found}")
    if not (math.isfinite(axle_length) and axle_length > 0.0):
        raise InvalidArgumentError(f"expected an axle length of more than 0 m, found {axle_length}")
    forward = 0.5 * (left_travel + right_travel)
    turn = (right_travel - left_travel) / axle_length
    heading = pose[:, 2] + 0.5 * turn
    # A pose that is not finite makes the yaw so: refused before any pose moves.
    yaw = wrap_angle(pose[:, 2] + turn)
    x = pose[:, 0] + forward * np.cos(heading)
    y = pose[:, 1] + forward * np.sin(heading)
    pose[:, 0], pose[:, 1], pose[:, 2] = x, y, yaw
