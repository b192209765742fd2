"""Reads a GPS of resolution 0.1 m and a compass of resolution 0.5 on the turret."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
gps = robot.getDevice("gps")
compass = robot.getDevice("compass")
gps.enable(time_step)
compass.enable(time_step)
robot.step(time_step)
log = {"gps": gps.getValues(), "compass": compass.getValues()}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
