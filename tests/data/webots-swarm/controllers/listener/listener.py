"""Drives straight ahead with its receiver listening and never reads a packet; records, after
each step, its clock, its left wheel's position sensor and its receiver's queue length."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
receiver = robot.getDevice("receiver")
receiver.enable(time_step)
wheel = robot.getDevice("left wheel sensor")
wheel.enable(time_step)
for name in ("left wheel motor", "right wheel motor"):
    motor = robot.getDevice(name)
    motor.setPosition(float("inf"))
    motor.setVelocity(4.0)
seen = {"time": [], "wheel": [], "queue": []}
steps = 0
while robot.step(time_step) != -1 and steps < 40:
    steps += 1
    seen["time"].append(robot.getTime())
    seen["wheel"].append(wheel.getValue())
    seen["queue"].append(receiver.getQueueLength())

with open(os.path.join(os.environ["SWARM_LOG"], "listener.json"), "w") as log:
    json.dump(seen, log)
