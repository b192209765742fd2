"""The e-puck's Braitenberg obstacle avoidance of Webots' samples, at 4 rad/s, for 200 steps."""

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
    motor.setVelocity(0.0)
weights = [
    [-1.3, -1.0],
    [-1.3, -1.0],
    [-0.5, 0.5],
    [0, 0],
    [0, 0],
    [0.5, -0.5],
    [-0.75, 0],
    [-0.75, 0],
]
log = {"steps": 0}
while robot.step(time_step) != -1 and log["steps"] < 200:
    log["steps"] += 1
    values = [s.getValue() / 4096 for s in sensors]
    speeds = [4.0 + sum(w[k] * v * 6.0 for w, v in zip(weights, values)) for k in (0, 1)]
    left.setVelocity(max(-6.28, min(6.28, speeds[0])))
    right.setVelocity(max(-6.28, min(6.28, speeds[1])))
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
