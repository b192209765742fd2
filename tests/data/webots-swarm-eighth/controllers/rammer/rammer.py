"""Drives ahead at 3 rad/s for 60 steps, then backs off at 3 rad/s for 30."""

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(3.0)
steps = 0
while robot.step(time_step) != -1 and steps < 90:
    steps += 1
    if steps == 60:
        left.setVelocity(-3.0)
        right.setVelocity(-3.0)
