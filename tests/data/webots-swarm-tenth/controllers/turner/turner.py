"""A supervisor that turns TURNED to face +y (keeping its place) after its 15th step, and
logs its position then and after its 30th."""

import json
import os

from controller import Supervisor

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
node = supervisor.getFromDef("TURNED")
steps = 0
at_turn = None
while supervisor.step(time_step) != -1 and steps < 30:
    steps += 1
    if steps == 15:
        at_turn = list(node.getPosition())
        node.getField("rotation").setSFRotation([0.0, 0.0, 1.0, 1.5707963267948966])
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "turner.json"), "w") as out:
    json.dump({"at_turn": at_turn, "end": list(node.getPosition())}, out)
