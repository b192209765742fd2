"""Drives straight ahead at 4 rad/s for as long as it runs."""

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
for side in ("left", "right"):
    motor = robot.getDevice(f"{side} wheel motor")
    motor.setPosition(float("inf"))
    motor.setVelocity(4.0)
while robot.step(time_step) != -1:
    pass
