"""Drives ahead at 3 rad/s for 2 s without a keyboard."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(3.0)
steps = 0
while robot.step(time_step) != -1 and robot.getTime() < 2.0:
    steps += 1
name = robot.getName().replace(" ", "_")
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{name}.json"), "w") as out:
    json.dump({"steps": steps}, out)
