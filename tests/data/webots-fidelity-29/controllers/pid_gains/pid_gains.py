"""Turns each wheel to 3 rad by position control: the left motor with a softer P gain set by
setControlPID(2, 0, 0), the right with the E-puck's default controlPID (10, 0, 0); logs both
encoders after every step."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
left_sensor = left.getPositionSensor()
right_sensor = right.getPositionSensor()
left_sensor.enable(time_step)
right_sensor.enable(time_step)
left.setControlPID(2.0, 0.0, 0.0)
left.setPosition(3.0)
right.setPosition(3.0)
angles = []
while robot.step(time_step) != -1 and len(angles) < 40:
    angles.append([left_sensor.getValue(), right_sensor.getValue()])
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump({"angles": angles}, out)
