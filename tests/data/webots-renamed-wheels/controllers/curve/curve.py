"""Curves left on an e-puck saved expanded whose wheels' devices its world renames, and prints
what its wheels' encoders read (the right one's node has a ``resolution``, the left one's none)."""

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
left, right = robot.getDevice("left_motor"), robot.getDevice("right_motor")
encoder = robot.getDevice("encoder L")
encoder.enable(time_step)
right_encoder = robot.getDevice("encoder R")
right_encoder.enable(time_step)
for motor, speed in ((left, 2.0), (right, 4.0)):
    motor.setPosition(float("inf"))
    motor.setVelocity(speed)
for _ in range(30):
    robot.step(time_step)
print(f"left wheel turned {encoder.getValue():.2f} rad")
print(f"encoders read {encoder.getValue()!r} {right_encoder.getValue()!r}")
