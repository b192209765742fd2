"""Moves the DEF MOON e-puck (a robot without controller) every step, by its translation and
rotation fields, round a circle of 8.5 cm about the origin: after its step K, to the angle
2 pi K / 80, facing along the circle."""

import json
import math
import os

from controller import Supervisor

robot = Supervisor()
time_step = int(robot.getBasicTimeStep())
moon = robot.getFromDef("MOON")
translation = moon.getField("translation")
rotation = moon.getField("rotation")
placed = []
steps = 0
while robot.step(time_step) != -1 and steps < 80:
    steps += 1
    placed.append(list(moon.getPosition()))
    angle = 2.0 * math.pi * steps / 80
    translation.setSFVec3f([0.085 * math.cos(angle), 0.085 * math.sin(angle), 0.0])
    rotation.setSFRotation([0.0, 0.0, 1.0, angle + math.pi / 2])
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "orbiter.json"), "w") as out:
    json.dump({"placed": placed}, out)
