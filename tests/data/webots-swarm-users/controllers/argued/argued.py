"""Drives straight at the speed given after --speed (1 rad/s without) for 1 s; notes its
arguments and its left wheel's position sensor."""

import json
import os
import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
speed = float(sys.argv[sys.argv.index("--speed") + 1]) if "--speed" in sys.argv else 1.0
encoder = robot.getDevice("left wheel sensor")
encoder.enable(time_step)
for name in ("left wheel motor", "right wheel motor"):
    motor = robot.getDevice(name)
    motor.setPosition(float("inf"))
    motor.setVelocity(speed)
while robot.step(time_step) != -1 and robot.getTime() < 1.0 - 1e-9:
    pass
for name in ("left wheel motor", "right wheel motor"):
    robot.getDevice(name).setVelocity(0.0)
log = {"argv": sys.argv[1:], "speed": speed, "encoder": encoder.getValue()}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
