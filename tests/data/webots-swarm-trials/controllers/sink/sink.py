"""Reads its Receiver (bufferSize 500 bytes) at every step up to step 10, then leaves it alone
until step 21; notes the packets' numbers read at each step."""

import json
import os
import struct

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
rx = robot.getDevice("rx")
rx.enable(time_step)
reads = {}
steps = 0
while robot.step(time_step) != -1 and steps < 25:
    steps += 1
    if steps <= 10 or steps == 21:
        got = []
        while rx.getQueueLength() > 0:
            got.append(struct.unpack("<i", rx.getBytes()[:4])[0])
            rx.nextPacket()
        reads[steps] = got
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "sink.json"), "w") as out:
    json.dump({"reads": reads}, out)
