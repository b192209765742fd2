"""Drives straight ahead at 3 rad/s for 4 s whatever it meets, logging its front sensors' highest
reading each step."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
front = [robot.getDevice(name) for name in ("ps0", "ps7")]
for sensor in front:
    sensor.enable(time_step)
for name in ("left wheel motor", "right wheel motor"):
    motor = robot.getDevice(name)
    motor.setPosition(float("inf"))
    motor.setVelocity(3.0)
readings = []
while robot.step(time_step) != -1 and robot.getTime() < 4.0 - 1e-9:
    readings.append(max(sensor.getValue() for sensor in front))
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump({"readings": readings}, out)
