"""Asks the robot its name, model, custom data and devices."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
before = robot.getCustomData()
robot.setCustomData("changed")
robot.step(time_step)
count = robot.getNumberOfDevices()
names = [robot.getDeviceByIndex(i).getName() for i in range(count)]
log = {
    "before": before,
    "after": robot.getCustomData(),
    "model": robot.getModel(),
    "count": count,
    "names": names,
    "time": robot.getTime(),
    "step": robot.getBasicTimeStep(),
}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
