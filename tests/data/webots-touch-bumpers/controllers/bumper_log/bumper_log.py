"""Stands still, logging each step the value of every bumper its controllerArgs name."""

import json
import os
import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
bumpers = {name: robot.getDevice(name) for name in sys.argv[1:]}
for bumper in bumpers.values():
    bumper.enable(time_step)
rows = []
while robot.step(time_step) != -1 and len(rows) < 60:
    rows.append({name: bumper.getValue() for name, bumper in bumpers.items()})
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump({"rows": rows}, out)
