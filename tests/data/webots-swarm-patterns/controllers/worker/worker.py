"""Drives forward at a speed set by its number (its customData) until its step returns -1."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
number = int(robot.getCustomData())
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(1.0 + number)
steps = 0
while robot.step(time_step) != -1:
    steps += 1
log = {"name": robot.getName(), "number": number, "steps": steps, "time": robot.getTime()}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
