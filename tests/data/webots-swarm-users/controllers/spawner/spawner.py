"""A supervisor that imports two e-pucks running "pinger" at its 10th and 20th steps, at the end
of the root's children, each with its own controllerArgs, and counts the root's children."""

import json
import os

from controller import Supervisor

robot = Supervisor()
time_step = int(robot.getBasicTimeStep())
children = robot.getRoot().getField("children")
log = {"count_before": children.getCount(), "counts": []}
steps = 0
while robot.step(time_step) != -1 and steps < 40:
    steps += 1
    if steps in (10, 20):
        number = steps // 10
        children.importMFNodeFromString(
            -1,
            f'DEF P{number} E-puck {{ translation {0.3 * number} 0.5 0 name "pinger{number}" '
            f'controller "pinger" controllerArgs [ "{number}" ] }}',
        )
        log["counts"].append(children.getCount())
log["p1"] = list(robot.getFromDef("P1").getPosition())
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "spawner.json"), "w") as out:
    json.dump(log, out)
