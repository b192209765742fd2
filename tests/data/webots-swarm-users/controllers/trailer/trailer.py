"""A follower that moves its receiver to channel 3 (or the channel of its first argument) and
notes, each step, the queue's length and, for each packet, its number, signal strength and the
emitter's direction; it turns towards the leader along that direction."""

import json
import os
import struct
import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
receiver = robot.getDevice("receiver")
receiver.enable(time_step)
receiver.setChannel(int(sys.argv[1]) if len(sys.argv) > 1 else 3)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
left.setPosition(float("inf"))
right.setPosition(float("inf"))
lengths, heard = [], []
steps = 0
while robot.step(time_step) != -1 and steps < 60:
    steps += 1
    lengths.append(receiver.getQueueLength())
    turn = 0.0
    while receiver.getQueueLength() > 0:
        (number,) = struct.unpack("<i", receiver.getBytes())
        direction = list(receiver.getEmitterDirection())
        heard.append([steps, number, receiver.getSignalStrength(), direction])
        turn = direction[1]
        receiver.nextPacket()
    left.setVelocity(1.0 - 2.0 * turn)
    right.setVelocity(1.0 + 2.0 * turn)
log = {"lengths": lengths, "heard": heard, "channel": receiver.getChannel()}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
