"""Reads a sonar of the turret, 7 cm from the arena's wall, for 200 steps: its table has a 5 %
noise column and its resolution is 1."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
sonar = robot.getDevice("sonar")
sonar.enable(time_step)
values = []
while robot.step(time_step) != -1 and len(values) < 200:
    values.append(sonar.getValue())
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump({"values": values}, out)
