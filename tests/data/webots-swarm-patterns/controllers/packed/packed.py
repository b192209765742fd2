"""The robot named "caller" sends its step number and a time in a packed struct every step; the
others read what reaches them, with where it came from."""

import json
import os
import struct

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
name = robot.getName()
emitter = robot.getDevice("emitter")
receiver = robot.getDevice("receiver")
receiver.enable(time_step)
log = {
    "name": name,
    "channels": [emitter.getChannel(), receiver.getChannel()],
    "heard": [],
    "direction": None,
}
steps = 0
while robot.step(time_step) != -1 and steps < 30:
    steps += 1
    if name == "caller":
        emitter.send(struct.pack("<id", steps, robot.getTime()))
    while receiver.getQueueLength() > 0:
        number, sent_at = struct.unpack("<id", receiver.getBytes())
        log["heard"].append([steps, number, sent_at])
        log["direction"] = receiver.getEmitterDirection()
        receiver.nextPacket()
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{name}.json"), "w") as out:
    json.dump(log, out)
