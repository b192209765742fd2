"""The part of Webots' Python ``controller`` module that an e-puck controller uses.

``mazesim webots run`` installs this module as ``controller``, so an unmodified Webots
controller's ``from controller import Robot`` resolves here::

    from controller import Robot

    robot = Robot()
    time_step = int(robot.getBasicTimeStep())
    left = robot.getDevice("left wheel motor")
    left.setPosition(float("inf"))
    ps0 = robot.getDevice("ps0")
    ps0.enable(time_step)
    while robot.step(time_step) != -1:
        left.setVelocity(3.0 if ps0.getValue() < 80 else -3.0)

Devices (the e-puck's names): ``left wheel motor`` / ``right wheel motor`` (:class:`Motor`),
``ps0``..``ps7`` and ``gs0``..``gs2`` (:class:`DistanceSensor`), ``left wheel sensor`` /
``right wheel sensor`` (:class:`PositionSensor`), ``led0``..``led9`` (:class:`LED`).
``Robot.step`` returns -1 once the run's time is up; a controller that steps again after that is
stopped, as Webots stops it.
"""

from __future__ import annotations

import math
import sys
import warnings
from typing import ClassVar

from mazesim.errors import InvalidArgumentError
from mazesim.webots import simulation as _simulations
from mazesim.webots.devices import LED, Device, DistanceSensor, Motor, PositionSensor

__all__ = [
    "LED",
    "ControllerStopped",
    "Device",
    "DistanceSensor",
    "Motor",
    "PositionSensor",
    "Robot",
]

#: Number of LEDs of the e-puck (led0..led9; led8 is the body LED, led9 the front LED).
LED_COUNT = 10


class ControllerStopped(BaseException):
    """Raised in a controller that calls ``Robot.step`` after it returned -1: the run is over.

    It derives from ``BaseException`` so that a controller's ``except Exception`` does not
    swallow it; ``mazesim webots run`` treats it as the controller's normal end.
    """


class Robot:
    """The e-puck the controller drives (only one per controller process, as in Webots)."""

    EVENT_QUIT = -1
    EVENT_NO_EVENT = 0
    MODE_SIMULATION = 0
    created: ClassVar[Robot | None] = None
    _simulation: _simulations.RobotSimulation
    _devices: dict[str, Device]
    _motors: list[Motor]
    _sensors: list[DistanceSensor | PositionSensor]

    def __init__(self) -> None:
        """Attaches to the prepared simulation and finds the e-puck's devices.

        Raises:
            InvalidArgumentError: No simulation was prepared (see :func:`mazesim.webots.prepare`).
        """
        simulation = _simulations.current()
        earlier = Robot.created
        if earlier is not None and earlier._simulation is simulation:
            print(
                "Error: only one Robot instance can be created per controller process.",
                file=sys.stderr,
            )
            self._simulation = simulation
            self._devices = earlier._devices
            self._motors = earlier._motors
            self._sensors = earlier._sensors
            return
        Robot.created = self
        self._simulation = simulation
        profile = simulation.simulator.robot
        encoders = [
            PositionSensor(name, simulation, side)
            for side, name in enumerate(("left wheel sensor", "right wheel sensor"))
        ]
        self._motors = [
            Motor(name, simulation, side, encoders[side])
            for side, name in enumerate(("left wheel motor", "right wheel motor"))
        ]
        for motor, encoder in zip(self._motors, encoders):
            encoder._motor = motor
        proximity = [
            DistanceSensor(name, simulation, i, ground=False)
            for i, name in enumerate(profile.distance_sensor_names)
        ]
        ground = [
            DistanceSensor(name, simulation, i, ground=True)
            for i, name in enumerate(profile.ground_sensor_names)
        ]
        self._sensors = [*proximity, *ground, *encoders]
        leds = [LED(f"led{i}", simulation) for i in range(LED_COUNT)]
        devices: list[Device] = [*self._motors, *self._sensors, *leds]
        self._devices = {device.getName(): device for device in devices}

    # --- the robot -------------------------------------------------------------------------

    def getBasicTimeStep(self) -> float:
        """The world's basic time step in milliseconds (``WorldInfo.basicTimeStep``)."""
        return self._simulation.basic_time_step_ms

    def getTime(self) -> float:
        """Simulated seconds since the start."""
        return float(self._simulation.simulator.time)

    def getName(self) -> str:
        """The robot's name, ``"e-puck"``."""
        return "e-puck"

    def getModel(self) -> str:
        """The robot's model, as Webots' E-puck PROTO names it."""
        return "GCtronic e-puck"

    def getSupervisor(self) -> bool:
        """False: mazesim runs no supervisor."""
        return False

    def step(self, duration: float | None = None) -> int:
        """Runs the simulation for ``duration`` ms (a whole number of basic steps, rounded up).

        Args:
            duration: Milliseconds to simulate; by default one basic time step.

        Returns:
            0, or -1 when the run's time is up (the simulation does not advance then).

        Raises:
            InvalidArgumentError: ``duration`` is negative or not a number.
            ControllerStopped: ``step`` was called again after it returned -1.
        """
        simulation = self._simulation
        basic = simulation.basic_time_step_ms
        if duration is None:
            duration = basic
        duration = float(duration)
        if not (math.isfinite(duration) and duration >= 0.0):
            raise InvalidArgumentError(
                f"Robot.step expects a duration in ms >= 0, found {duration!r}"
            )
        if simulation.ended:
            raise ControllerStopped("the run is over: Robot.step returned -1 before")
        for _ in range(max(1, math.ceil(duration / basic - 1e-9))):
            if simulation.time_is_up:
                simulation.ended = True
                return -1
            left, right = simulation.simulator.encoders
            simulation.advance(
                self._motors[0]._wheel_speed(left), self._motors[1]._wheel_speed(right)
            )
            for sensor in self._sensors:
                sensor._after_step()
        return 0

    # --- devices ---------------------------------------------------------------------------

    def getDevice(self, name: str) -> Device | None:
        """The device of that name, or None (with Webots' message) if the e-puck has none."""
        device = self._devices.get(name)
        if device is None:
            print(f'Device "{name}" was not found on robot "{self.getName()}"', file=sys.stderr)
        return device

    def getNumberOfDevices(self) -> int:
        """How many devices the robot has."""
        return len(self._devices)

    def getDeviceByIndex(self, index: int) -> Device:
        """The device at ``index`` (0 <= index < getNumberOfDevices())."""
        return list(self._devices.values())[index]

    def _deprecated(self, getter: str, name: str) -> Device | None:
        warnings.warn(
            f"DEPRECATION: Robot.{getter} is deprecated, please use Robot.getDevice instead.",
            DeprecationWarning,
            stacklevel=3,
        )
        return self.getDevice(name)

    def getMotor(self, name: str) -> Device | None:
        """Deprecated in Webots: use :meth:`getDevice`."""
        return self._deprecated("getMotor", name)

    def getDistanceSensor(self, name: str) -> Device | None:
        """Deprecated in Webots: use :meth:`getDevice`."""
        return self._deprecated("getDistanceSensor", name)

    def getPositionSensor(self, name: str) -> Device | None:
        """Deprecated in Webots: use :meth:`getDevice`."""
        return self._deprecated("getPositionSensor", name)

    def getLED(self, name: str) -> Device | None:
        """Deprecated in Webots: use :meth:`getDevice`."""
        # Webots' own message spells it getLed.
        return self._deprecated("getLed", name)
