"""Sets the worker's controller field to "spin" after its 20th step, and to "" (none) after
its 60th; logs what the field reads."""

import json
import os

from controller import Supervisor

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
field = supervisor.getFromDef("WORKER").getField("controller")
log = {"before": field.getSFString()}
steps = 0
while supervisor.step(time_step) != -1:
    steps += 1
    if steps == 20:
        field.setSFString("spin")
        log["after"] = field.getSFString()
        log["x_at_switch"] = supervisor.getFromDef("WORKER").getPosition()[0]
    if steps == 60:
        field.setSFString("")
        log["x_at_stop"] = supervisor.getFromDef("WORKER").getPosition()[0]
    if steps == 90:
        break
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "switcher.json"), "w") as out:
    json.dump(log, out)
