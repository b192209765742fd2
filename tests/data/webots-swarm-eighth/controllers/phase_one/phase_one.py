"""Drives ahead at 2 rad/s, noting its steps in phase_one.json when the world ends it."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(2.0)
log = {"steps": 0, "start": robot.getTime()}
while robot.step(time_step) != -1:
    log["steps"] += 1
log["end"] = robot.getTime()
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "phase_one.json"), "w") as out:
    json.dump(log, out)
