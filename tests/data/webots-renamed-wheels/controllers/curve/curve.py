"""Curves left on an e-puck saved expanded whose wheels' devices its world renames, and prints
what its left wheel's encoder reads."""

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
left, right = robot.getDevice("left_motor"), robot.getDevice("right_motor")
encoder = robot.getDevice("encoder L")
encoder.enable(time_step)
for motor, speed in ((left, 2.0), (right, 4.0)):
    motor.setPosition(float("inf"))
    motor.setVelocity(speed)
for _ in range(30):
    robot.step(time_step)
print(f"left wheel turned {encoder.getValue():.2f} rad")
