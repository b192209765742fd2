"""Reads a turret accelerometer whose lookup table scales m/s^2 by 100 (a raw IMU count)."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
imu = robot.getDevice("imu acc")
imu.enable(time_step)
for _ in range(3):
    robot.step(time_step)
log = {"values": imu.getValues(), "table": imu.getLookupTable()}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
