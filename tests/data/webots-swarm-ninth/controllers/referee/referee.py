"""Notes where the crate (DEF CRATE) is after each step."""

import json
import os

from controller import Supervisor

robot = Supervisor()
time_step = int(robot.getBasicTimeStep())
crate = robot.getFromDef("CRATE")
track = []
while robot.step(time_step) != -1 and robot.getTime() < 4.0 - 1e-9:
    track.append(list(crate.getPosition()))
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "referee.json"), "w") as out:
    json.dump({"track": track}, out)
