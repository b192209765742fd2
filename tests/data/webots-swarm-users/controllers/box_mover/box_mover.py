"""A supervisor that, after its 5th step, puts BOX 0.1 m ahead of the pusher by its translation
field and resets its physics, then notes the box's x after every step."""

import json
import os

from controller import Supervisor

robot = Supervisor()
time_step = int(robot.getBasicTimeStep())
box = robot.getFromDef("BOX")
xs = []
steps = 0
while robot.step(time_step) != -1 and robot.getTime() < 2.5 - 1e-9:
    steps += 1
    if steps == 5:
        box.getField("translation").setSFVec3f([0.1, 0.0, 0.025])
        box.resetPhysics()
    xs.append(box.getPosition()[0])
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "box_mover.json"), "w") as out:
    json.dump({"xs": xs}, out)
