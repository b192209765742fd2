"""Drives forward, then divides by zero at its 10th step."""

import math

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
for name in ("left wheel motor", "right wheel motor"):
    motor = robot.getDevice(name)
    motor.setPosition(math.inf)
    motor.setVelocity(5.0)
steps = 0
while robot.step(time_step) != -1:
    steps += 1
    if steps == 10:
        print(1 / (steps - 10))
