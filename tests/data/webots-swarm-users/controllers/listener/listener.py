"""Listens on the e-puck's receiver (channel 1) and notes after each step, for each sender, the
step it was first heard and the text of its first packet, and how many packets it heard."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
receiver = robot.getDevice("receiver")
receiver.enable(time_step)
first = {}
count = 0
steps = 0
while robot.step(time_step) != -1 and steps < 40:
    steps += 1
    while receiver.getQueueLength() > 0:
        text = receiver.getString()
        sender = text.split(":")[0]
        first.setdefault(sender, [steps, text])
        count += 1
        receiver.nextPacket()
    log = {"first": first, "count": count, "steps": steps}
    with open(
        os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w"
    ) as out:
        json.dump(log, out)
