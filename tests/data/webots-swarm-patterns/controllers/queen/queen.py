"""A supervisor that brings four workers in at step 5, takes two out at step 40 (one by its
node, one by its place in the root's children) and ends the simulation at step 80."""

import json
import os

from controller import Supervisor

WORKER = (
    'DEF W{index} E-puck {{ translation {x} {y} 0 name "w{index}" controller "worker" '
    'customData "{index}" }}'
)

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
children = supervisor.getRoot().getField("children")
seen = {"count_before": children.getCount()}
steps = 0
while supervisor.step(time_step) != -1:
    steps += 1
    if steps == 5:
        for index in range(4):
            children.importMFNodeFromString(-1, WORKER.format(index=index, x=-0.6, y=0.3 * index))
        seen["count_with"] = children.getCount()
        seen["imported"] = [supervisor.getFromDef(f"W{i}").getPosition() for i in range(4)]
    if steps == 6:
        seen["after_a_step"] = [supervisor.getFromDef(f"W{i}").getPosition() for i in range(4)]
    if steps == 40:
        supervisor.getFromDef("W1").remove()
        last = children.getCount() - 1
        seen["last_is_w3"] = children.getMFNode(last).getDef() == "W3"
        children.removeMF(last)
        seen["count_after"] = children.getCount()
        seen["gone"] = [supervisor.getFromDef(f"W{i}") is None for i in range(4)]
    if steps == 80:
        seen["final"] = {f"W{i}": supervisor.getFromDef(f"W{i}").getPosition() for i in (0, 2)}
        supervisor.simulationQuit(0)
seen["steps"] = steps
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "queen.json"), "w") as log:
    json.dump(seen, log)
