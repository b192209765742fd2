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
give the same class; Webots 8's ``DifferentialWheels``, the e-puck's class before R2018a, too
(:mod:`mazesim.webots.differential_wheels`). The e-puck's devices are simulated (see
:mod:`mazesim.webots.equipment` for the list), devices in the world's extension slots too; the
rest answers with Webots' values for a missing device. ``Robot.step`` returns -1 once the run's
time is up; a controller that steps again after that is stopped, as Webots stops it.
"""

from __future__ import annotations

import sys
from types import ModuleType

from mazesim.errors import _shown
from mazesim.webots.camera import Camera, CameraRecognitionObject
from mazesim.webots.devices import LED, Device, DistanceSensor, Motor, PositionSensor, _Sensor
from mazesim.webots.differential_wheels import DifferentialWheels
from mazesim.webots.field import Field
from mazesim.webots.inert import (
    Altimeter,
    AnsiCodes,
    Brake,
    Connector,
    ContactPoint,
    Display,
    Lidar,
    LidarPoint,
    Motion,
    Pen,
    Radar,
    RadarTarget,
    RangeFinder,
    Skin,
    Speaker,
    VacuumGripper,
)
from mazesim.webots.keyboard import Joystick, Keyboard, Mouse, MouseState
from mazesim.webots.radio_devices import Emitter, Receiver
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
from mazesim.webots.supervisor import Node, Supervisor

#: Webots' submodules, one per class as Webots names them (``controller.distance_sensor``...),
#: with the classes each gives.
SUBMODULE_CLASSES: dict[str, tuple[str, ...]] = {
    "accelerometer": ("Accelerometer",),
    "altimeter": ("Altimeter",),
    "ansi_codes": ("AnsiCodes",),
    "brake": ("Brake",),
    "camera": ("Camera", "CameraRecognitionObject"),
    "compass": ("Compass",),
    "connector": ("Connector",),
    "device": ("Device",),
    "display": ("Display",),
    "distance_sensor": ("DistanceSensor",),
    "emitter": ("Emitter",),
    "field": ("Field",),
    "gps": ("GPS",),
    "gyro": ("Gyro",),
    "inertial_unit": ("InertialUnit",),
    "joystick": ("Joystick",),
    "keyboard": ("Keyboard",),
    "led": ("LED",),
    "lidar": ("Lidar", "LidarPoint"),
    "light_sensor": ("LightSensor",),
    "motion": ("Motion",),
    "motor": ("Motor",),
    "mouse": ("Mouse", "MouseState"),
    "node": ("ContactPoint", "Node"),
    "pen": ("Pen",),
    "position_sensor": ("PositionSensor",),
    "radar": ("Radar", "RadarTarget"),
    "range_finder": ("RangeFinder",),
    "receiver": ("Receiver",),
    "robot": ("Robot",),
    "skin": ("Skin",),
    "speaker": ("Speaker",),
    "supervisor": ("Supervisor",),
    "touch_sensor": ("TouchSensor",),
    "vacuum_gripper": ("VacuumGripper",),
}
#: Webots' submodules of base classes that its package itself does not give: ``controller.sensor``
#: (``Sensor``, the base of every sampled device, which controllers import to annotate their
#: device wrappers: ``from controller.sensor import Sensor``).
BASE_SUBMODULE_CLASSES: dict[str, tuple[str, ...]] = {"sensor": ("Sensor",)}
Sensor = _Sensor
SUBMODULES = list(SUBMODULE_CLASSES) + list(BASE_SUBMODULE_CLASSES)

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
    "DifferentialWheels",
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


def _submodule(name: str, classes: tuple[str, ...]) -> ModuleType:
    """The submodule ``controller.<name>``, registered under this package's name, giving the
    package's own classes."""
    module = ModuleType(f"{__name__}.{name}", f"Webots' ``controller.{name}`` module.")
    module.__dict__.update({cls: globals()[cls] for cls in classes}, __all__=list(classes))
    sys.modules[module.__name__] = module
    return module


for _name, _classes in {**SUBMODULE_CLASSES, **BASE_SUBMODULE_CLASSES}.items():
    globals()[_name] = _submodule(_name, _classes)


def __getattr__(name: str) -> object:
    """A name the module lacks.

    Raises:
        AttributeError: Always, in the words of Webots' own module.
    """
    raise AttributeError(f"module 'controller' has no attribute {_shown(name)}")
