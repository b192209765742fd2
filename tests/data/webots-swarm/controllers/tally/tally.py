"""Stands still and counts the packets its radio and infra-red receivers read, by text, for 25
steps; writes the counts to SWARM_LOG/<robot name>.json."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
receivers = [robot.getDevice("radio receiver"), robot.getDevice("infra-red receiver")]
for receiver in receivers:
    receiver.enable(time_step)
counts: dict[str, int] = {}
steps = 0
while robot.step(time_step) != -1 and steps < 25:
    steps += 1
    for receiver in receivers:
        while receiver.getQueueLength() > 0:
            text = receiver.getString()
            counts[text] = counts.get(text, 0) + 1
            receiver.nextPacket()

with open(os.path.join(os.environ["SWARM_LOG"], f"{robot.getName()}.json"), "w") as log:
    json.dump(counts, log)
