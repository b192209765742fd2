"""The drive of Webots' ``DifferentialWheels`` node (Webots 5 to R2018a, the e-puck's node
before R2018a made it a Robot with motors): its fields, its wheel speeds in speed units and its
built-in encoders. Python's :class:`~mazesim.webots.differential_wheels.DifferentialWheels` and
the C library's ``wb_differential_wheels_*`` functions (calls over the link,
:mod:`mazesim.webots.native_calls`) both run on it, so both behave alike by construction.

What it does, read from Webots' sources (Apache-2.0; facts only): the controller library's
``src/controller/c/differential_wheels.c`` (R2019a) and the node's ``WbDifferentialWheels.cpp``
(R2018b):

- ``set_speed(left, right)`` turns the wheels at ``left * speedUnit`` and ``right *
  speedUnit`` rad/s. The library prints ``wb_differential_wheels_set_speed(l,r) overflows
  maxSpeed/speedUnit`` when ``left * speedUnit * 0.99999`` (or right's) exceeds ``maxSpeed``
  (rad/s), and sends the speed anyway; the node's ``qBound`` leaves it as it is (its result is
  not used). A NaN is refused with the library's error. ``get_left_speed`` answers the last
  speed set, NaN before any.
- ``get_max_speed`` and ``get_speed_unit`` answer the node's ``maxSpeed`` and ``speedUnit``.
- The encoders: at every step the node adds ``encoderResolution`` times each wheel's turn (rad)
  to its count, times a uniform factor in ``[1 - n, 1 + n]`` when ``encoderNoise`` n is
  positive, and adds nothing when ``encoderNoise`` is negative; the controller reads the counts
  as they were at its sampling period's last end (0 before), and ``set_encoders`` sets them.
- A ``DifferentialWheels`` node's defaults: ``speedUnit 1`` (0.1 in a file of a version before
  6), ``maxSpeed 10``, ``encoderResolution -1``, ``encoderNoise -1``. Webots 8's ``EPuck``
  PROTO (as projects ship copies of it) writes ``speedUnit 0.00628``, ``maxSpeed 6.28``,
  ``encoderResolution 159.23``, ``encoderNoise 0``: these serve a robot whose node does not
  say (an EPuck PROTO node, a project's own PROTO, an R2018a-or-later E-puck).

mazesim turns the e-puck's wheels at most at its motors' 6.28 rad/s: a speed beyond, which
Webots' node would turn the wheels at, is held there.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from mazesim.webots.devices import _print_error, _Sensor, noise_stream, sampling_period

if TYPE_CHECKING:
    from mazesim.webots.simulation import RobotSimulation

__all__ = ["EPUCK_WHEELS", "DifferentialDrive", "WheelsNode", "wheels_node"]


@dataclass(frozen=True)
class WheelsNode:
    """The fields of a ``DifferentialWheels`` node the controller's side reads.

    Attributes:
        speed_unit: rad/s a speed unit of ``setSpeed`` (``speedUnit``).
        max_speed: The wheels' top speed, rad/s (``maxSpeed``).
        encoder_resolution: Encoder counts a radian of wheel turn (``encoderResolution``).
        encoder_noise: The encoders' relative noise (``encoderNoise``); negative: they do not
            count.
    """

    speed_unit: float
    max_speed: float
    encoder_resolution: float
    encoder_noise: float


#: Webots 8's EPuck PROTO's fields.
EPUCK_WHEELS = WheelsNode(
    speed_unit=0.00628, max_speed=6.28, encoder_resolution=159.23, encoder_noise=0.0
)
#: A ``DifferentialWheels`` node's defaults (Webots' reference manual, 7.0 to 8).
NODE_DEFAULTS = WheelsNode(
    speed_unit=1.0, max_speed=10.0, encoder_resolution=-1.0, encoder_noise=-1.0
)
#: The world file versions whose ``speedUnit`` 1 reads as 0.1 (Webots 6 changed the default).
_OLD_SPEED_UNIT = 0.1


def wheels_node(fields: Mapping[str, float], version: str | None) -> WheelsNode:
    """The fields of a ``DifferentialWheels`` node that writes ``fields`` (by Webots' names;
    the others take the node's defaults), in a file of ``version`` (its ``#VRML_SIM`` tag)."""
    speed_unit = fields.get("speedUnit", NODE_DEFAULTS.speed_unit)
    if speed_unit == 1.0 and _before_webots_6(version):
        speed_unit = _OLD_SPEED_UNIT
    return WheelsNode(
        speed_unit=speed_unit,
        max_speed=fields.get("maxSpeed", NODE_DEFAULTS.max_speed),
        encoder_resolution=fields.get("encoderResolution", NODE_DEFAULTS.encoder_resolution),
        encoder_noise=fields.get("encoderNoise", NODE_DEFAULTS.encoder_noise),
    )


def _before_webots_6(version: str | None) -> bool:
    """Whether a ``#VRML_SIM`` tag names a release before Webots 6 (``V5.10.0``)."""
    if version is None or not version.startswith("V"):
        return False
    major = version[1:].split(".", 1)[0]
    return major.isdigit() and int(major) < 6


class Encoders(_Sensor):
    """The node's two encoders, one sampled sensor as in Webots: their counts at the last end
    of the sampling period (0 before any); not a device of the robot's."""

    _api = "wb_differential_wheels"

    def __init__(self, simulation: RobotSimulation, node: WheelsNode) -> None:
        super().__init__("encoders", simulation)
        self._node = node
        self._value = [0.0, 0.0]
        #: The counts when the wheels were at the angles ``_angles``.
        self._counts = [0.0, 0.0]
        self._angles = simulation.wheel_angles()
        self._noise = (
            noise_stream(simulation, "differential wheels encoders")
            if node.encoder_noise > 0.0
            else None
        )
        simulation.reset_listeners.append(self._rebase)

    def _rebase(self) -> None:
        """The world's reset put the wheels back: counting goes on from where they are."""
        self._counts = self._counted()
        self._angles = self._simulation.wheel_angles()

    def _counted(self) -> list[float]:
        """The counts now: each wheel's turn since ``_angles`` in counts (none when the node's
        ``encoderNoise`` is negative)."""
        if self._node.encoder_noise < 0.0:
            return list(self._counts)
        now = self._simulation.wheel_angles()
        resolution = self._node.encoder_resolution
        return [c + resolution * (a - b) for c, a, b in zip(self._counts, now, self._angles)]

    def _after_step(self) -> None:
        if self._noise is not None:
            # Noisy counts are summed step by step, each turn times its own factor, as the node
            # sums them.
            now = self._simulation.wheel_angles()
            noise = self._node.encoder_noise
            for side in (0, 1):
                factor = 1.0 - noise + float(self._noise.random()) * noise * 2.0
                turn = (now[side] - self._angles[side]) * factor
                self._counts[side] += self._node.encoder_resolution * turn
            self._angles = now
        super()._after_step()

    def _read(self) -> list[float]:
        return self._counted()

    def _checked_period(self, samplingPeriod: int) -> int | None:
        return sampling_period(samplingPeriod, "wb_differential_wheels_enable_encoders")

    def _warn_disabled(self, function: str) -> None:
        if self._period_ms == 0 and not self._warned_disabled:
            self._warned_disabled = True
            _print_error(
                f"Error: wb_differential_wheels_{function}() called for a disabled device! "
                "Please use: wb_differential_wheels_enable_encoders()."
            )

    def count(self, side: int, function: str) -> float:
        """Encoder ``side``'s count as last read (``function`` names the call in Webots'
        message for a disabled read)."""
        return float(self._reading(function)[side])

    def set(self, left: float, right: float) -> None:
        """Sets the counts to ``left`` and ``right`` from the wheels' angles now."""
        self._counts = [left, right]
        self._angles = self._simulation.wheel_angles()
        self._value = [left, right]


class DifferentialDrive:
    """The controller's side of a ``DifferentialWheels`` node, on the e-puck's wheel motors.

    Args:
        simulation: The robot's simulation.
        motors: The left and right wheel motors.
        node: The node's fields.
    """

    def __init__(
        self, simulation: RobotSimulation, motors: Sequence[Any], node: WheelsNode
    ) -> None:
        self.node = node
        self._motors = motors
        self._speeds = [math.nan, math.nan]
        self.encoders = Encoders(simulation, node)

    def setSpeed(self, left: float, right: float) -> None:
        """Turns the wheels at ``left`` and ``right`` speed units."""
        speeds = [float(left), float(right)]
        if any(math.isnan(s) for s in speeds):
            _print_error(
                "Error: wb_differential_wheels_set_speed(): invalid NaN value passed as argument."
            )
            return
        unit, top = self.node.speed_unit, self.node.max_speed
        if any(s * unit * 0.99999 > top for s in speeds):
            _print_error(
                f"Error: wb_differential_wheels_set_speed({speeds[0]:g},{speeds[1]:g}) overflows "
                f"maxSpeed/speedUnit: {top:g}/{unit:g}={top / unit:g}."
            )
        self._speeds = speeds
        for motor, speed in zip(self._motors, speeds):
            limit = motor.getMaxVelocity()
            motor.setPosition(math.inf)
            motor.setVelocity(max(-limit, min(limit, speed * unit)))

    def getLeftSpeed(self) -> float:
        """The left wheel's last speed set, speed units (NaN before any)."""
        return self._speeds[0]

    def getRightSpeed(self) -> float:
        """The right wheel's last speed set, speed units (NaN before any)."""
        return self._speeds[1]

    def getMaxSpeed(self) -> float:
        """The node's ``maxSpeed``, rad/s."""
        return self.node.max_speed

    def getSpeedUnit(self) -> float:
        """The node's ``speedUnit``, rad/s a speed unit."""
        return self.node.speed_unit

    def enableEncoders(self, samplingPeriod: int) -> None:
        """Reads the encoders every ``samplingPeriod`` ms."""
        self.encoders.enable(samplingPeriod)

    def disableEncoders(self) -> None:
        """Stops reading the encoders; they keep their last reading."""
        self.encoders.disable()

    def getEncodersSamplingPeriod(self) -> int:
        """The encoders' sampling period, ms (0: disabled)."""
        return int(self.encoders.getSamplingPeriod())

    def getLeftEncoder(self) -> float:
        """The left encoder's count at its last reading."""
        return self.encoders.count(0, "get_left_encoder")

    def getRightEncoder(self) -> float:
        """The right encoder's count at its last reading."""
        return self.encoders.count(1, "get_right_encoder")

    def setEncoders(self, left: float, right: float) -> None:
        """Sets the encoders' counts to ``left`` and ``right``."""
        counts = [float(left), float(right)]
        if any(math.isnan(c) for c in counts):
            _print_error(
                "Error: wb_differential_wheels_set_encoders(): invalid NaN value passed as "
                "argument."
            )
            return
        self.encoders.set(*counts)
