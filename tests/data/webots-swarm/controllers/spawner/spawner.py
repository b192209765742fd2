"""A supervisor that puts a crate in the pusher's path a few steps in (or the node its
``controllerArgs`` give, and its DEF name), takes it away later, and records what its scene
tree said of it."""

import json
import os
import sys

from controller import Supervisor

CRATE = (
    "DEF CRATE Solid { translation -0.09 0 0.05 children [ Shape { geometry DEF CRATE_BOX "
    'Box { size 0.02 0.3 0.1 } } ] name "crate" boundingObject USE CRATE_BOX }'
)

NODE, NAME = (sys.argv[1], sys.argv[2]) if len(sys.argv) > 2 else (CRATE, "CRATE")

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
children = supervisor.getRoot().getField("children")
seen = {"count_before": children.getCount()}
steps = 0
while supervisor.step(time_step) != -1:
    steps += 1
    if steps == 3:
        children.importMFNodeFromString(-1, NODE)
        seen["count_with"] = children.getCount()
        seen["crate"] = supervisor.getFromDef(NAME).getPosition()
    if steps == 40:
        supervisor.getFromDef(NAME).remove()
        seen["count_after"] = children.getCount()
        seen["gone"] = supervisor.getFromDef(NAME) is None
    if steps == 62:
        break
with open(os.path.join(os.environ["SWARM_LOG"], "spawner.json"), "w") as log:
    json.dump(seen, log)
