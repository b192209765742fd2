"""Drives a hand-built two-wheeled robot straight ahead by its two wheel motors."""

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
for name in ("left wheel motor", "right wheel motor"):
    motor = robot.getDevice(name)
    motor.setPosition(float("inf"))
    motor.setVelocity(4.0)
while robot.step(time_step) != -1:
    pass
