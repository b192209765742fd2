"""Says "alive N" at its step N until its step returns -1; then notes the step it got to."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
tx = robot.getDevice("emitter")
steps = 0
while robot.step(time_step) != -1:
    steps += 1
    tx.send(f"alive {steps}")
    if steps > 200:
        break
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "doomed.json"), "w") as out:
    json.dump({"last_step": steps, "time": robot.getTime()}, out)
