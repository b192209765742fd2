"""An imported e-puck that drives straight on at the speed of its first controller argument."""

import json
import os
import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
speed = float(sys.argv[1])
for name in ("left wheel motor", "right wheel motor"):
    motor = robot.getDevice(name)
    motor.setPosition(float("inf"))
    motor.setVelocity(speed)
steps = 0
while robot.step(time_step) != -1:
    steps += 1
log = {"argv": sys.argv[1:], "steps": steps, "time": robot.getTime()}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
