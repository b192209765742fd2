"""Moves its emitter to the channel its argument names and sends its name there every step."""

import json
import os
import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
emitter = robot.getDevice("emitter")
emitter.setChannel(int(sys.argv[1]))
log = {"channel": emitter.getChannel(), "sent": 0}
while robot.step(time_step) != -1 and log["sent"] < 10:
    emitter.send(robot.getName())
    log["sent"] += 1
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
