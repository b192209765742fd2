"""Drives forward until its front sensors read above 300, then stands; notes its model, its
highest front reading and where it stopped."""

import json
import math
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
sensors = [robot.getDevice(f"ps{i}") for i in (0, 7)]
for sensor in sensors:
    sensor.enable(time_step)
wheels = [robot.getDevice(n) for n in ("left wheel motor", "right wheel motor")]
for wheel in wheels:
    wheel.setPosition(math.inf)
    wheel.setVelocity(4.0)
log = {"model": robot.getModel(), "max_speed": wheels[0].getMaxVelocity(), "peak": 0.0}
steps = stopped = 0
while robot.step(time_step) != -1:
    steps += 1
    front = max(s.getValue() for s in sensors)
    log["peak"] = max(log["peak"], front)
    if front > 300 and not stopped:
        stopped = steps
        for wheel in wheels:
            wheel.setVelocity(0.0)
    if steps == 250:
        break
log["stopped"] = stopped
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
