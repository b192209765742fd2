"""Places six e-pucks in a ring with importMFNodeFromString in a loop before its first step,
each named "bot<i>" and running "placed", then counts the children and reads their positions."""

import json
import math
import os

from controller import Supervisor

robot = Supervisor()
time_step = int(robot.getBasicTimeStep())
children = robot.getRoot().getField("children")
log = {"before": children.getCount()}
for i in range(6):
    angle = i * math.pi / 3
    x, y = 0.4 * math.cos(angle), 0.4 * math.sin(angle)
    children.importMFNodeFromString(
        -1,
        f"DEF BOT{i} E-puck {{ translation {x:.4f} {y:.4f} 0 rotation 0 0 1 {angle + math.pi:.4f} "
        f'name "bot{i}" controller "placed" }}',
    )
log["after"] = children.getCount()
steps = 0
while robot.step(time_step) != -1 and steps < 40:
    steps += 1
log["positions"] = [list(robot.getFromDef(f"BOT{i}").getPosition())[:2] for i in range(6)]
log["names"] = [robot.getFromDef(f"BOT{i}").getField("name").getSFString() for i in range(6)]
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "placer.json"), "w") as out:
    json.dump(log, out)
