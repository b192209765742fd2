"""Drives on a circle: left and right wheel speeds from its two arguments."""

import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor, speed in zip((left, right), sys.argv[1:3]):
    motor.setPosition(float("inf"))
    motor.setVelocity(float(speed))
while robot.step(time_step) != -1:
    pass
