"""Drives ahead at 3 rad/s and stops for good once ps0 or ps7 reads above 80 (another e-puck
ahead), as the e-puck tutorials' obstacle check does."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
sensors = [robot.getDevice(f"ps{i}") for i in (0, 7)]
for sensor in sensors:
    sensor.enable(time_step)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(3.0)
log = {"stopped": None, "readings": []}
steps = 0
while robot.step(time_step) != -1 and steps < 120:
    steps += 1
    values = [s.getValue() for s in sensors]
    log["readings"].append(values)
    if log["stopped"] is None and max(values) > 80:
        log["stopped"] = steps
        left.setVelocity(0.0)
        right.setVelocity(0.0)
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
