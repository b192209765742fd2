"""One of thirty: the report's avoid-collision rule (a front sensor above 80 turns it away,
else straight on at half speed) for 0.65 s."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
sensors = [robot.getDevice(f"ps{i}") for i in range(8)]
for sensor in sensors:
    sensor.enable(time_step)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
steps = 0
turns = 0
while robot.step(time_step) != -1 and robot.getTime() < 0.65:
    steps += 1
    values = [s.getValue() for s in sensors]
    if max(values[0], values[1], values[2]) > 80:
        left.setVelocity(-3.14)
        right.setVelocity(3.14)
        turns += 1
    elif max(values[5], values[6], values[7]) > 80:
        left.setVelocity(3.14)
        right.setVelocity(-3.14)
        turns += 1
    else:
        left.setVelocity(3.14)
        right.setVelocity(3.14)
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump({"steps": steps, "turns": turns}, out)
