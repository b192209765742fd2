"""The only robot of its world, a supervisor without a body: imports two e-pucks a few steps
in, the world's first, and records where their nodes are then and later."""

import json
import os

from controller import Supervisor

ROBOTS = [
    'DEF NEW_A E-puck { translation -0.6 -0.3 0 name "new-a" controller "cruise" }',
    'DEF NEW_B E-puck { translation 0.2 0.4 0 rotation 0 0 1 3.1416 name "new-b" '
    'controller "cruise" }',
]

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
children = supervisor.getRoot().getField("children")
seen = {}
steps = 0
while supervisor.step(time_step) != -1:
    steps += 1
    if steps == 5:
        for text in ROBOTS:
            children.importMFNodeFromString(-1, text)
        seen["new_a_at_import"] = supervisor.getFromDef("NEW_A").getPosition()
    if steps == 40:
        seen["new_a_later"] = supervisor.getFromDef("NEW_A").getPosition()
        seen["new_b_later"] = supervisor.getFromDef("NEW_B").getPosition()
    if steps == 80:
        break
with open(os.path.join(os.environ["SWARM_LOG"], "importer.json"), "w") as log:
    json.dump(seen, log)
