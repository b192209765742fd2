"""Switches the e-puck's LEDs and reads them back."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
leds = [robot.getDevice(f"led{i}") for i in range(10)]
initial = [led.get() for led in leds]
for i, led in enumerate(leds):
    led.set(i % 2)
robot.step(time_step)
log = {"initial": initial, "set": [led.get() for led in leds]}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
