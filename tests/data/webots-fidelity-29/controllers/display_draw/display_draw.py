"""Draws a red square and a blue line on the turret's 32 x 16 display and saves what it shows
with imageSave, as a mapping controller saves its map."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
display = robot.getDevice("display")
display.setColor(0x000000)
display.fillRectangle(0, 0, display.getWidth(), display.getHeight())
display.setColor(0xFF0000)
display.fillRectangle(2, 2, 4, 4)
display.setColor(0x0000FF)
display.drawLine(10, 8, 20, 8)
robot.step(time_step)
display.imageSave(None, "screen.png")
log = {
    "width": display.getWidth(),
    "height": display.getHeight(),
    "saved": os.path.exists("screen.png"),
}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
