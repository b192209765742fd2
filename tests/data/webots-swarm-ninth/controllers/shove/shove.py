"""Drives straight ahead at 4 rad/s for 4 s."""

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
for name in ("left wheel motor", "right wheel motor"):
    motor = robot.getDevice(name)
    motor.setPosition(float("inf"))
    motor.setVelocity(4.0)
while robot.step(time_step) != -1 and robot.getTime() < 4.0 - 1e-9:
    pass
