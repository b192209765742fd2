"""Webots' Python ``controller`` module, for the e-puck and the e-puck2, on mazesim.

``mazesim webots run`` installs this module as ``controller``, so an unmodified Webots
controller's ``from controller import Robot`` (or ``from controller import *``) resolves here::

    from controller import Robot

    robot = Robot()
    time_step = int(robot.getBasicTimeStep())
    left = robot.getDevice("left wheel motor")
    left.setPosition(float("inf"))
    ps0 = robot.getDevice("ps0")
    ps0.enable(time_step)
    while robot.step(time_step) != -1:
        left.setVelocity(3.0 if ps0.getValue() < 80 else -3.0)

Every class of Webots' module can be imported. The e-puck's devices are simulated (see
:mod:`mazesim.webots.equipment` for the list), devices in the world's extension slots too; the
rest answers with Webots' values for a missing device. ``Robot.step`` returns -1 once the run's
time is up; a controller that steps again after that is stopped, as Webots stops it.
"""

from __future__ import annotations

from mazesim.webots.camera import Camera, CameraRecognitionObject
from mazesim.webots.devices import LED, Device, DistanceSensor, Motor, PositionSensor
from mazesim.webots.inert import (
    Altimeter,
    AnsiCodes,
    Brake,
    Connector,
    ContactPoint,
    Display,
    Emitter,
    Lidar,
    LidarPoint,
    Motion,
    Pen,
    Radar,
    RadarTarget,
    RangeFinder,
    Receiver,
    Skin,
    Speaker,
    VacuumGripper,
)
from mazesim.webots.keyboard import Joystick, Keyboard, Mouse, MouseState
from mazesim.webots.robot import ControllerStopped, Robot
from mazesim.webots.sensors import (
    GPS,
    Accelerometer,
    Compass,
    Gyro,
    InertialUnit,
    LightSensor,
    TouchSensor,
)
from mazesim.webots.supervisor import Field, Node, Supervisor

__all__ = [
    "GPS",
    "LED",
    "Accelerometer",
    "Altimeter",
    "AnsiCodes",
    "Brake",
    "Camera",
    "CameraRecognitionObject",
    "Compass",
    "Connector",
    "ContactPoint",
    "ControllerStopped",
    "Device",
    "Display",
    "DistanceSensor",
    "Emitter",
    "Field",
    "Gyro",
    "InertialUnit",
    "Joystick",
    "Keyboard",
    "Lidar",
    "LidarPoint",
    "LightSensor",
    "Motion",
    "Motor",
    "Mouse",
    "MouseState",
    "Node",
    "Pen",
    "PositionSensor",
    "Radar",
    "RadarTarget",
    "RangeFinder",
    "Receiver",
    "Robot",
    "Skin",
    "Speaker",
    "Supervisor",
    "TouchSensor",
    "VacuumGripper",
]
