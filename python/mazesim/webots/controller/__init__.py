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

Every class of Webots' module can be imported, from the package or, as Webots R2023b and later
ship it, from its own submodule (``from controller.distance_sensor import DistanceSensor``); both
give the same class. The e-puck's devices are simulated (see
:mod:`mazesim.webots.equipment` for the list), devices in the world's extension slots too; the
rest answers with Webots' values for a missing device. ``Robot.step`` returns -1 once the run's
time is up; a controller that steps again after that is stopped, as Webots stops it.
"""

from __future__ import annotations

from mazesim.errors import UnknownNameError
from mazesim.webots.controller.accelerometer import Accelerometer
from mazesim.webots.controller.altimeter import Altimeter
from mazesim.webots.controller.ansi_codes import AnsiCodes
from mazesim.webots.controller.brake import Brake
from mazesim.webots.controller.camera import Camera, CameraRecognitionObject
from mazesim.webots.controller.compass import Compass
from mazesim.webots.controller.connector import Connector
from mazesim.webots.controller.device import Device
from mazesim.webots.controller.display import Display
from mazesim.webots.controller.distance_sensor import DistanceSensor
from mazesim.webots.controller.emitter import Emitter
from mazesim.webots.controller.field import Field
from mazesim.webots.controller.gps import GPS
from mazesim.webots.controller.gyro import Gyro
from mazesim.webots.controller.inertial_unit import InertialUnit
from mazesim.webots.controller.joystick import Joystick
from mazesim.webots.controller.keyboard import Keyboard
from mazesim.webots.controller.led import LED
from mazesim.webots.controller.lidar import Lidar, LidarPoint
from mazesim.webots.controller.light_sensor import LightSensor
from mazesim.webots.controller.motion import Motion
from mazesim.webots.controller.motor import Motor
from mazesim.webots.controller.mouse import Mouse, MouseState
from mazesim.webots.controller.node import ContactPoint, Node
from mazesim.webots.controller.pen import Pen
from mazesim.webots.controller.position_sensor import PositionSensor
from mazesim.webots.controller.radar import Radar, RadarTarget
from mazesim.webots.controller.range_finder import RangeFinder
from mazesim.webots.controller.receiver import Receiver
from mazesim.webots.controller.robot import Robot
from mazesim.webots.controller.skin import Skin
from mazesim.webots.controller.speaker import Speaker
from mazesim.webots.controller.supervisor import Supervisor
from mazesim.webots.controller.touch_sensor import TouchSensor
from mazesim.webots.controller.vacuum_gripper import VacuumGripper
from mazesim.webots.robot import ControllerStopped

#: The submodules, one per class as Webots names them (``controller.distance_sensor``...).
SUBMODULES = (
    "accelerometer altimeter ansi_codes brake camera compass connector device display "
    "distance_sensor emitter field gps gyro inertial_unit joystick keyboard led lidar "
    "light_sensor motion motor mouse node pen position_sensor radar range_finder receiver robot "
    "skin speaker supervisor touch_sensor vacuum_gripper"
).split()

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


def __getattr__(name: str) -> object:
    """Refuses, saying what to use instead, the classes of Webots before R2018a that the module
    does not have (``from controller import DifferentialWheels``).

    Raises:
        UnknownNameError: ``DifferentialWheels``, the node of the e-puck before R2018a, which
            Webots deprecated with "Please use the Robot node instead with two HingeJoint,
            RotationalMotor and PositionSensor nodes".
        AttributeError: Any other name the module lacks.
    """
    if name == "DifferentialWheels":
        raise UnknownNameError(
            "controller.DifferentialWheels: the e-puck of Webots before R2018a, which Webots "
            "deprecated and mazesim does not have; the e-puck is a Robot with two motors: "
            "robot = Robot(), robot.getDevice('left wheel motor') and 'right wheel motor', "
            "setPosition(float('inf')) then setVelocity(rad/s) for setSpeed (speed units of "
            "0.00628 rad/s: setVelocity(0.00628 * speed)), and the encoders 'left wheel "
            "sensor' and 'right wheel sensor' in radians"
        )
    raise AttributeError(f"module 'controller' has no attribute {name!r}")
