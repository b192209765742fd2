"""Imports in the style of Webots R2023b and later: one submodule per class, beside the package.

Test controller of mazesim's Webots interoperability (tests/test_webots_api.py). Every check
that fails raises, so the run's exit status says whether the classes are the same objects
whichever way they are imported.
"""

import controller
import controller.distance_sensor
from controller import DistanceSensor as PackageDistanceSensor
from controller import Node as PackageNode
from controller.camera import Camera
from controller.device import Device
from controller.distance_sensor import DistanceSensor
from controller.field import Field
from controller.keyboard import Keyboard
from controller.led import LED
from controller.motor import Motor
from controller.node import Node
from controller.position_sensor import PositionSensor
from controller.robot import Robot
from controller.supervisor import Supervisor

robot = Robot()
timestep = int(robot.getBasicTimeStep())

assert DistanceSensor is PackageDistanceSensor is controller.distance_sensor.DistanceSensor
assert Node is PackageNode is controller.Node
assert issubclass(Supervisor, Robot) and isinstance(robot, controller.Robot)
assert Field.SF_VEC3F != Field.SF_ROTATION

proximity = [robot.getDevice(f"ps{i}") for i in range(8)]
assert all(isinstance(sensor, DistanceSensor) for sensor in proximity)
assert all(isinstance(sensor, Device) for sensor in proximity)
assert all(isinstance(sensor, controller.DistanceSensor) for sensor in proximity)
left_motor = robot.getDevice("left wheel motor")
right_motor = robot.getDevice("right wheel motor")
assert isinstance(left_motor, Motor) and isinstance(right_motor, controller.motor.Motor)
assert isinstance(left_motor.getPositionSensor(), PositionSensor)
assert isinstance(robot.getDevice("camera"), Camera)
assert isinstance(robot.getDevice("led0"), LED)
assert isinstance(robot.getKeyboard(), Keyboard)

for sensor in proximity:
    sensor.enable(timestep)
left_motor.setPosition(float("inf"))
right_motor.setPosition(float("inf"))
while robot.step(timestep) != -1:
    front = max(proximity[0].getValue(), proximity[7].getValue())
    left_motor.setVelocity(-2.0 if front > 100 else 4.0)
    right_motor.setVelocity(4.0)
print("submodules: the same classes")
