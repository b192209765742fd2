"""Drives ahead at 5 rad/s on a battery of 1 J, logging the battery and the left encoder."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
robot.batterySensorEnable(time_step)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
encoder = robot.getDevice("left wheel sensor")
encoder.enable(time_step)
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(5.0)
rows = []
while robot.step(time_step) != -1 and len(rows) < 6:
    rows.append([robot.batterySensorGetValue(), encoder.getValue()])
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump({"rows": rows}, out)
