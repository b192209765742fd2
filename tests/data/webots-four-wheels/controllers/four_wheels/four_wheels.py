"""Drives the four wheels of a robot that is not an e-puck, as Webots' four-wheeled tutorial
robot does, and prints what its first wheel's position sensor reads."""

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
wheels = [robot.getDevice(f"wheel{i}") for i in (1, 2, 3, 4)]
sensor = robot.getDevice("wheel1 sensor")
sensor.enable(time_step)
for wheel in wheels:
    wheel.setPosition(float("inf"))
    wheel.setVelocity(3.0)
for _ in range(20):
    robot.step(time_step)
print(f"wheel1 turned {sensor.getValue():.2f} rad")
