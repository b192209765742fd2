"""Broadcasts "go" for 30 steps, then "stop"; counts the followers' acknowledgements."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
emitter = robot.getDevice("emitter")
emitter.setRange(0.8)  # the E-puck PROTO sets no range: its orders reach 0.8 m only
receiver = robot.getDevice("receiver")
receiver.setChannel(2)
receiver.enable(time_step)
steps = 0
acknowledgements = []
while robot.step(time_step) != -1:
    steps += 1
    while receiver.getQueueLength() > 0:
        acknowledgements.append(receiver.getString())
        receiver.nextPacket()
    emitter.send("go" if steps <= 30 else "stop")
    if steps == 60:
        break

with open(os.path.join(os.environ["SWARM_LOG"], "leader.json"), "w") as log:
    json.dump({"steps": steps, "acknowledgements": acknowledgements}, log)
