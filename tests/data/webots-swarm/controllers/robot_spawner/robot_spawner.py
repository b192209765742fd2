"""A supervisor that imports two e-pucks a few steps in (unless ``SPAWN_NONE`` is set),
removes one of them later and then the world file's e-puck, and records what its scene tree
said of them."""

import json
import os

from controller import Supervisor

ROBOTS = [
    'DEF NEW_A E-puck { translation -0.6 -0.3 0 name "new-a" controller "cruise" '
    "camera_width 80 turretSlot [ Compass { } ] }",
    'DEF NEW_B E-puck { translation 0.2 -0.6 0 name "new-b" controller "cruise" }',
]

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
children = supervisor.getRoot().getField("children")
seen = {"count_before": children.getCount()}
spawn = "SPAWN_NONE" not in os.environ
steps = 0
while supervisor.step(time_step) != -1:
    steps += 1
    if steps == 5 and spawn:
        for text in ROBOTS:
            children.importMFNodeFromString(-1, text)
        seen["count_with"] = children.getCount()
        new_a = supervisor.getFromDef("NEW_A")
        seen["new_a_type"] = new_a.getTypeName()
        seen["new_a_found_by_id"] = supervisor.getFromId(new_a.getId()) is new_a
        seen["new_a_at_import"] = new_a.getPosition()
    if steps == 40 and spawn:
        seen["new_a_later"] = supervisor.getFromDef("NEW_A").getPosition()
        supervisor.getFromDef("NEW_B").remove()
        seen["count_after"] = children.getCount()
        seen["new_b_gone"] = supervisor.getFromDef("NEW_B") is None
    if steps == 60 and spawn:
        supervisor.getFromDef("FIRST").remove()
    if steps == 80:
        break
with open(os.path.join(os.environ["SWARM_LOG"], "spawner.json"), "w") as log:
    json.dump(seen, log)
