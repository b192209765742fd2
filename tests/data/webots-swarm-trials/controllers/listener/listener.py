"""Answers each "ping N" on channel 4 with "pong N" on channel 5, at once."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
rx = robot.getDevice("rx")
tx = robot.getDevice("tx")
rx.enable(time_step)
heard = []
steps = 0
while robot.step(time_step) != -1 and steps < 20:
    steps += 1
    while rx.getQueueLength() > 0:
        text = rx.getString()
        heard.append([steps, text])
        tx.send(text.replace("ping", "pong"))
        rx.nextPacket()
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "listener.json"), "w") as out:
    json.dump({"heard": heard}, out)
