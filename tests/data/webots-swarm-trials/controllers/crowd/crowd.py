"""Twelve copies of a Braitenberg avoider: each drives towards the arena's middle, where the
others are, and steers away from what its eight proximity sensors see, for 10 s."""

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
weights_left = [-1.3, -1.0, -0.7, 0.0, 0.0, 0.6, 0.9, 1.2]
weights_right = list(reversed(weights_left))
most = 0.0
steps = 0
while robot.step(time_step) != -1 and robot.getTime() < 10.0:
    steps += 1
    values = [s.getValue() / 1000.0 for s in sensors]
    most = max(most, max(values))
    turn_l = sum(w * v for w, v in zip(weights_left, values))
    turn_r = sum(w * v for w, v in zip(weights_right, values))
    left.setVelocity(max(-6.28, min(6.28, 3.0 + 6.0 * turn_l)))
    right.setVelocity(max(-6.28, min(6.28, 3.0 + 6.0 * turn_r)))
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump({"steps": steps, "most": most}, out)
