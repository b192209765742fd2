"""Alg. 1 of the e-puck tutorials, for 15 s: drive ahead, turn away from whatever a front
sensor reads above 80."""

from controller import Robot

MAX_SPEED = 6.28
robot = Robot()
time_step = int(robot.getBasicTimeStep())
sensors = [robot.getDevice(f"ps{i}") for i in range(8)]
for sensor in sensors:
    sensor.enable(time_step)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(0.0)
while robot.step(time_step) != -1 and robot.getTime() < 15.0 - 1e-9:
    values = [sensor.getValue() for sensor in sensors]
    right_obstacle = values[0] > 80.0 or values[1] > 80.0 or values[2] > 80.0
    left_obstacle = values[5] > 80.0 or values[6] > 80.0 or values[7] > 80.0
    left_speed = right_speed = 0.5 * MAX_SPEED
    if left_obstacle:
        left_speed, right_speed = 0.5 * MAX_SPEED, -0.5 * MAX_SPEED
    elif right_obstacle:
        left_speed, right_speed = -0.5 * MAX_SPEED, 0.5 * MAX_SPEED
    left.setVelocity(left_speed)
    right.setVelocity(right_speed)
