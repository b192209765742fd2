"""Drives straight ahead; records the highest front proximity reading and the colour of the
middle of its camera's first image."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
front = [robot.getDevice(name) for name in ("ps0", "ps7")]
for sensor in front:
    sensor.enable(time_step)
for name in ("left wheel motor", "right wheel motor"):
    motor = robot.getDevice(name)
    motor.setPosition(float("inf"))
    motor.setVelocity(4.0)
camera = robot.getDevice("camera")
camera.enable(time_step)
highest = 0.0
steps = 0
middle = None
while robot.step(time_step) != -1 and steps < 60:
    steps += 1
    highest = max([highest] + [sensor.getValue() for sensor in front])
    if middle is None:
        middle = camera.getImageArray()[camera.getWidth() // 2][camera.getHeight() // 2]

with open(os.path.join(os.environ["SWARM_LOG"], f"{robot.getName()}.json"), "w") as log:
    json.dump({"highest_front_reading": highest, "first_middle_pixel": middle}, log)
