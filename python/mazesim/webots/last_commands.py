"""What a robot's wheel motors do once its controller has ended.

Webots keeps a motor's last commands in the motor node (``WbMotor``'s target position and
target velocity), and nothing resets them when the robot's controller ends: the controller's
library sends the commands set before its end with ``wb_robot_cleanup`` (a step of 0 ms), the
robot then notes only that its controller has terminated (``WbRobot``,
``C_ROBOT_CLIENT_EXIT_NOTIFY``), and the world goes on stepping the other robots. So a wheel
under velocity control keeps turning at its last velocity, and one under position control keeps
turning towards its last target, after its controller exits or crashes; one that dies
without ``wb_robot_cleanup`` (killed, or crashed in native code) leaves the commands its last
``wb_robot_step`` sent (Webots' source, src/webots/nodes/WbMotor.cpp and
src/webots/nodes/WbRobot.cpp, and src/controller/c/robot.c's ``wb_robot_cleanup``).

One rule gives a wheel's speed, for the controller's own steps (:class:`~mazesim.webots.devices.
Motor`) and after its end in a world run (:class:`Coasting`, in the world's process).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

__all__ = ["POSITION_GAIN", "Coasting", "PositionControl", "WheelCommand", "motor_speed"]

#: Proportional gain of Webots' motor position control (Motor.controlPID default 10 0 0).
POSITION_GAIN = 10.0


def motor_speed(
    target_position: float,
    velocity: float,
    max_velocity: float,
    angle: float,
    control: float | None = None,
) -> float:
    """A wheel's speed (rad/s) for the next step: ``velocity`` under velocity control (an
    infinite ``target_position``), else the position control's towards ``target_position``
    from ``angle`` (rad), at most ``velocity``; never beyond ``max_velocity``. The position
    control's output is ``control`` when given (:class:`PositionControl`), else its
    proportional term at the default gain."""
    if math.isinf(target_position):
        speed = velocity if target_position > 0 else -velocity
        return max(-max_velocity, min(max_velocity, speed))
    limit = min(abs(velocity), max_velocity)
    output = POSITION_GAIN * (target_position - angle) if control is None else control
    return max(-limit, min(limit, output))


class PositionControl:
    """A motor's PID position control as Webots computes it each basic step
    (``WbMotor::computeCurrentDynamicVelocity``): ``P e + I sum(e dt) + D (e - e_last) / dt``
    with ``e`` the target minus the position, the previous error starting at 0; setting the
    gains (the ``controlPID`` field, ``setControlPID``) clears the integral and the previous
    error (``WbMotor::updateControlPID``)."""

    def __init__(self, gains: tuple[float, float, float] = (POSITION_GAIN, 0.0, 0.0)) -> None:
        self.gains = gains
        self.integral = 0.0
        self.previous_error = 0.0

    def set_gains(self, gains: tuple[float, float, float]) -> None:
        """New gains; the integral and the previous error start again from 0."""
        self.gains = gains
        self.integral = 0.0
        self.previous_error = 0.0

    def output(self, error: float, dt: float) -> float:
        """The velocity (rad/s) the control asks for an ``error`` (rad) over a step of ``dt``
        seconds, before the motor's velocity limit."""
        p, i, d = self.gains
        if i == 0.0 and d == 0.0:
            return p * error
        self.integral += error * dt
        derivative = (error - self.previous_error) / dt
        self.previous_error = error
        return p * error + i * self.integral + d * derivative


@dataclass(frozen=True)
class WheelCommand:
    """A wheel motor's commands as its controller left them, and where the wheel stood.

    Attributes:
        target_position: The target (rad), infinite under velocity control.
        velocity: The velocity (rad/s), the speed limit of position control.
        max_velocity: The motor's ``maxVelocity``.
        angle: The wheel's angle (rad) when the controller ended.
        gain: The proportional gain of its position control (``controlPID``'s first).
        powered: Whether the motor has torque to drive (``setAvailableTorque`` not 0).
    """

    target_position: float
    velocity: float
    max_velocity: float
    angle: float
    gain: float = POSITION_GAIN
    powered: bool = True

    def speed(self) -> float:
        """The wheel's speed for the next step (0 without torque)."""
        if not self.powered:
            return 0.0
        control = self.gain * (self.target_position - self.angle)
        return motor_speed(
            self.target_position, self.velocity, self.max_velocity, self.angle, control
        )


class Coasting:
    """The robots whose controllers have ended, each one's wheels driven by the commands its
    controller left (:class:`WheelCommand`, left wheel first)."""

    def __init__(self) -> None:
        self._wheels: dict[int, tuple[WheelCommand, ...]] = {}

    def start(self, index: int, commands: Sequence[WheelCommand]) -> None:
        """Robot ``index``'s controller ended leaving ``commands`` (none: it stands still)."""
        if len(commands) == 2:
            self._wheels[index] = tuple(commands)

    def stop(self, index: int) -> None:
        """Robot ``index`` coasts no more (a new controller drives it, or it was removed)."""
        self._wheels.pop(index, None)

    def wheels(self, dt: float) -> dict[int, tuple[float, float]]:
        """Each coasting robot's wheel speeds for the next step of ``dt`` seconds; the wheels'
        angles advance by that step."""
        speeds = {}
        for index, commands in self._wheels.items():
            left, right = (command.speed() for command in commands)
            speeds[index] = (left, right)
            self._wheels[index] = tuple(
                replace(command, angle=command.angle + speed * dt)
                for command, speed in zip(commands, (left, right))
            )
        return speeds
