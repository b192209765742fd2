"""Driven from the keyboard: UP drives ahead at 4 rad/s, LEFT turns on the spot; notes the
keys it read and at which step."""

import json
import os

from controller import Keyboard, Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
keyboard = robot.getKeyboard()
keyboard.enable(time_step)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
keys = []
steps = 0
while robot.step(time_step) != -1 and robot.getTime() < 2.0:
    steps += 1
    key = keyboard.getKey()
    if key != -1:
        keys.append([steps, key])
    speed = 4.0 if key == Keyboard.UP else 0.0
    turn = 2.0 if key == Keyboard.LEFT else 0.0
    left.setVelocity(speed - turn)
    right.setVelocity(speed + turn)
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "pilot.json"), "w") as out:
    json.dump({"keys": keys, "steps": steps}, out)
