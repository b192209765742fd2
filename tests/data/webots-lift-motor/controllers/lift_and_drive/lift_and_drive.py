"""Drives straight ahead on the wheels' own motors of an e-puck saved expanded with a gripper's
lift motor, named "motor", beside them, and prints what each name gives."""

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
left, right = robot.getDevice("left wheel motor"), robot.getDevice("right wheel motor")
lift = robot.getDevice("motor")
print(f"left wheel motor found: {left is not None}; lift motor found: {lift is not None}")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(4.0)
lift.setPosition(-1.4)
for _ in range(30):
    robot.step(time_step)
