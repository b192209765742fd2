"""A supervisor that times its trials with getTime, as reinforcement learning loops do: it
broadcasts a packet at each of its first 20 steps, resets the simulation at its 30th and
records its clock around the reset."""

import json
import os

from controller import Supervisor

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
emitter = supervisor.getDevice("emitter")
seen = {}
steps = 0
while supervisor.step(time_step) != -1:
    steps += 1
    if steps <= 20:
        emitter.send("tick")
    if steps == 30:
        seen["before_reset"] = supervisor.getTime()
        supervisor.simulationReset()
        seen["at_reset"] = supervisor.getTime()
    if steps == 31:
        seen["step_after_reset"] = supervisor.getTime()
    if steps == 40:
        break
seen["end"] = supervisor.getTime()
with open(os.path.join(os.environ["SWARM_LOG"], "clock_keeper.json"), "w") as log:
    json.dump(seen, log)
