"""Keeps the leader at the bearing its argument gives (rad, left positive) and 15 cm away, from
getEmitterDirection and the signal strength (range = 1 / sqrt(strength))."""

import json
import math
import os
import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
wanted = float(sys.argv[1])
receiver = robot.getDevice("receiver")
receiver.enable(time_step)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(0.0)
log = {"ranges": [], "bearings": []}
steps = 0
while robot.step(time_step) != -1 and steps < 300:
    steps += 1
    heard = None
    while receiver.getQueueLength() > 0:
        d = receiver.getEmitterDirection()
        heard = (1 / math.sqrt(receiver.getSignalStrength()), math.atan2(d[1], d[0]))
        receiver.nextPacket()
    if heard is None:
        continue
    distance, bearing = heard
    log["ranges"].append(distance)
    log["bearings"].append(bearing)
    speed = max(-6.0, min(6.0, 40.0 * (distance - 0.15)))
    turn = max(-3.0, min(3.0, 6.0 * (bearing - wanted)))
    left.setVelocity(max(-6.28, min(6.28, speed - turn)))
    right.setVelocity(max(-6.28, min(6.28, speed + turn)))
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
