"""A supervisor e-puck that imports a second e-puck running controller "joiner" at step 20,
and notes what it hears from it (its own receiver, channel 1)."""

import json
import os

from controller import Supervisor

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
rx = supervisor.getDevice("receiver")
rx.enable(time_step)
children = supervisor.getRoot().getField("children")
heard = []
steps = 0
while supervisor.step(time_step) != -1 and supervisor.getTime() < 2.0:
    steps += 1
    while rx.getQueueLength() > 0:
        heard.append([steps, rx.getString()])
        rx.nextPacket()
    if steps == 20:
        children.importMFNodeFromString(
            -1, 'DEF NEW E-puck { translation 0.3 0 0 name "newcomer" controller "joiner" }'
        )
final = supervisor.getFromDef("NEW").getPosition()
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "host.json"), "w") as out:
    json.dump({"heard": heard, "newcomer_at": final}, out)
