"""Sends its name on every step; logs the names heard over 5 steps, sorted, and when each
other robot was first heard."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
emitter = robot.getDevice("emitter")
receiver = robot.getDevice("receiver")
receiver.enable(time_step)
name = robot.getName()
first = {}
steps = 0
while robot.step(time_step) != -1 and steps < 5:
    steps += 1
    while receiver.getQueueLength() > 0:
        first.setdefault(receiver.getString(), steps)
        receiver.nextPacket()
    emitter.send(name)
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{name}.json"), "w") as out:
    json.dump({"first": first}, out)
