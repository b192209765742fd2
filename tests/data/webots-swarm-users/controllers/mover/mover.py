"""A supervisor that, after its 20th step, moves RUNNER to (0.3, 0.3) and STILL to (0, -0.5)
by their translation fields, resets their physics, and notes what the fields and getPosition
read on the next steps."""

import json
import os

from controller import Supervisor

robot = Supervisor()
time_step = int(robot.getBasicTimeStep())
runner = robot.getFromDef("RUNNER")
still = robot.getFromDef("STILL")
log = {"before": None, "after": [], "still_after": None}
steps = 0
while robot.step(time_step) != -1 and steps < 40:
    steps += 1
    if steps == 20:
        log["before"] = runner.getField("translation").getSFVec3f()
        runner.getField("translation").setSFVec3f([0.3, 0.3, 0.0])
        runner.resetPhysics()
        still.getField("translation").setSFVec3f([0.0, -0.5, 0.0])
        still.resetPhysics()
    elif 20 < steps <= 23:
        log["after"].append(
            [runner.getField("translation").getSFVec3f(), list(runner.getPosition())]
        )
        log["still_after"] = list(still.getPosition())
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "mover.json"), "w") as out:
    json.dump(log, out)
