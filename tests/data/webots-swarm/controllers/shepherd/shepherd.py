"""A supervisor without wheels: brings the stray e-puck home and orders the other to go."""

import json
import os

from controller import Supervisor

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
emitter = supervisor.getDevice("emitter")
stray = supervisor.getFromDef("STRAY").getField("translation")
flock = supervisor.getFromDef("FLOCK").getField("translation")
seen = {"stray": stray.getSFVec3f(), "flock_start": flock.getSFVec3f()}
stray.setSFVec3f([0.5, -0.5, 0.0])
steps = 0
while supervisor.step(time_step) != -1:
    steps += 1
    emitter.send("go" if steps <= 20 else "stop")
    if steps == 40:
        break
seen["flock_end"] = flock.getSFVec3f()
seen["channel"] = emitter.getChannel()
seen["range"] = emitter.getRange()
with open(os.path.join(os.environ["SWARM_LOG"], "shepherd.json"), "w") as log:
    json.dump(seen, log)
