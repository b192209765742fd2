"""Drives ahead at 3 rad/s for 120 steps, looking at nothing."""

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(3.0)
steps = 0
while robot.step(time_step) != -1 and steps < 120:
    steps += 1
