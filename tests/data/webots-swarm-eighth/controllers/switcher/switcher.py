"""After its 20th step sets the worker's controller field to "phase_two" and restarts its
controller, as Webots' forums advise; notes the field and the worker's pose."""

import json
import os

from controller import Supervisor

robot = Supervisor()
time_step = int(robot.getBasicTimeStep())
worker = robot.getFromDef("WORKER")
field = worker.getField("controller")
log = {"before": field.getSFString()}
steps = 0
while robot.step(time_step) != -1 and steps < 60:
    steps += 1
    if steps == 20:
        log["at_switch"] = list(worker.getPosition())
        field.setSFString("phase_two")
        worker.restartController()
        log["after"] = field.getSFString()
log["end"] = list(worker.getPosition())
log["yaw_end"] = worker.getOrientation()[:2]
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "switcher.json"), "w") as out:
    json.dump(log, out)
