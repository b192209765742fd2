"""Controllers of the source report, written against mazesim's sensor arrays.

:class:`AvoidCollision` is the report's Alg. 1 (the avoid-collision controller of the e-puck, as
in Webots' e-puck obstacle-avoidance tutorial): it reads the eight infra-red proximity sensors
``ps0``..``ps7`` and turns away from whichever side sees an obstacle. :class:`FollowLine` is
Alg. 2 (follow a black line with the ground sensors ``gs0``..``gs2``), and :class:`Explore` the
exploration controller of the report's barcode study (section 4.2.2) on the seed robot's six
Sharp sensors. Each works on one robot (call it) or on a batch (``batch``).
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from mazesim._sizes import number_array
from mazesim.errors import InvalidArgumentError, _bounded_number

__all__ = ["AvoidCollision", "Explore", "FollowLine"]

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
        self.threshold = _bounded_number("threshold", threshold)
        self.max_speed = _bounded_number("max_speed", max_speed, least=0.0)

    def __call__(self, distance_sensors: npt.ArrayLike) -> tuple[float, float]:
        """Computes the wheel speeds for one robot.

        Args:
            distance_sensors: The eight readings ps0..ps7, shape (8,).

        Returns:
            The (left, right) wheel speeds in rad/s.

        Raises:
            InvalidArgumentError: The readings are not of shape (8,).
        """
        readings = number_array(distance_sensors, "distance_sensors")
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
        readings = number_array(distance_sensors, "distance_sensors")
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


#: Indices of the seed robot's Sharp sensors, in the report's order.
FRONT, BACK, LEFT, RIGHT, LEFT_FRONT, RIGHT_FRONT = range(6)


def _rows(values: npt.ArrayLike, width: int, who: str) -> npt.NDArray[np.float64]:
    """Readings of N robots as a float64 (N, width) array, or an error naming ``who``."""
    readings = number_array(values, f"{who}'s readings")
    if readings.ndim != 2 or readings.shape[1] != width:
        raise InvalidArgumentError(
            f"{who}.batch expects readings of shape (N, {width}); found shape {readings.shape}"
        )
    return readings


def _row(values: npt.ArrayLike, width: int, who: str, names: str) -> npt.NDArray[np.float64]:
    """Readings of one robot as a float64 (width,) array, or an error naming ``who``."""
    readings = number_array(values, f"{who}'s readings")
    if readings.shape != (width,):
        raise InvalidArgumentError(
            f"{who} expects the {width} readings {names}, shape ({width},); "
            f"found shape {readings.shape}"
        )
    return readings


class FollowLine:
    """The report's Alg. 2: follow a black line with the three ground sensors gs0, gs1, gs2.

    A ground sensor sees the line when it reads below the threshold (black ~300, white ~856).
    If the right sensor (gs2) is the only one that sees the line, the robot turns right (left
    wheel faster); if the left sensor (gs0) is the only one, it turns left; otherwise both
    wheels keep the same speed. Speeds are ``speed +- turn`` while turning, ``speed`` otherwise.

    Attributes:
        MAX_SPEED: The e-puck's maximum wheel speed in rad/s.
        threshold: Ground reading below which a sensor sees the black line.
        speed: Wheel speed in rad/s when going straight.
        turn: Wheel speed difference in rad/s added to one wheel and taken from the other.

    Example:
        >>> controller = FollowLine()
        >>> controller([856.0, 300.0, 856.0])
        (3.14, 3.14)
        >>> controller([856.0, 856.0, 300.0])
        (4.71, 1.57)
    """

    MAX_SPEED = 6.28

    def __init__(
        self,
        threshold: float = 500.0,
        speed: float = 0.5 * MAX_SPEED,
        turn: float = 0.25 * MAX_SPEED,
    ) -> None:
        """Creates the controller.

        Args:
            threshold: Ground reading below which a sensor sees the line.
            speed: Wheel speed in rad/s on a straight line (half the e-puck's maximum).
            turn: Speed difference in rad/s added to one wheel and taken from the other.
        """
        self.threshold = _bounded_number("threshold", threshold)
        self.speed = _bounded_number("speed", speed)
        self.turn = _bounded_number("turn", turn)

    def __call__(self, ground_sensors: npt.ArrayLike) -> tuple[float, float]:
        """Computes the wheel speeds for one robot.

        Args:
            ground_sensors: The three readings gs0 (left), gs1 (centre), gs2 (right).

        Returns:
            The (left, right) wheel speeds in rad/s.

        Raises:
            InvalidArgumentError: The readings are not of shape (3,).
        """
        readings = _row(ground_sensors, 3, "FollowLine", "gs0..gs2")
        wheel_speeds = self._wheel_speeds(readings.reshape(1, 3))
        return float(wheel_speeds[0, 0]), float(wheel_speeds[0, 1])

    def batch(self, ground_sensors: npt.ArrayLike) -> npt.NDArray[np.float32]:
        """Computes the wheel speeds for many robots at once.

        Args:
            ground_sensors: The readings gs0..gs2 of N robots, shape (N, 3).

        Returns:
            A float32 array (N, 2) of left and right wheel speeds in rad/s, row for row equal
            to calling the controller on each row.

        Raises:
            InvalidArgumentError: The readings are not of shape (N, 3).
        """
        return self._wheel_speeds(_rows(ground_sensors, 3, "FollowLine")).astype(np.float32)

    def _wheel_speeds(self, readings: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        on_line = readings < self.threshold
        left_only = on_line[:, 0] & ~on_line[:, 1] & ~on_line[:, 2]
        right_only = on_line[:, 2] & ~on_line[:, 0] & ~on_line[:, 1]
        # +1: turn right (left wheel faster), -1: turn left, 0: straight on.
        direction = np.where(right_only, 1.0, np.where(left_only, -1.0, 0.0))
        wheel_speeds = np.empty((readings.shape[0], 2), dtype=np.float64)
        wheel_speeds[:, 0] = self.speed + direction * self.turn
        wheel_speeds[:, 1] = self.speed - direction * self.turn
        return wheel_speeds


class Explore:
    """The report's exploration controller of section 4.2.2, on the seed robot's Sharp sensors.

    The report drove the robot around the maze "with an algorithm similar to Alg. 2, with the
    robot turning around itself when it detects an obstacle in front"; this is that rule on the
    six Sharp GP2Y0A41SK0F sensors (volts, in the order front, back, left, right, left-front,
    right-front), where a higher voltage means a nearer wall:

    - a robot that is turning on the spot keeps turning the same way until the front sensor
      reads at most ``threshold``;
    - otherwise, when the front sensor reads above ``threshold`` it starts turning on the spot
      (wheels ``+-speed``) towards the more open side: the side whose left/right and diagonal
      sensors read less in total, a random side when they differ by less than ``tie`` volts;
    - otherwise Alg. 2's three-way rule on the two diagonal sensors: if only the right-front
      one reads above ``threshold`` it turns left (``speed - turn``, ``speed + turn``), if only
      the left-front one does it turns right, else it goes straight at ``speed``.

    A lower threshold in volts is a farther obstacle: 1.2 V is about 11 cm, 2.0 V about 6 cm
    (:func:`mazesim.sharp_volts_to_cm`). The controller keeps the spinning state of each robot
    and draws its random sides from its own seeded generator, so a run replays exactly.

    Attributes:
        threshold: Sharp reading in volts above which a sensor sees an obstacle.
        speed: Wheel speed in rad/s going straight, and of both wheels turning on the spot.
        turn: Wheel speed difference in rad/s when veering away from a side wall.
        tie: Difference in volts below which both sides are taken as equally open.

    Example:
        >>> controller = Explore(threshold=1.4, speed=3.14, seed=0)
        >>> controller([0.5, 0.5, 1.0, 1.0, 0.9, 0.9])
        (3.14, 3.14)
        >>> controller([0.5, 0.5, 1.0, 1.0, 0.9, 1.6])
        (1.57, 4.71)
        >>> controller([2.0, 0.5, 2.0, 0.5, 1.0, 0.5])
        (3.14, -3.14)
    """

    def __init__(
        self,
        threshold: float = 1.4,
        speed: float = 3.14,
        turn: float | None = None,
        tie: float = 0.2,
        seed: int = 0,
    ) -> None:
        """Creates the controller.

        Args:
            threshold: Obstacle threshold in volts (the report tried 1.2 to 2.0).
            speed: Wheel speed in rad/s (half the e-puck's maximum by default).
            turn: Speed difference in rad/s when veering; half of ``speed`` by default.
            tie: Sides closer than this in volts count as equally open (a random side is taken).
            seed: Seed of the random choice of side.
        """
        self.threshold = _bounded_number("threshold", threshold)
        self.speed = _bounded_number("speed", speed)
        self.turn = 0.5 * self.speed if turn is None else _bounded_number("turn", turn)
        self.tie = _bounded_number("tie", tie, least=0.0)
        self.seed = seed
        self.reset()

    def reset(self) -> None:
        """Forgets every robot's turning state and restarts the random generator."""
        self._rng = np.random.default_rng(self.seed)
        self._spin = np.zeros(0, dtype=np.int8)
        self._single_spin = np.zeros(1, dtype=np.int8)

    def __call__(self, distance_sensors: npt.ArrayLike) -> tuple[float, float]:
        """Computes the wheel speeds for one robot (the controller keeps its turning state).

        Args:
            distance_sensors: The six Sharp readings in volts: front, back, left, right,
                left-front, right-front.

        Returns:
            The (left, right) wheel speeds in rad/s.

        Raises:
            InvalidArgumentError: The readings are not of shape (6,).
        """
        names = "front, back, left, right, left-front, right-front"
        readings = _row(distance_sensors, 6, "Explore", names)
        wheel_speeds = self._wheel_speeds(readings.reshape(1, 6), self._single_spin)
        return float(wheel_speeds[0, 0]), float(wheel_speeds[0, 1])

    def batch(
        self, distance_sensors: npt.ArrayLike, mask: npt.ArrayLike | None = None
    ) -> npt.NDArray[np.float32]:
        """Computes the wheel speeds for many robots at once, each with its own turning state.

        The states are kept between calls; a call with a different number of robots starts
        them all afresh.

        Args:
            distance_sensors: The Sharp readings of N robots in volts, shape (N, 6).
            mask: (N,) the robots that act on these readings (all by default); the others'
                turning states stay as they were (their rows are computed but not meant to
                be used).

        Returns:
            A float32 array (N, 2) of left and right wheel speeds in rad/s.

        Raises:
            InvalidArgumentError: The readings are not of shape (N, 6), or a mask of another
                shape.
        """
        readings = _rows(distance_sensors, 6, "Explore")
        if self._spin.shape[0] != readings.shape[0]:
            self._spin = np.zeros(readings.shape[0], dtype=np.int8)
        if mask is None:
            return self._wheel_speeds(readings, self._spin).astype(np.float32)
        acting = self._robots_in(mask)
        spin = self._spin.copy()
        wheel_speeds = self._wheel_speeds(readings, spin)
        self._spin[acting] = spin[acting]
        return wheel_speeds.astype(np.float32)

    def reset_robots(self, mask: npt.ArrayLike) -> None:
        """Forgets the turning state of the robots in ``mask`` (N,) of the last batch."""
        self._spin[self._robots_in(mask)] = 0

    def _robots_in(self, mask: npt.ArrayLike) -> npt.NDArray[np.bool_]:
        """``mask`` as flags of the last batch's robots, refused when of another shape."""
        flags = np.asarray(mask, dtype=bool)
        if flags.shape != self._spin.shape:
            raise InvalidArgumentError(
                f"expected a mask of shape {self._spin.shape}, found {flags.shape}"
            )
        return flags

    def _wheel_speeds(
        self, readings: npt.NDArray[np.float64], spin: npt.NDArray[np.int8]
    ) -> npt.NDArray[np.float64]:
        """Wheel speeds (N, 2); updates ``spin`` (+1 clockwise, -1 anticlockwise, 0 none)."""
        blocked = readings[:, FRONT] > self.threshold
        spin[~blocked] = 0
        starting = blocked & (spin == 0)
        # Positive: the left side is nearer (reads more), so turn right (clockwise).
        left_minus_right = (readings[:, LEFT] + readings[:, LEFT_FRONT]) - (
            readings[:, RIGHT] + readings[:, RIGHT_FRONT]
        )
        coin = np.where(self._rng.random(readings.shape[0]) < 0.5, 1, -1)
        side = np.where(
            np.abs(left_minus_right) < self.tie, coin, np.where(left_minus_right > 0, 1, -1)
        )
        spin[starting] = side[starting]
        left_wall = readings[:, LEFT_FRONT] > self.threshold
        right_wall = readings[:, RIGHT_FRONT] > self.threshold
        # +1: veer right (left wheel faster), -1: veer left, 0: straight on.
        veer = np.where(left_wall & ~right_wall, 1.0, np.where(right_wall & ~left_wall, -1.0, 0.0))
        wheel_speeds = np.empty((readings.shape[0], 2), dtype=np.float64)
        wheel_speeds[:, 0] = self.speed + veer * self.turn
        wheel_speeds[:, 1] = self.speed - veer * self.turn
        spinning = spin != 0
        wheel_speeds[spinning, 0] = spin[spinning] * self.speed
        wheel_speeds[spinning, 1] = -spin[spinning] * self.speed
        return wheel_speeds
