"""Turns on the spot (2, -2 rad/s), noting when it started and its steps, in phase_two.json
(rewritten after each step: the run may end it at any step)."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
left.setVelocity(2.0)
right.setVelocity(-2.0)
path = os.path.join(os.environ.get("SWARM_LOG", "."), "phase_two.json")
starts = []
if os.path.exists(path):
    with open(path) as old:
        starts = json.load(old)["starts"]
log = {"starts": [*starts, robot.getTime()], "steps": 0, "name": robot.getName()}
while robot.step(time_step) != -1:
    log["steps"] += 1
    with open(path, "w") as out:
        json.dump(log, out)
