"""Webots 8's ``DifferentialWheels``, the e-puck's controller class before R2018a, on the
e-puck's wheel motors.

A controller of Webots 5 to 8 subclasses it (``class EPuck(DifferentialWheels)``) and drives
the wheels in speed units with ``setSpeed(left, right)``, reading encoders in encoder units;
Webots R2018a replaced the node by a Robot with two motors and position sensors. The numbers are
the world's ``DifferentialWheels`` node's fields (``speedUnit``, ``maxSpeed``,
``encoderResolution``, ``encoderNoise``), Webots 8's ``EPuck`` PROTO's for a robot whose node
does not say; the methods run on the robot's
:class:`~mazesim.webots.differential_drive.DifferentialDrive`, as the C library's
``<webots/differential_wheels.h>`` functions do (see that module for Webots' rules).
"""

from __future__ import annotations

from mazesim.webots.robot import Robot

__all__ = ["DifferentialWheels"]


class DifferentialWheels(Robot):
    """The e-puck as Webots 8's ``DifferentialWheels`` robot: a :class:`Robot` whose wheels
    turn at ``setSpeed`` speed units and whose encoders count from where ``setEncoders`` put
    them."""

    def setSpeed(self, left: float, right: float) -> None:
        """Turns the wheels at ``left`` and ``right`` speed units (``speedUnit`` rad/s each;
        Webots' error beyond ``maxSpeed``)."""
        self._equipment.differential_drive.setSpeed(left, right)

    def getLeftSpeed(self) -> float:
        """The left wheel's last ``setSpeed``, speed units (NaN before any)."""
        return self._equipment.differential_drive.getLeftSpeed()

    def getRightSpeed(self) -> float:
        """The right wheel's last ``setSpeed``, speed units (NaN before any)."""
        return self._equipment.differential_drive.getRightSpeed()

    def getMaxSpeed(self) -> float:
        """The node's ``maxSpeed``, rad/s (6.28 for Webots 8's EPuck)."""
        return self._equipment.differential_drive.getMaxSpeed()

    def getSpeedUnit(self) -> float:
        """The node's ``speedUnit``, rad/s a speed unit (0.00628 for Webots 8's EPuck)."""
        return self._equipment.differential_drive.getSpeedUnit()

    def enableEncoders(self, samplingPeriod: int) -> None:
        """Reads the encoders every ``samplingPeriod`` ms."""
        self._equipment.differential_drive.enableEncoders(samplingPeriod)

    def disableEncoders(self) -> None:
        """Stops reading the encoders."""
        self._equipment.differential_drive.disableEncoders()

    def getEncodersSamplingPeriod(self) -> int:
        """The encoders' sampling period, ms (0: disabled)."""
        return self._equipment.differential_drive.getEncodersSamplingPeriod()

    def getLeftEncoder(self) -> float:
        """The left encoder, encoder units (``encoderResolution`` a radian)."""
        return self._equipment.differential_drive.getLeftEncoder()

    def getRightEncoder(self) -> float:
        """The right encoder, encoder units (``encoderResolution`` a radian)."""
        return self._equipment.differential_drive.getRightEncoder()

    def setEncoders(self, left: float, right: float) -> None:
        """Sets the encoders to ``left`` and ``right`` units from now on."""
        self._equipment.differential_drive.setEncoders(left, right)
