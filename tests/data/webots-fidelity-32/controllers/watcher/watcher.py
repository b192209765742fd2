"""Steps until the simulation ends, then writes how many steps it took as JSON into
$SWARM_LOG."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
steps = 0
while robot.step(time_step) != -1:
    steps += 1
log = {"steps": steps, "time": robot.getTime()}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
