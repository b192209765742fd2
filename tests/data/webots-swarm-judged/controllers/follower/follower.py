"""A follower that listens on its turret Receiver and notes, for each packet, the step it
arrived, the number in it, the signal strength and the direction of the emitter."""

import json
import os
import struct

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
ear = robot.getDevice("ear")
ear.enable(time_step)
heard = []
steps = 0
while robot.step(time_step) != -1 and steps < 60:
    steps += 1
    while ear.getQueueLength() > 0:
        (number,) = struct.unpack("<i", ear.getBytes())
        heard.append([steps, number, ear.getSignalStrength(), list(ear.getEmitterDirection())])
        ear.nextPacket()
log = {"heard": heard, "channel": ear.getChannel()}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
