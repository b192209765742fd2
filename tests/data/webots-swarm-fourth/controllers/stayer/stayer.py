"""Runs on for 3 s at 2 rad/s, noting at which of its steps it heard the quitter."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
rx = robot.getDevice("receiver")
rx.enable(time_step)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(2.0)
heard = []
steps = 0
while robot.step(time_step) != -1 and robot.getTime() < 3.0:
    steps += 1
    while rx.getQueueLength() > 0:
        heard.append([steps, rx.getString()])
        rx.nextPacket()
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump({"heard": heard, "steps": steps, "time": robot.getTime()}, out)
