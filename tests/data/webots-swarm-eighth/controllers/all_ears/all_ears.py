"""Listens on every channel (Receiver.setChannel(-1)) and notes who it heard on which channel."""

import json
import os

from controller import Receiver, Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
receiver = robot.getDevice("receiver")
receiver.setChannel(Receiver.CHANNEL_BROADCAST)
receiver.enable(time_step)
log = {"channel": receiver.getChannel(), "heard": {}}
steps = 0
while robot.step(time_step) != -1 and steps < 10:
    steps += 1
    while receiver.getQueueLength() > 0:
        text = receiver.getString()
        log["heard"][text] = log["heard"].get(text, 0) + 1
        receiver.nextPacket()
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
