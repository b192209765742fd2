"""A supervisor that puts RUNNER at (0.5, 0.5) facing +y after its 10th step, then reads where
it is after its 30th."""

import json
import os

from controller import Supervisor

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
runner = supervisor.getFromDef("RUNNER")
steps = 0
before = None
while supervisor.step(time_step) != -1 and steps < 30:
    steps += 1
    if steps == 10:
        before = list(runner.getPosition())
        runner.getField("translation").setSFVec3f([0.5, 0.5, 0.0])
        runner.getField("rotation").setSFRotation([0.0, 0.0, 1.0, 1.5707963267948966])
        runner.resetPhysics()
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "mover.json"), "w") as out:
    json.dump({"before": before, "after": list(runner.getPosition())}, out)
