"""Listens on the channel its receiver_channel field gives, or on the one its first argument
names; notes each packet's text and the step whose end found it."""

import json
import os
import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
receiver = robot.getDevice("receiver")
if len(sys.argv) > 1:
    receiver.setChannel(int(sys.argv[1]))
receiver.enable(time_step)
heard = []
steps = 0
while robot.step(time_step) != -1 and steps < 45:
    steps += 1
    while receiver.getQueueLength() > 0:
        heard.append([steps, receiver.getString()])
        receiver.nextPacket()
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump({"channel": receiver.getChannel(), "heard": heard}, out)
