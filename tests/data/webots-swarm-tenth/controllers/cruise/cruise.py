"""Drives straight at the speed (rad/s) of its argument, both wheels."""

import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
speed = float(sys.argv[1]) if len(sys.argv) > 1 else 2.0
turn = float(sys.argv[2]) if len(sys.argv) > 2 else 0.0
for name, sign in (("left wheel motor", -1.0), ("right wheel motor", 1.0)):
    motor = robot.getDevice(name)
    motor.setPosition(float("inf"))
    motor.setVelocity(speed + sign * turn)
while robot.step(time_step) != -1:
    pass
