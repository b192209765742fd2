"""Stands still, noting each step what it hears from the robot before it and what its two
front sensors read, for 3 s."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
rx = robot.getDevice("receiver")
rx.enable(time_step)
front = [robot.getDevice("ps0"), robot.getDevice("ps7")]
for sensor in front:
    sensor.enable(time_step)
heard = []
fronts = {}
steps = 0
while robot.step(time_step) != -1 and robot.getTime() < 3.0:
    steps += 1
    while rx.getQueueLength() > 0:
        heard.append([steps, rx.getString()])
        rx.nextPacket()
    fronts[steps] = max(s.getValue() for s in front)
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "watcher.json"), "w") as out:
    json.dump({"heard": heard, "fronts": fronts}, out)
