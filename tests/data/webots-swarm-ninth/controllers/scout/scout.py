"""Drives straight at the speed its first argument names (tuning.py beside it) for 1 s, through
the project's shared library (runtime.ini puts it on the path)."""

import json
import os
import sys

import swarmlib
import tuning
from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
left_speed, right_speed = swarmlib.wheel_speeds(tuning.SPEEDS[sys.argv[1]], 0.0)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor, speed in ((left, left_speed), (right, right_speed)):
    motor.setPosition(float("inf"))
    motor.setVelocity(speed)
while robot.step(time_step) != -1 and robot.getTime() < 1.0 - 1e-9:
    pass
left.setVelocity(0.0)
right.setVelocity(0.0)
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump({"speed": left_speed, "time": robot.getTime()}, out)
