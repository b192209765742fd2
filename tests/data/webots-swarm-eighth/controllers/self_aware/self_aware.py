"""An e-puck that is its own supervisor: drives at 2 rad/s and, after each step, notes its own
position (getSelf) and the others' (getFromDef R0..R2) and its own heading."""

import json
import math
import os

from controller import Supervisor

robot = Supervisor()
time_step = int(robot.getBasicTimeStep())
me = robot.getSelf()
others = {name: robot.getFromDef(name) for name in ("R0", "R1", "R2")}
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(2.0)
log = {"self": [], "seen": [], "heading": []}
steps = 0
while robot.step(time_step) != -1 and steps < 40:
    steps += 1
    log["self"].append(list(me.getPosition())[:2])
    log["seen"].append({k: list(n.getPosition())[:2] for k, n in others.items()})
    m = me.getOrientation()
    log["heading"].append(math.atan2(m[3], m[0]))
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
