"""A supervisor that reads each e-puck's name and customData field every step."""

import json
import os

from controller import Supervisor

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
seen = {}
steps = 0
while supervisor.step(time_step) != -1 and steps < 10:
    steps += 1
    for index in range(4):
        node = supervisor.getFromDef(f"E{index}")
        name = node.getField("name").getSFString()
        seen.setdefault(name, []).append(node.getField("customData").getSFString())
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "roll_call.json"), "w") as out:
    json.dump(seen, out)
