"""The motors and position sensors of a robot's own joints that mazesim's body does not have.

A robot's motors beyond the e-puck's two wheels (the four wheels of Webots' tutorial robot, an
arm's or a gripper's joints, a plain ``Robot`` that is not an e-puck) are devices in Webots,
found by their names. mazesim's body has two wheels, so such a motor moves nothing: its joint
turns freely, as an unloaded joint does, by the motor's command (at its velocity in velocity
control, towards its target in position control, within ``maxVelocity``), and a
``PositionSensor`` of the same joint reads that angle (or length, of a ``LinearMotor``). A
controller that drives them therefore runs, instead of stopping at the ``None`` a missing
device would give; a warning at the run's start says each such motor moves nothing.

The import lists a joint's devices one after the other (its ``device`` field, in file order),
at the joint's place: a position sensor belongs to the motor listed just before or just after
it at the same place and axes (:func:`pair_joints`).
"""

from __future__ import annotations

import sys
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from mazesim.errors import _shown
from mazesim.webots.devices import Motor, PositionSensor
from mazesim.webots.last_commands import POSITION_GAIN, PositionControl
from mazesim.webots.node_types import node_type

if TYPE_CHECKING:
    from mazesim.webots.simulation import RobotSimulation

__all__ = ["JointMotor", "JointPositionSensor", "LinearJointMotor", "pair_joints"]

#: Webots' default ``maxVelocity`` of a RotationalMotor (rad/s) and a LinearMotor (m/s).
DEFAULT_MAX_VELOCITY = 10.0
#: Webots' default ``maxTorque`` (N m) and ``maxForce`` (N).
DEFAULT_MAX_TORQUE = 10.0


def _number(fields: Mapping[str, Any], name: str, default: float) -> float:
    value = fields.get(name, default)
    return float(value) if isinstance(value, (int, float)) else default


def _gains(fields: Mapping[str, Any]) -> tuple[float, float, float]:
    """The node's ``controlPID`` (Webots' default 10 0 0 where it is missing or malformed)."""
    value = fields.get("controlPID")
    if isinstance(value, Sequence) and len(value) == 3:
        if all(isinstance(v, (int, float)) for v in value):
            p, i, d = (float(v) for v in value)
            if p > 0.0 and i >= 0.0 and d >= 0.0:
                return p, i, d
    return POSITION_GAIN, 0.0, 0.0


class JointMotor(Motor):
    """A ``RotationalMotor`` of a joint mazesim does not simulate: it takes every command of
    Webots' motor API, and its joint turns freely as commanded; it moves nothing."""

    def __init__(
        self, name: str, simulation: RobotSimulation, fields: Mapping[str, Any] | None = None
    ) -> None:
        fields = fields or {}
        # Not the wheel motor's own set-up (it reads the e-puck's wheels): the joint's.
        self._name = name
        self._simulation = simulation
        self._max_velocity = abs(_number(fields, "maxVelocity", DEFAULT_MAX_VELOCITY))
        self._min_position = _number(fields, "minPosition", 0.0)
        self._max_position = _number(fields, "maxPosition", 0.0)
        self._max_torque = _number(fields, self._force_field, DEFAULT_MAX_TORQUE)
        self._available_torque = self._max_torque
        self._control = PositionControl(_gains(fields))
        self._sensor: PositionSensor | None = None  # type: ignore[assignment]
        self._angle = 0.0
        self._target_position = 0.0
        self._velocity = self._max_velocity
        self._acceleration = -1.0
        self._set_points = (0.0, self._max_velocity)
        self._warned_clamp = False
        kind = "LinearMotor" if self.getType() == self.LINEAR else "RotationalMotor"
        print(
            f"mazesim: warning: robot {_shown(simulation.robot_name)}: the {kind} device "
            f"{_shown(name)} in the world drives a joint "
            "mazesim does not simulate: it takes every command and its joint turns freely, but it "
            "moves nothing",
            file=sys.stderr,
        )

    _force_field = "maxTorque"

    def _restart(self) -> None:
        """As Webots' reset: position control at the joint's start, at ``maxVelocity``."""
        self._angle = 0.0
        self._target_position = 0.0
        self._velocity = self._max_velocity
        self._control.set_gains(self._control.gains)

    def _turn(self, dt: float) -> None:
        """Turns the joint for one basic step of ``dt`` seconds, within its limits (Webots
        has none when ``minPosition`` equals ``maxPosition``)."""
        self._angle += self._wheel_speed(self._angle) * dt
        if self._min_position < self._max_position:
            self._angle = min(self._max_position, max(self._min_position, self._angle))

    def getMinPosition(self) -> float:
        """The joint's ``minPosition`` (0 with ``maxPosition``: no limit)."""
        return self._min_position

    def getMaxPosition(self) -> float:
        """The joint's ``maxPosition`` (0 with ``minPosition``: no limit)."""
        return self._max_position

    def getPositionSensor(self) -> PositionSensor:
        """The position sensor of the same joint (None when it has none)."""
        return self._sensor  # type: ignore[return-value]


class LinearJointMotor(JointMotor):
    """A ``LinearMotor`` of a joint mazesim does not simulate (see :class:`JointMotor`)."""

    _node_type = node_type("LINEAR_MOTOR")
    _force_field = "maxForce"

    def getType(self) -> int:
        """``Motor.LINEAR``."""
        return self.LINEAR


class JointPositionSensor(PositionSensor):
    """A ``PositionSensor`` of a joint mazesim does not simulate: it reads its motor's joint
    (0 for a joint without a motor, which nothing turns)."""

    def __init__(self, name: str, simulation: RobotSimulation) -> None:
        super().__init__(name, simulation, side=0)

    def _angle(self) -> float:
        motor = self._motor
        return motor._angle if isinstance(motor, JointMotor) else 0.0

    def getType(self) -> int:
        """Its motor's type (``Motor.ROTATIONAL`` without one)."""
        motor = self._motor
        return motor.getType() if motor is not None else self.ROTATIONAL


def _place(entry: Mapping[str, Any]) -> tuple[Any, Any]:
    return (entry.get("translation"), entry.get("axes"))


def pair_joints(entries: Sequence[tuple[Mapping[str, Any], Any]]) -> list[JointMotor]:
    """Gives each :class:`JointPositionSensor` among ``entries`` (import entry, device, in the
    import's order) the :class:`JointMotor` listed just before or just after it at the same
    place and axes, and returns the joint motors, each of which turns at every basic step."""
    motors: list[JointMotor] = []
    for index, (entry, device) in enumerate(entries):
        if isinstance(device, JointMotor):
            motors.append(device)
        if not isinstance(device, JointPositionSensor):
            continue
        for other in (index - 1, index + 1):
            if not 0 <= other < len(entries):
                continue
            near_entry, near = entries[other]
            if (
                isinstance(near, JointMotor)
                and near._sensor is None
                and _place(near_entry) == _place(entry)
            ):
                near._sensor = device
                device._motor = near
                break
    return motors
