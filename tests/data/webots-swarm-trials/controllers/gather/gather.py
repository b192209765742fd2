"""Rendezvous by radio alone: each robot broadcasts its name every step and steers towards the
loudest robot it hears (Receiver.getSignalStrength, 1 / d^2 in Webots), by the direction
Receiver.getEmitterDirection gives in its own frame, until that robot is within 0.15 m."""

import json
import math
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
tx = robot.getDevice("tx")
rx = robot.getDevice("rx")
rx.enable(time_step)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(0.0)
log = {"first": {}, "last": {}, "steps": 0}
steps = 0
while robot.step(time_step) != -1 and steps < 250:
    steps += 1
    tx.send(robot.getName().encode())
    loudest = None
    while rx.getQueueLength() > 0:
        sender = rx.getBytes().decode()
        heard = (rx.getSignalStrength(), list(rx.getEmitterDirection()))
        log["first"].setdefault(sender, [steps, *heard])
        log["last"][sender] = [steps, *heard]
        if loudest is None or heard[0] > loudest[0]:
            loudest = heard
        rx.nextPacket()
    if loudest is None or loudest[0] > 1 / 0.15**2:
        left.setVelocity(0.0)
        right.setVelocity(0.0)
        continue
    bearing = math.atan2(loudest[1][1], loudest[1][0])
    turn = max(-2.0, min(2.0, 3.0 * bearing))
    left.setVelocity(3.0 - turn)
    right.setVelocity(3.0 + turn)
log["steps"] = steps
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
