"""Drives straight on at the speed of its first argument (4 rad/s by default) and notes its GPS
position after every step."""

import json
import os
import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
gps = robot.getDevice("gps")
gps.enable(time_step)
speed = float(sys.argv[1]) if len(sys.argv) > 1 else 4.0
for name in ("left wheel motor", "right wheel motor"):
    motor = robot.getDevice(name)
    motor.setPosition(float("inf"))
    motor.setVelocity(speed)
track = []
while robot.step(time_step) != -1 and len(track) < 60:
    track.append(list(gps.getValues()))
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump({"track": track}, out)
