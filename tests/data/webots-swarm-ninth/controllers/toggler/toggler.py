"""Listens for 10 steps, turns its receiver off for 10 steps (having read its queue) and on
again: notes what it heard at which step and the receiver's sampling period."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
receiver = robot.getDevice("receiver")
receiver.enable(time_step)
heard, periods = [], []
steps = 0
while robot.step(time_step) != -1 and steps < 40:
    steps += 1
    while receiver.getQueueLength() > 0:
        heard.append([steps, int(receiver.getString())])
        receiver.nextPacket()
    if steps == 10:
        receiver.disable()
    elif steps == 20:
        receiver.enable(time_step)
    periods.append(receiver.getSamplingPeriod())
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "toggler.json"), "w") as out:
    json.dump({"heard": heard, "periods": periods}, out)
