"""Follows the robot carrying the red mast: finds the red pixels of its camera, turns towards
their mean column and closes in while the red blob is narrow, stops when it is wide."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
camera = robot.getDevice("camera")
camera.enable(time_step)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
width = camera.getWidth()
seen = {"widths": [], "first_seen": None}
steps = 0
while robot.step(time_step) != -1 and robot.getTime() < 8.0:
    steps += 1
    image = camera.getImage()
    columns = []
    for x in range(width):
        for y in range(camera.getHeight()):
            r = camera.imageGetRed(image, width, x, y)
            g = camera.imageGetGreen(image, width, x, y)
            b = camera.imageGetBlue(image, width, x, y)
            if r > 120 and r > 2 * g and r > 2 * b:
                columns.append(x)
                break
    if not columns:
        left.setVelocity(-1.0)
        right.setVelocity(1.0)
        continue
    if seen["first_seen"] is None:
        seen["first_seen"] = steps
    seen["widths"].append(len(columns))
    offset = (sum(columns) / len(columns) - (width - 1) / 2) / (width / 2)
    forward = 3.0 if len(columns) < 12 else 0.0
    left.setVelocity(forward + 2.0 * offset)
    right.setVelocity(forward - 2.0 * offset)
seen["steps"] = steps
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "follower.json"), "w") as out:
    json.dump(seen, out)
