"""Foraging by two: drives straight ahead at 3 rad/s, pushing what is before it, for 3 s, and
notes its front sensors at the start."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
front = [robot.getDevice("ps0"), robot.getDevice("ps7")]
for sensor in front:
    sensor.enable(time_step)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(3.0)
seen = {}
steps = 0
while robot.step(time_step) != -1 and robot.getTime() < 3.0:
    steps += 1
    if steps == 1:
        seen["front_at_start"] = [s.getValue() for s in front]
seen["front_at_end"] = [s.getValue() for s in front]
seen["steps"] = steps
name = robot.getName().replace(" ", "_")
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{name}.json"), "w") as out:
    json.dump(seen, out)
