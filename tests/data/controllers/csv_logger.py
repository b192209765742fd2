"""Writes a CSV log of time, encoders and proximity readings into its own folder.

Test controller of mazesim's Webots interoperability (tests/test_webots_user_controllers.py).
"""

import csv
import os

from controller import Robot

LOG = os.path.join(os.path.dirname(os.path.abspath(__file__)), "robot_log.csv")

robot = Robot()
timestep = int(robot.getBasicTimeStep())
sensors = [robot.getDevice(f"ps{i}") for i in range(8)]
for sensor in sensors:
    sensor.enable(timestep)
encoders = [robot.getDevice("left wheel sensor"), robot.getDevice("right wheel sensor")]
for encoder in encoders:
    encoder.enable(timestep)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
left.setPosition(float("inf"))
right.setPosition(float("inf"))
left.setVelocity(2.0)
right.setVelocity(3.0)

with open(LOG, "w", newline="") as handle:
    writer = csv.writer(handle)
    writer.writerow(["time", "left_encoder", "right_encoder"] + [f"ps{i}" for i in range(8)])
    while robot.step(timestep) != -1:
        row = [robot.getTime()] + [encoder.getValue() for encoder in encoders]
        writer.writerow(row + [sensor.getValue() for sensor in sensors])
print(f"log written to {os.path.basename(LOG)}")
