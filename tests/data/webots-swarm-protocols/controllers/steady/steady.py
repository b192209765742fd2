"""Drives forward for 80 steps and notes its steps and clock."""

import json
import math
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
for name in ("left wheel motor", "right wheel motor"):
    motor = robot.getDevice(name)
    motor.setPosition(math.inf)
    motor.setVelocity(2.0)
steps = 0
while robot.step(time_step) != -1:
    steps += 1
    if steps == 80:
        break
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "steady.json"), "w") as out:
    json.dump({"steps": steps, "time": robot.getTime()}, out)
