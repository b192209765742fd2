"""Polls the keyboard while nobody types."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
keyboard = robot.getKeyboard()
keyboard.enable(time_step)
keys = []
for _ in range(5):
    robot.step(time_step)
    keys.append(keyboard.getKey())
log = {"keys": keys, "period": keyboard.getSamplingPeriod()}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
