"""An e-puck2 of a platoon along +x: the head drives at 2 rad/s, the others follow the robot
ahead by their ToF, keeping 8 cm (speed 60 * (range - 0.08) rad/s, at most 6)."""

import json
import os
import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
head = sys.argv[1:] == ["head"]
tof = robot.getDevice("tof")
tof.enable(time_step)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(0.0)
log = {"tof": []}
steps = 0
while robot.step(time_step) != -1 and steps < 200:
    steps += 1
    value = tof.getValue() / 1000.0
    log["tof"].append(value)
    speed = 2.0 if head else max(-6.0, min(6.0, 60.0 * (value - 0.08)))
    left.setVelocity(speed)
    right.setVelocity(speed)
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
