"""The leader: straight on at 2 rad/s for 2 s, then a wide left arc, logging where it is."""

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
while robot.step(time_step) != -1 and robot.getTime() < 8.0:
    if robot.getTime() < 2.0:
        left.setVelocity(2.0)
        right.setVelocity(2.0)
    else:
        left.setVelocity(1.6)
        right.setVelocity(2.2)
