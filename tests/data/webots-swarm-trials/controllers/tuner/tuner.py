"""Robots that tune their own radio at run time. The caller sends its step number on channel 1,
from step 11 on channel 2, from step 21 with a range of 0.3 m, and at step 31 asks for a range
of 5 m (above its maxRange of 0.6 m). The hearer, 0.5 m away, listens on channel 1 and moves to
channel 2 at step 15, after reading; the scanner, 0.2 m away, listens on every channel (-1)."""

import json
import os
import struct

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
name = robot.getName()
log = {"heard": []}
tx = robot.getDevice("tx") if name == "caller" else None
rx = None if tx else robot.getDevice("rx")
if rx:
    rx.enable(time_step)
steps = 0
while robot.step(time_step) != -1 and steps < 40:
    steps += 1
    if tx:
        if steps == 11:
            tx.setChannel(2)
        if steps == 21:
            tx.setRange(0.3)
        if steps == 31:
            tx.setRange(5.0)
            log["range_asked_5"] = tx.getRange()
        tx.send(struct.pack("<i", steps))
        log["channel"] = tx.getChannel()
        continue
    while rx.getQueueLength() > 0:
        log["heard"].append(struct.unpack("<i", rx.getBytes())[0])
        rx.nextPacket()
    if name == "hearer" and steps == 15:
        rx.setChannel(2)
    log["channel"] = rx.getChannel()
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{name}.json"), "w") as out:
    json.dump(log, out)
