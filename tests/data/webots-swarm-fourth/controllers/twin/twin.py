"""Two robots of one name ("e-puck", the PROTO's default): each drives at the speed its
customData gives for 1 s and notes its name and what it did."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
speed = float(robot.getCustomData())
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(speed)
steps = 0
while robot.step(time_step) != -1 and robot.getTime() < 1.0:
    steps += 1
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"twin{int(speed)}.json"), "w") as out:
    json.dump({"name": robot.getName(), "steps": steps, "speed": speed}, out)
