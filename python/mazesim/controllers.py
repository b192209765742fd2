"""Controllers of the source report, written against mazesim's sensor arrays.

:class:`AvoidCollision` is the report's Alg. 1 (the avoid-collision controller of the e-puck, as
in Webots' e-puck obstacle-avoidance tutorial): it reads the eight infra-red proximity sensors
``ps0``..``ps7`` and turns away from whichever side sees an obstacle.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from mazesim.errors import InvalidArgumentError

__all__ = ["AvoidCollision"]

#: Indices of the proximity sensors on the e-puck's front-right (ps0, ps1, ps2).
RIGHT_SENSORS = (0, 1, 2)
#: Indices of the proximity sensors on the e-puck's front-left (ps5, ps6, ps7).
LEFT_SENSORS = (5, 6, 7)


class AvoidCollision:
    """The report's Alg. 1: drive forward, turn away from obstacles.

    Both wheels start at half the maximum speed. If one of ps5, ps6, ps7 (front-left) reads above
    the threshold, the robot turns right (left wheel at full speed, right wheel stopped); else if
    one of ps0, ps1, ps2 (front-right) does, it turns left. The left side wins when both see an
    obstacle, as in Webots' e-puck tutorial.

    Attributes:
        MAX_SPEED: The e-puck's maximum wheel speed in rad/s.
        threshold: The raw proximity reading above which a sensor sees an obstacle.
        max_speed: The wheel speed in rad/s that the rule scales.

    Example:
        >>> import numpy as np
        >>> controller = AvoidCollision()
        >>> controller(np.zeros(8))
        (3.14, 3.14)
        >>> controller(np.array([0, 0, 0, 0, 0, 0, 200.0, 0]))
        (6.28, 0.0)
    """

    MAX_SPEED = 6.28

    def __init__(self, threshold: float = 80.0, max_speed: float = MAX_SPEED) -> None:
        """Creates the controller.

        Args:
            threshold: Raw proximity reading above which an obstacle is seen (80 in the report).
            max_speed: Maximum wheel speed in rad/s (6.28 for the e-puck).
        """
        self.threshold = float(threshold)
        self.max_speed = float(max_speed)

    def __call__(self, distance_sensors: npt.ArrayLike) -> tuple[float, float]:
        """Computes the wheel speeds for one robot.

        Args:
            distance_sensors: The eight readings ps0..ps7, shape (8,).

        Returns:
            The (left, right) wheel speeds in rad/s.

        Raises:
            InvalidArgumentError: The readings are not of shape (8,).
        """
        readings = np.asarray(distance_sensors, dtype=np.float64)
        if readings.shape != (8,):
            raise InvalidArgumentError(
                f"AvoidCollision expects the 8 readings ps0..ps7, shape (8,); "
                f"found shape {readings.shape}"
            )
        left_obstacle = bool(np.any(readings[list(LEFT_SENSORS)] > self.threshold))
        right_obstacle = bool(np.any(readings[list(RIGHT_SENSORS)] > self.threshold))
        half = 0.5 * self.max_speed
        left_speed = half
        right_speed = half
        if left_obstacle:
            left_speed += half
            right_speed -= half
        elif right_obstacle:
            left_speed -= half
            right_speed += half
        return left_speed, right_speed

    def batch(self, distance_sensors: npt.ArrayLike) -> npt.NDArray[np.float32]:
        """Computes the wheel speeds for many robots at once.

        Args:
            distance_sensors: The readings ps0..ps7 of N robots, shape (N, 8).

        Returns:
            A float32 array of shape (N, 2): the left and right wheel speeds of each robot in
            rad/s, row for row equal to calling the controller on each row.

        Raises:
            InvalidArgumentError: The readings are not of shape (N, 8).
        """
        readings = np.asarray(distance_sensors, dtype=np.float64)
        if readings.ndim != 2 or readings.shape[1] != 8:
            raise InvalidArgumentError(
                f"AvoidCollision.batch expects readings of shape (N, 8); "
                f"found shape {readings.shape}"
            )
        left_obstacle = np.any(readings[:, list(LEFT_SENSORS)] > self.threshold, axis=1)
        right_obstacle = np.any(readings[:, list(RIGHT_SENSORS)] > self.threshold, axis=1)
        half = 0.5 * self.max_speed
        # +1: turn right (left wheel faster), -1: turn left, 0: straight on.
        turn = np.where(left_obstacle, 1.0, np.where(right_obstacle, -1.0, 0.0))
        wheel_speeds = np.empty((readings.shape[0], 2), dtype=np.float64)
        wheel_speeds[:, 0] = half + turn * half
        wheel_speeds[:, 1] = half - turn * half
        return wheel_speeds.astype(np.float32)
