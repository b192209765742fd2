"""Reads the robot's battery sensor while standing still."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
robot.batterySensorEnable(time_step)
levels = []
while robot.step(time_step) != -1 and len(levels) < 5:
    levels.append(robot.batterySensorGetValue())
log = {"levels": levels, "period": robot.batterySensorGetSamplingPeriod()}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
