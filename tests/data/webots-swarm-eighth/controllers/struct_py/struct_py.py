"""Reads the C robot's structs with struct.unpack("<ifd") and answers each with
struct.pack("<iff", its step, step / 10, -step / 10)."""

import json
import os
import struct

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
emitter = robot.getDevice("emitter")
receiver = robot.getDevice("receiver")
receiver.enable(time_step)
log = {"reports": [], "sizes": []}
steps = 0
while robot.step(time_step) != -1 and steps < 20:
    steps += 1
    while receiver.getQueueLength() > 0:
        data = receiver.getBytes()
        log["sizes"].append(receiver.getDataSize())
        log["reports"].append(list(struct.unpack("<ifd", data)))
        receiver.nextPacket()
    emitter.send(struct.pack("<iff", steps, steps / 10, -steps / 10))
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
