"""A supervisor that finds every robot among the root's children, reads each one's translation
field at step 10 and sets its rotation field so that it faces the arena's centre; at step 50 it
reads the translations again."""

import json
import math
import os

from controller import Supervisor

turner = Supervisor()
time_step = int(turner.getBasicTimeStep())
children = turner.getRoot().getField("children")
robots = []
for index in range(children.getCount()):
    node = children.getMFNode(index)
    if node.getBaseTypeName() == "Robot" and node.getDef() != "TURNER":
        robots.append(node)
log = {
    "names": [r.getField("name").getSFString() for r in robots],
    "at10": {},
    "set": {},
    "at50": {},
}
steps = 0
while turner.step(time_step) != -1 and steps < 50:
    steps += 1
    if steps == 10:
        for node in robots:
            name = node.getField("name").getSFString()
            x, y, z = node.getField("translation").getSFVec3f()
            log["at10"][name] = [x, y]
            node.getField("rotation").setSFRotation([0.0, 0.0, 1.0, math.atan2(-y, -x)])
            log["set"][name] = node.getField("rotation").getSFRotation()
for node in robots:
    log["at50"][node.getField("name").getSFString()] = node.getField("translation").getSFVec3f()[:2]
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "turner.json"), "w") as out:
    json.dump(log, out)
