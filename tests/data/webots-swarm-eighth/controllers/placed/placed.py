"""Drives towards the ring's centre at 2 rad/s for 30 steps, noting its name and steps."""

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
while robot.step(time_step) != -1 and log["steps"] < 30:
    log["steps"] += 1
left.setVelocity(0.0)
right.setVelocity(0.0)
robot.step(time_step)
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
