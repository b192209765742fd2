"""Drives straight on at 3 rad/s for 60 steps."""

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
for side in ("left", "right"):
    motor = robot.getDevice(f"{side} wheel motor")
    motor.setPosition(float("inf"))
    motor.setVelocity(3.0)
steps = 0
while robot.step(time_step) != -1 and steps < 60:
    steps += 1
