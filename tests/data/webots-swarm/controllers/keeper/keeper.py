"""A supervisor that keeps a trial: once the pusher has met the gate, it moves the gate out of
the way and puts the box in the pusher's path, then reads where the pusher took the box."""

import json
import os

from controller import Supervisor

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
box = supervisor.getFromDef("BOX")
gate = supervisor.getFromDef("GATE").getField("translation")
seen = {"box_start": box.getPosition()}
steps = 0
while supervisor.step(time_step) != -1:
    steps += 1
    if steps == 20:
        gate.setSFVec3f([-0.12, 0.6, 0.05])
        box.getField("translation").setSFVec3f([-0.06, 0.0, 0.02])
        seen["box_placed"] = box.getPosition()
    if steps == 58:
        break
seen["box_end"] = box.getPosition()
with open(os.path.join(os.environ["SWARM_LOG"], "keeper.json"), "w") as log:
    json.dump(seen, log)
