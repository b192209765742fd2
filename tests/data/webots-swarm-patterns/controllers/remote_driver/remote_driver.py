"""An extern controller: drives backwards for 50 steps and says which robot it drove."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(-2.0)
steps = 0
while robot.step(time_step) != -1 and steps < 50:
    steps += 1
for motor in (left, right):
    motor.setVelocity(0.0)
robot.step(time_step)
log = {"name": robot.getName(), "steps": steps, "file": os.path.basename(__file__)}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
