"""Drives at 3 rad/s until ps0 or ps7 reads over 150, then stops; logs the step it stopped."""

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
stopped = None
steps = 0
readings = []
while robot.step(time_step) != -1 and steps < 300:
    steps += 1
    readings.append(round(max(s.getValue() for s in sensors), 1))
    if stopped is None and max(s.getValue() for s in sensors) > 150:
        stopped = steps
        left.setVelocity(0.0)
        right.setVelocity(0.0)
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump({"stopped": stopped, "readings": readings}, out)
