"""A supervisor that resets the simulation at step 20 (simulationReset), stops the physics at
step 40 (simulationResetPhysics) and restarts the runner's controller at step 50; it notes the
runner's position and its own clock around each."""

import json
import os

from controller import Supervisor

boss = Supervisor()
time_step = int(boss.getBasicTimeStep())
runner = boss.getFromDef("RUNNER")
log = {"x": {}, "time": {}}
steps = 0
while boss.step(time_step) != -1 and steps < 80:
    steps += 1
    log["x"][steps] = runner.getPosition()[0]
    log["time"][steps] = boss.getTime()
    if steps == 20:
        boss.simulationReset()
    if steps == 40:
        boss.simulationResetPhysics()
    if steps == 50:
        runner.restartController()
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "boss.json"), "w") as out:
    json.dump(log, out)
