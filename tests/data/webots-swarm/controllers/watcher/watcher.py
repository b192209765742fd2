"""Watches a box through its camera's Recognition while another e-puck crosses the line of
sight; records how many objects each step recognises."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
camera = robot.getDevice("rec")
camera.recognitionEnable(time_step)
counts = []
while robot.step(time_step) != -1 and len(counts) < 40:
    counts.append(camera.getRecognitionNumberOfObjects())
with open(os.path.join(os.environ["SWARM_LOG"], "watcher.json"), "w") as log:
    json.dump(counts, log)
