"""Sends its first argument and its step count as text on the e-puck's emitter (channel 1)
after each step, from its first step on; notes the time of its first step."""

import json
import os
import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
emitter = robot.getDevice("emitter")
first = None
steps = 0
while robot.step(time_step) != -1:
    steps += 1
    if first is None:
        first = robot.getTime()
        with open(
            os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w"
        ) as out:
            json.dump({"first": first, "argv": sys.argv[1:]}, out)
    emitter.send(f"{sys.argv[1]}:{steps}")
