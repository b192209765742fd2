"""Saves the camera's image before the first step, then as PNG, as JPEG and with an extension
Webots does not write; writes what each call returned and what landed on disk as JSON into
$SWARM_LOG (the images go there too)."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
folder = os.environ.get("SWARM_LOG", ".")
camera = robot.getDevice("camera")
camera.enable(time_step)
results = {"early": camera.saveImage(os.path.join(folder, "early.png"), 100)}
robot.step(time_step)
for name in ("shot.png", "shot.jpg", "shot.bmp"):
    results[name] = camera.saveImage(os.path.join(folder, name), 90)


def head(name):
    path = os.path.join(folder, name)
    if not os.path.exists(path):
        return None
    with open(path, "rb") as image:
        return image.read(24).hex()


log = {
    "returned": results,
    "heads": {name: head(name) for name in ("early.png", "shot.png", "shot.jpg", "shot.bmp")},
    "size": [camera.getWidth(), camera.getHeight()],
}
with open(os.path.join(folder, f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
