"""Reads the proximity sensors before the first step (Webots gives NaN there) and handles it.

Test controller of mazesim's Webots interoperability (tests/test_webots_user_controllers.py).
"""

import math

from controller import Robot

robot = Robot()
timestep = int(robot.getBasicTimeStep())
ps0 = robot.getDevice("ps0")
ps0.enable(timestep)
first = ps0.getValue()
print(f"before the first step: {'nan' if math.isnan(first) else first}")

left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
left.setPosition(float("inf"))
right.setPosition(float("inf"))
nan_steps = 0
while robot.step(timestep) != -1:
    value = ps0.getValue()
    if math.isnan(value):
        nan_steps += 1
        value = 0.0
    left.setVelocity(-2.0 if value > 100 else 4.0)
    right.setVelocity(4.0)
print(f"steps that read NaN: {nan_steps}")
