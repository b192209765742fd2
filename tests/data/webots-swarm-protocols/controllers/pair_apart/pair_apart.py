"""Drives at the wheel speed of its first argument (3 rad/s without one) for 30 steps, then
stands; notes its largest proximity reading at the start."""

import json
import math
import os
import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
speed = float(sys.argv[1]) if len(sys.argv) > 1 else 3.0
sensors = [robot.getDevice(f"ps{i}") for i in range(8)]
for sensor in sensors:
    sensor.enable(time_step)
wheels = [robot.getDevice(n) for n in ("left wheel motor", "right wheel motor")]
for wheel in wheels:
    wheel.setPosition(math.inf)
    wheel.setVelocity(speed)
steps = 0
first = None
while robot.step(time_step) != -1:
    steps += 1
    if first is None:
        first = [s.getValue() for s in sensors]
    if steps == 30:
        for wheel in wheels:
            wheel.setVelocity(0.0)
    if steps == 40:
        break
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump({"first": first}, out)
