"""Sets its wheels to the speeds its two arguments give (rad/s) and keeps them for 2 s."""

import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
for name, speed in zip(("left wheel motor", "right wheel motor"), sys.argv[1:3]):
    motor = robot.getDevice(name)
    motor.setPosition(float("inf"))
    motor.setVelocity(float(speed))
while robot.step(time_step) != -1 and robot.getTime() < 2.0 - 1e-9:
    pass
