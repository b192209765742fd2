"""Drives forward at 4 rad/s and notes each of its runs: when it started and its steps."""

import json
import math
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
for name in ("left wheel motor", "right wheel motor"):
    motor = robot.getDevice(name)
    motor.setPosition(math.inf)
    motor.setVelocity(4.0)
started = robot.getTime()
steps = 0
while robot.step(time_step) != -1:
    steps += 1
path = os.path.join(os.environ.get("SWARM_LOG", "."), f"forward_{robot.getName()}.json")
with open(path, "w") as out:
    json.dump({"started": started, "steps": steps, "ended": robot.getTime()}, out)
