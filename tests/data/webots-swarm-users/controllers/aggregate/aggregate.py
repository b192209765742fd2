"""Gauci et al.'s aggregation rule on the e-puck's front proximity sensors: with something
ahead (ps0 or ps7 above 150) turn on the spot clockwise, else drive on a wide anticlockwise
circle; notes its steps."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
front = [robot.getDevice(name) for name in ("ps0", "ps7")]
for sensor in front:
    sensor.enable(time_step)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
left.setPosition(float("inf"))
right.setPosition(float("inf"))
steps = 0
while robot.step(time_step) != -1:
    steps += 1
    if max(sensor.getValue() for sensor in front) > 150:
        left.setVelocity(2.0)
        right.setVelocity(-2.0)
    else:
        left.setVelocity(4.0)
        right.setVelocity(5.0)
    with open(
        os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w"
    ) as out:
        json.dump({"steps": steps}, out)
