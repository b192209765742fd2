"""Says whether its robot's simulation waits for it (the robot's synchronization field)."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
steps = 0
while robot.step(time_step) != -1 and steps < 20:
    steps += 1
log = {"name": robot.getName(), "synchronization": robot.getSynchronization(), "steps": steps}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
