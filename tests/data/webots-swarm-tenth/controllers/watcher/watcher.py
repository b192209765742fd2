"""A supervisor reading LEFT_BOT and RIGHT_BOT by DEF name after 20 steps."""

import json
import os

from controller import Supervisor

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
steps = 0
while supervisor.step(time_step) != -1 and steps < 20:
    steps += 1
found = {}
for name in ("LEFT_BOT", "RIGHT_BOT"):
    node = supervisor.getFromDef(name)
    found[name] = [node.getField("name").getSFString(), list(node.getPosition())]
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "watcher.json"), "w") as out:
    json.dump(found, out)
