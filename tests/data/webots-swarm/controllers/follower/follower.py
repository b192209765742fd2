"""Drives forward while the leader's last order is "go"; acknowledges each order on channel 2."""

import json
import os

from controller import Robot

# Module-level state: each follower must have its own (Webots runs each in its own process).
ORDERS = []

robot = Robot()
name = robot.getName()
time_step = int(robot.getBasicTimeStep())
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(0.0)
emitter = robot.getDevice("emitter")
emitter.setChannel(2)
receiver = robot.getDevice("receiver")
receiver.enable(time_step)
steps = 0
first_heard = None
strengths = []
while robot.step(time_step) != -1:
    steps += 1
    while receiver.getQueueLength() > 0:
        if first_heard is None:
            first_heard = steps
            strengths.append(receiver.getSignalStrength())
            strengths.append(receiver.getEmitterDirection())
        ORDERS.append(receiver.getString())
        receiver.nextPacket()
        emitter.send(f"{name} {ORDERS[-1]}")
    speed = 4.0 if ORDERS and ORDERS[-1] == "go" else 0.0
    left.setVelocity(speed)
    right.setVelocity(speed)
    if steps == 60:
        break

with open(os.path.join(os.environ["SWARM_LOG"], f"{name}.json"), "w") as log:
    json.dump({"first_heard": first_heard, "orders": ORDERS, "strengths": strengths}, log)
