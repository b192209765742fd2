"""A referee that counts, step by step, the contact points of robots A, B and C
(getContactPoints() of each node, descendants left out) and notes the first step with any and
the points' places."""

import json
import os

from controller import Supervisor

robot = Supervisor()
time_step = int(robot.getBasicTimeStep())
nodes = {name: robot.getFromDef(name) for name in ("A", "B", "C")}
log = {name: {"steps_in_contact": 0, "first": None, "points": []} for name in nodes}
steps = 0
while robot.step(time_step) != -1 and steps < 90:
    steps += 1
    for name, node in nodes.items():
        points = node.getContactPoints()
        if points:
            entry = log[name]
            entry["steps_in_contact"] += 1
            if entry["first"] is None:
                entry["first"] = steps
                entry["points"] = [list(p.getPoint()) for p in points]
                entry["at"] = list(node.getPosition())
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "referee.json"), "w") as out:
    json.dump(log, out)
