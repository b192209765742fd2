"""A supervisor that imports three e-pucks into a Group's children, each at the front, with
its speed in controllerArgs, moves one, and removes another."""

import json
import os

from controller import Supervisor

BEE = (
    'DEF B{index} E-puck {{ translation {x} 0.5 0 name "bee_{index}" controller "bee" '
    'controllerArgs [ "{speed}" "tag {index}" ] }}'
)

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
swarm = supervisor.getFromDef("SWARM")
children = swarm.getField("children")
log = {"count_before": children.getCount()}
steps = 0
while supervisor.step(time_step) != -1:
    steps += 1
    if steps == 3:
        for index in range(3):
            bee = BEE.format(index=index, x=0.3 * index, speed=index + 1)
            children.importMFNodeFromString(0, bee)
        log["count_with"] = children.getCount()
        log["order"] = [children.getMFNode(i).getDef() for i in range(children.getCount())]
        log["parent"] = supervisor.getFromDef("B1").getParentNode().getDef()
    if steps == 4:
        log["start"] = {f"B{i}": supervisor.getFromDef(f"B{i}").getPosition() for i in range(3)}
    if steps == 20:
        supervisor.getFromDef("B2").getField("translation").setSFVec3f([0.6, -0.5, 0.0])
    if steps == 21:
        log["moved"] = supervisor.getFromDef("B2").getPosition()
    if steps == 30:
        supervisor.getFromDef("B0").remove()
        log["count_after"] = children.getCount()
        log["b0_gone"] = supervisor.getFromDef("B0") is None
    if steps == 50:
        log["final"] = {f"B{i}": supervisor.getFromDef(f"B{i}").getPosition() for i in (1, 2)}
        supervisor.simulationQuit(0)
log["steps"] = steps
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "hive.json"), "w") as out:
    json.dump(log, out)
