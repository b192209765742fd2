"""Takes the robot DEF DOOMED out of the world at step 30 with Node.remove()."""

import json
import os

from controller import Supervisor

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
seen = {}
steps = 0
while supervisor.step(time_step) != -1 and supervisor.getTime() < 3.0:
    steps += 1
    if steps == 30:
        supervisor.getFromDef("DOOMED").remove()
        seen["gone"] = supervisor.getFromDef("DOOMED") is None
        seen["names"] = [
            supervisor.getRoot().getField("children").getMFNode(i).getTypeName()
            for i in range(supervisor.getRoot().getField("children").getCount())
        ]
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "warden.json"), "w") as out:
    json.dump(seen, out)
