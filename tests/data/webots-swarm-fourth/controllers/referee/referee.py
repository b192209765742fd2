"""Watches the crate the pushers push: its position at the first step and every 20."""

import json
import os

from controller import Supervisor

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
crate = supervisor.getFromDef("CRATE")
track = {}
steps = 0
while supervisor.step(time_step) != -1 and supervisor.getTime() < 3.0:
    steps += 1
    if steps == 1 or steps % 20 == 0:
        track[steps] = crate.getPosition()
track[steps] = crate.getPosition()
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "referee.json"), "w") as out:
    json.dump(track, out)
