"""Drives forward at the speed of its first argument (3 rad/s without one) for 50 steps."""

import json
import os
import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
speed = float(sys.argv[1]) if len(sys.argv) > 1 else 3.0
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(speed)
steps = 0
while robot.step(time_step) != -1 and steps < 50:
    steps += 1
for motor in (left, right):
    motor.setVelocity(0.0)
robot.step(time_step)
log = {"name": robot.getName(), "steps": steps, "argv": sys.argv[1:]}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
