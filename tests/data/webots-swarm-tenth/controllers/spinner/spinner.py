"""Spins on the spot: left wheel -2 rad/s, right +2 rad/s."""

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
robot.getDevice("left wheel motor").setPosition(float("inf"))
robot.getDevice("right wheel motor").setPosition(float("inf"))
robot.getDevice("left wheel motor").setVelocity(-2.0)
robot.getDevice("right wheel motor").setVelocity(2.0)
while robot.step(time_step) != -1:
    pass
