"""Webots 8's ``DifferentialWheels``, the e-puck's controller class before R2018a, on the
e-puck's wheel motors and sensors.

A controller of Webots 6 to 8 subclasses it (``class EPuck(DifferentialWheels)``) and drives
the wheels in speed units with ``setSpeed(left, right)``, reading encoders in encoder units;
Webots R2018a replaced the node by a Robot with two motors and position sensors. The numbers are
the e-puck's ``DifferentialWheels`` fields in Webots 8's ``EPuck`` node (``speedUnit 0.00628``
rad/s, ``maxSpeed 1000``, ``encoderResolution 159.23`` units a radian), the ones the C
library's ``<webots/differential_wheels.h>`` uses (``capi/src/differential_wheels.c``).
"""

from __future__ import annotations

import math
from typing import Any

from mazesim.webots.robot import Robot

__all__ = ["DifferentialWheels"]

#: The e-puck's wheel speed unit, rad/s (Webots 8's EPuck ``speedUnit``).
SPEED_UNIT = 0.00628
#: The e-puck's top wheel speed in speed units (Webots 8's EPuck ``maxSpeed``).
MAX_SPEED = 1000.0
#: Encoder units a radian of wheel turn (Webots 8's EPuck ``encoderResolution``).
ENCODER_RESOLUTION = 159.23
_SIDES = ("left", "right")


class DifferentialWheels(Robot):
    """The e-puck as Webots 8's ``DifferentialWheels`` robot: a :class:`Robot` whose wheels
    turn at ``setSpeed`` speed units (0.00628 rad/s each, at most 1000) and whose encoders
    count 159.23 units a radian from where ``setEncoders`` put them."""

    def __init__(self) -> None:
        super().__init__()
        self._speeds = [0.0, 0.0]
        self._encoder_offsets = [0.0, 0.0]

    def _wheel(self, kind: str, side: int) -> Any:
        """The ``left``/``right wheel motor`` or ``sensor`` (None, with Webots' message, on a
        robot without it)."""
        return self.getDevice(f"{_SIDES[side]} wheel {kind}")

    def setSpeed(self, left: float, right: float) -> None:
        """Turns the wheels at ``left`` and ``right`` speed units (clamped to +-1000)."""
        for side, speed in enumerate((float(left), float(right))):
            self._speeds[side] = max(-MAX_SPEED, min(MAX_SPEED, speed)) if speed == speed else speed
            motor = self._wheel("motor", side)
            if motor is not None:
                motor.setPosition(math.inf)
                motor.setVelocity(self._speeds[side] * SPEED_UNIT)

    def getLeftSpeed(self) -> float:
        """The left wheel's last ``setSpeed``, speed units."""
        return self._speeds[0]

    def getRightSpeed(self) -> float:
        """The right wheel's last ``setSpeed``, speed units."""
        return self._speeds[1]

    def getMaxSpeed(self) -> float:
        """1000 speed units."""
        return MAX_SPEED

    def getSpeedUnit(self) -> float:
        """0.00628 rad/s a speed unit."""
        return SPEED_UNIT

    def enableEncoders(self, samplingPeriod: int) -> None:
        """Reads both wheel sensors every ``samplingPeriod`` ms."""
        for side in (0, 1):
            sensor = self._wheel("sensor", side)
            if sensor is not None:
                sensor.enable(samplingPeriod)

    def disableEncoders(self) -> None:
        """Stops reading the wheel sensors."""
        for side in (0, 1):
            sensor = self._wheel("sensor", side)
            if sensor is not None:
                sensor.disable()

    def getEncodersSamplingPeriod(self) -> int:
        """The wheel sensors' sampling period, ms (0: disabled)."""
        sensor = self._wheel("sensor", 0)
        return 0 if sensor is None else int(sensor.getSamplingPeriod())

    def _raw_encoder(self, side: int) -> float:
        """The encoder before its offset: 0 before the first reading."""
        sensor = self._wheel("sensor", side)
        angle = math.nan if sensor is None else float(sensor.getValue())
        return 0.0 if math.isnan(angle) else angle * ENCODER_RESOLUTION

    def getLeftEncoder(self) -> float:
        """The left encoder, encoder units (159.23 a radian)."""
        return self._raw_encoder(0) - self._encoder_offsets[0]

    def getRightEncoder(self) -> float:
        """The right encoder, encoder units (159.23 a radian)."""
        return self._raw_encoder(1) - self._encoder_offsets[1]

    def setEncoders(self, left: float, right: float) -> None:
        """Sets the encoders to ``left`` and ``right`` units from now on."""
        self._encoder_offsets = [
            self._raw_encoder(0) - float(left),
            self._raw_encoder(1) - float(right),
        ]
