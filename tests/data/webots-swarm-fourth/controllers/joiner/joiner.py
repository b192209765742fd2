"""Started mid-run: says "hello T" (its clock) at each of its steps and drives ahead at
2 rad/s; notes its first clock reading."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
tx = robot.getDevice("emitter")
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(2.0)
first = robot.getTime()
steps = 0
while robot.step(time_step) != -1 and robot.getTime() < 2.0:
    steps += 1
    tx.send(f"hello {robot.getTime():.3f}")
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "joiner.json"), "w") as out:
    json.dump({"first_time": first, "steps": steps, "name": robot.getName()}, out)
