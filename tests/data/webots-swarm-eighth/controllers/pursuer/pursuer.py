"""Chases the evader's signal: turns towards getEmitterDirection, drives at 5 rad/s, stops once
the signal is stronger than at 12 cm (1 / 0.12^2)."""

import json
import math
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
receiver = robot.getDevice("receiver")
receiver.enable(time_step)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(0.0)
log = {"strengths": [], "bearings": [], "caught": None}
steps = 0
while robot.step(time_step) != -1 and steps < 250:
    steps += 1
    strength, bearing = None, None
    while receiver.getQueueLength() > 0:
        strength = receiver.getSignalStrength()
        d = receiver.getEmitterDirection()
        bearing = math.atan2(d[1], d[0])
        receiver.nextPacket()
    if strength is None:
        continue
    log["strengths"].append(strength)
    log["bearings"].append(bearing)
    if strength > 1 / 0.12**2:
        if log["caught"] is None:
            log["caught"] = steps
        left.setVelocity(2.0)
        right.setVelocity(2.0)
        continue
    turn = max(-1.0, min(1.0, 2.0 * bearing))
    left.setVelocity(min(6.28, 5.0 * (1 - turn)))
    right.setVelocity(min(6.28, 5.0 * (1 + turn)))
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
