"""Drives straight on at 4 rad/s for 40 steps, noting its GPS position and compass heading at
the first step and the last."""

import json
import math
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
gps = robot.getDevice("gps")
compass = robot.getDevice("compass")
gps.enable(time_step)
compass.enable(time_step)
for name in ("left wheel motor", "right wheel motor"):
    motor = robot.getDevice(name)
    motor.setPosition(float("inf"))
    motor.setVelocity(4.0)
log = {}
steps = 0
while robot.step(time_step) != -1:
    steps += 1
    north = compass.getValues()
    heading = math.atan2(north[0], north[1])
    if steps == 1:
        log["first"] = [*gps.getValues(), heading]
    if steps == 40:
        log["last"] = [*gps.getValues(), heading]
        for name in ("left wheel motor", "right wheel motor"):
            robot.getDevice(name).setVelocity(0.0)
    if steps == 41:
        break
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
