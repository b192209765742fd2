"""Drives the e-puck straight ahead at half speed and says hello once."""

from controller import Robot

robot = Robot()
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
left.setPosition(float("inf"))
right.setPosition(float("inf"))
left.setVelocity(3.14)
right.setVelocity(3.14)
print("hello corpus")
while robot.step(32) != -1:
    pass
