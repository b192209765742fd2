"""Stands still and reads its eight proximity sensors every step for 80 steps."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
sensors = [robot.getDevice(f"ps{i}") for i in range(8)]
for sensor in sensors:
    sensor.enable(time_step)
readings = []
while robot.step(time_step) != -1 and len(readings) < 80:
    readings.append([sensor.getValue() for sensor in sensors])
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "centre.json"), "w") as out:
    json.dump({"readings": readings}, out)
