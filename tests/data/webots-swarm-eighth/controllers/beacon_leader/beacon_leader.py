"""Drives a wide arc (3 and 2.6 rad/s) and sends "lead" after every step."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
emitter = robot.getDevice("emitter")
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
left.setVelocity(2.6)
right.setVelocity(3.0)
log = {"sent": 0}
while robot.step(time_step) != -1 and log["sent"] < 300:
    emitter.send("lead")
    log["sent"] += 1
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
