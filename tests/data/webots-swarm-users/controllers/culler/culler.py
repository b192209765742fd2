"""A supervisor that removes the robot TARGET after its 15th step and notes the root's children
before and after and whether getFromDef still finds it."""

import json
import os

from controller import Supervisor

robot = Supervisor()
time_step = int(robot.getBasicTimeStep())
children = robot.getRoot().getField("children")
log = {}
steps = 0
while robot.step(time_step) != -1 and steps < 40:
    steps += 1
    if steps == 15:
        log["count_before"] = children.getCount()
        robot.getFromDef("TARGET").remove()
    if steps == 16:
        log["count_after"] = children.getCount()
        log["gone"] = robot.getFromDef("TARGET") is None
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "culler.json"), "w") as out:
    json.dump(log, out)
