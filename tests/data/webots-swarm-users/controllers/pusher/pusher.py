"""Drives straight at 4 rad/s for 1.5 s, then stands still."""

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
left.setPosition(float("inf"))
right.setPosition(float("inf"))
left.setVelocity(4.0)
right.setVelocity(4.0)
while robot.step(time_step) != -1:
    if robot.getTime() >= 1.5 - 1e-9:
        left.setVelocity(0.0)
        right.setVelocity(0.0)
