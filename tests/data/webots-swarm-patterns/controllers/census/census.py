"""A supervisor that finds the robots nested in groups and transforms, says where they are,
and puts two of them back at the origin of their parent's frame."""

import json
import os

from controller import Supervisor

NAMES = ("FRONT", "BACK", "LONER")

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())


def where() -> dict:
    found = {}
    for name in NAMES:
        node = supervisor.getFromDef(name)
        if node is None:
            found[name] = None
            continue
        orientation = node.getOrientation()
        found[name] = {
            "position": node.getPosition(),
            "heading": [orientation[0], orientation[3]],
            "parent": node.getParentNode().getTypeName(),
            "translation": node.getField("translation").getSFVec3f(),
            "rotation": node.getField("rotation").getSFRotation(),
        }
    return found


supervisor.step(time_step)
seen = {"start": where(), "root_count": supervisor.getRoot().getField("children").getCount()}
steps = 1
while supervisor.step(time_step) != -1 and steps < 50:
    steps += 1
seen["end"] = where()
for name in ("FRONT", "LONER"):
    supervisor.getFromDef(name).getField("translation").setSFVec3f([0.0, 0.0, 0.0])
supervisor.step(time_step)
seen["put_back"] = where()
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "census.json"), "w") as log:
    json.dump(seen, log)
