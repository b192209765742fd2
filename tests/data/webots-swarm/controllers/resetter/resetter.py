"""A supervisor that ends a trial and starts the next: once the pusher has met the gate, it
moves the gate out of the way and sets the box sliding; ten steps later it resets the
simulation, and records where the box, the gate and the pusher are after the next step (at
whose end the reset comes) and at the end."""

import json
import os

from controller import Supervisor

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
box = supervisor.getFromDef("BOX")
gate = supervisor.getFromDef("GATE").getField("translation")
pusher = supervisor.getFromDef("PUSHER")
seen = {}
steps = 0
while supervisor.step(time_step) != -1:
    steps += 1
    if steps == 20:
        gate.setSFVec3f([-0.12, 0.6, 0.05])
        box.setVelocity([0.0, -0.7, 0.0, 0.0, 0.0, 0.0])
    if steps == 21:
        seen["box_sliding"] = box.getVelocity()
    if steps == 30:
        seen["before_reset"] = {"box": box.getPosition(), "pusher": pusher.getPosition()}
        supervisor.simulationReset()
    if steps == 31:
        seen["after_reset"] = {
            "box": box.getPosition(),
            "box_velocity": box.getVelocity(),
            "gate": gate.getSFVec3f(),
            "pusher": pusher.getPosition(),
            "time": supervisor.getTime(),
        }
    if steps == 58:
        break
seen["pusher_end"] = pusher.getPosition()
with open(os.path.join(os.environ["SWARM_LOG"], "resetter.json"), "w") as log:
    json.dump(seen, log)
