"""Sends "caller:N" after each step N on the e-puck's emitter, for 40 steps."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
emitter = robot.getDevice("emitter")
steps = 0
while robot.step(time_step) != -1 and steps < 40:
    steps += 1
    emitter.send(f"caller:{steps}")
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "caller.json"), "w") as out:
    json.dump({"sent": steps}, out)
