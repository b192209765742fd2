"""Wheel encoders and odometry for barcode reading, for one robot or a batch.

:class:`Odometry` dead-reckons N robots from their wheel encoder angles and gives where each
robot's barcode sensor is, in a frame fixed at the robot's pose when the odometry was (re)set.
:class:`WheelEncoders` stands in for the encoders of robots stepped in a
:class:`mazesim.BatchSimulator`, which reports none: it integrates the wheel speeds applied each
step (the actions clamped to the motor limit), quantised to the encoder resolution as
:attr:`mazesim.Simulator.encoders` is. Like real encoders, both know nothing of wheels spinning
against a wall.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from mazesim._core import RobotProfile
from mazesim._sizes import number_array
from mazesim.errors import InvalidArgumentError, _shown

__all__ = ["ENCODER_RESOLUTION", "Odometry", "WheelEncoders", "barcode_sensor_index"]

#: Encoder resolution of the e-puck and the report's robot, radians (Webots: 2 pi / 1000).
ENCODER_RESOLUTION = 2.0 * math.pi / 1000.0


def barcode_sensor_index(robot: RobotProfile) -> int:
    """The ground sensor that reads barcodes: the one nearest the robot's centre line.

    That is ``gs1`` on the e-puck and the single ``gs`` of the ``seed`` robot; the first of
    equally near ones wins, as the simulator's crossing ground truth chooses.

    Raises:
        InvalidArgumentError: The robot has no ground sensor.
    """
    positions = np.asarray(robot.ground_sensor_positions(), dtype=np.float64).reshape(-1, 2)
    if len(positions) == 0:
        raise InvalidArgumentError(
            f"robot {_shown(robot.name)} has no ground sensor to read barcodes with"
        )
    return int(np.argmin(np.abs(positions[:, 1])))


def _as_rows(values: npt.ArrayLike, count: int, what: str) -> npt.NDArray[np.float64]:
    rows = number_array(values, what)
    if rows.shape == (2,) and count == 1:
        rows = rows.reshape(1, 2)
    if rows.shape != (count, 2):
        raise InvalidArgumentError(f"expected {what} of shape ({count}, 2), found {rows.shape}")
    return rows


def _as_mask(mask: npt.ArrayLike | None, count: int) -> npt.NDArray[np.bool_]:
    if mask is None:
        return np.ones(count, dtype=bool)
    flags = np.asarray(mask, dtype=bool)
    if flags.shape != (count,):
        raise InvalidArgumentError(f"expected a mask of shape ({count},), found {flags.shape}")
    return flags


class WheelEncoders:
    """Wheel angle sensors of N robots in a batch, from the wheel speeds applied each step.

    Args:
        robot: The robot profile (its motor limit).
        num_envs: Number of robots.
        control_step_ms: The batch's control step in milliseconds.
        resolution: Encoder resolution in radians (0 for none).
    """

    def __init__(
        self,
        robot: RobotProfile,
        num_envs: int,
        control_step_ms: float,
        resolution: float = ENCODER_RESOLUTION,
    ) -> None:
        if num_envs < 1:
            raise InvalidArgumentError(f"expected at least one robot, found {num_envs}")
        if not 0.0 < control_step_ms < math.inf:
            raise InvalidArgumentError(
                f"expected a positive, finite control step in ms, found {control_step_ms}"
            )
        if not 0.0 <= resolution < math.inf:
            raise InvalidArgumentError(
                f"expected a resolution in radians of 0 or more, finite, found {resolution}"
            )
        self.max_wheel_speed = float(robot.max_wheel_speed)
        self.num_envs = int(num_envs)
        self.control_step = float(control_step_ms) / 1000.0
        self.resolution = float(resolution)
        self._angles = np.zeros((self.num_envs, 2), dtype=np.float64)

    def step(self, actions: npt.ArrayLike) -> None:
        """Adds one control step of wheel speeds ``actions`` (N, 2), rad/s, left then right."""
        speeds = _as_rows(number_array(actions, "actions", np.float32), self.num_envs, "actions")
        self._angles += np.clip(speeds, -self.max_wheel_speed, self.max_wheel_speed) * (
            self.control_step
        )

    def reset(self, mask: npt.ArrayLike | None = None) -> None:
        """Sets the angles of the robots in ``mask`` (all by default) back to zero."""
        self._angles[_as_mask(mask, self.num_envs)] = 0.0

    @property
    def values(self) -> npt.NDArray[np.float64]:
        """(N, 2) wheel angles in radians, quantised to the resolution."""
        if self.resolution <= 0.0:
            return self._angles.copy()
        return np.round(self._angles / self.resolution) * self.resolution


class Odometry:
    """Dead reckoning of N robots from wheel encoders, placing each robot's barcode sensor.

    Each robot's frame starts at its pose of the first :meth:`update` after construction or
    :meth:`reset`: origin at the robot's centre, x forward. Between two updates the robot is
    taken to move on an arc (midpoint heading).

    Args:
        robot: The robot profile (wheel radius, axle length, ground sensor positions).
        num_envs: Number of robots.
        sensor_index: The ground sensor to place; by default :func:`barcode_sensor_index`.
    """

    def __init__(self, robot: RobotProfile, num_envs: int = 1, sensor_index: int | None = None):
        if num_envs < 1:
            raise InvalidArgumentError(f"expected at least one robot, found {num_envs}")
        sensors = np.asarray(robot.ground_sensor_positions(), dtype=np.float64).reshape(-1, 2)
        index = barcode_sensor_index(robot) if sensor_index is None else int(sensor_index)
        if not 0 <= index < len(sensors):
            raise InvalidArgumentError(
                f"expected a ground sensor index in [0, {len(sensors)}), found {sensor_index}"
            )
        self.num_envs = int(num_envs)
        self.wheel_radius = float(robot.wheel_radius)
        self.axle_length = float(robot.axle_length)
        self.sensor_offset = sensors[index].copy()
        self._poses = np.zeros((self.num_envs, 3), dtype=np.float64)
        self._encoders = np.zeros((self.num_envs, 2), dtype=np.float64)
        self._fresh = np.ones(self.num_envs, dtype=bool)

    def reset(self, mask: npt.ArrayLike | None = None) -> None:
        """Restarts the frames of the robots in ``mask`` (all by default) at their next update."""
        flags = _as_mask(mask, self.num_envs)
        self._fresh |= flags
        self._poses[flags] = 0.0

    def update(self, encoders: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Advances the robots to new encoder angles.

        Args:
            encoders: (N, 2) wheel angles in radians, left then right (a pair for one robot).

        Returns:
            (N, 2) positions of the barcode sensors in metres, each in its robot's frame.
        """
        angles = _as_rows(encoders, self.num_envs, "encoders")
        turned = angles - self._encoders
        turned[self._fresh] = 0.0
        self._fresh[:] = False
        self._encoders = angles.copy()
        forward = self.wheel_radius * 0.5 * (turned[:, 0] + turned[:, 1])
        rotation = self.wheel_radius * (turned[:, 1] - turned[:, 0]) / self.axle_length
        heading = self._poses[:, 2] + 0.5 * rotation
        self._poses[:, 0] += forward * np.cos(heading)
        self._poses[:, 1] += forward * np.sin(heading)
        self._poses[:, 2] += rotation
        return self.sensor_positions()

    @property
    def poses(self) -> npt.NDArray[np.float64]:
        """(N, 3) dead-reckoned poses x, y, yaw of the robots' centres."""
        return self._poses.copy()

    def sensor_positions(self) -> npt.NDArray[np.float64]:
        """(N, 2) positions of the barcode sensors in their robots' frames."""
        cos_yaw = np.cos(self._poses[:, 2])
        sin_yaw = np.sin(self._poses[:, 2])
        offset_x, offset_y = self.sensor_offset
        positions = np.empty((self.num_envs, 2), dtype=np.float64)
        positions[:, 0] = self._poses[:, 0] + cos_yaw * offset_x - sin_yaw * offset_y
        positions[:, 1] = self._poses[:, 1] + sin_yaw * offset_x + cos_yaw * offset_y
        return positions
