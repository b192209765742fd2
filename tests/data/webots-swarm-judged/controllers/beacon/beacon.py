"""A leader that stands still and beacons its step number on its turret Emitter; from step 30
on it shrinks the emitter's range to 0.2 m."""

import json
import os
import struct

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
beacon = robot.getDevice("beacon")
log = {"channel": beacon.getChannel(), "range": beacon.getRange()}
steps = 0
while robot.step(time_step) != -1 and steps < 60:
    steps += 1
    if steps == 30:
        beacon.setRange(0.2)
        log["range_after"] = beacon.getRange()
    beacon.send(struct.pack("<i", steps))
log["steps"] = steps
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "leader.json"), "w") as out:
    json.dump(log, out)
