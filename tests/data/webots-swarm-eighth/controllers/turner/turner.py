"""After its 20th step turns R1 to face -x with setSFRotation and moves R2 with setSFVec3f."""

import json
import os

from controller import Supervisor

robot = Supervisor()
time_step = int(robot.getBasicTimeStep())
steps = 0
log = {}
while robot.step(time_step) != -1 and steps < 40:
    steps += 1
    if steps == 20:
        robot.getFromDef("R1").getField("rotation").setSFRotation([0, 0, 1, 3.14159])
        robot.getFromDef("R2").getField("translation").setSFVec3f([0.5, 0.5, 0])
        log["r1_rotation"] = robot.getFromDef("R1").getField("rotation").getSFRotation()
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "turner.json"), "w") as out:
    json.dump(log, out)
