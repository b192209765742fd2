"""Steps by the period of its first argument (ms), ps0 enabled at that period; at 1 s of
simulated time it stops its wheels (which turned at 4 rad/s) and notes its clock at each step."""

import json
import os
import sys

from controller import Robot

robot = Robot()
period = int(sys.argv[1])
ps0 = robot.getDevice("ps0")
ps0.enable(period)
for side in ("left", "right"):
    motor = robot.getDevice(f"{side} wheel motor")
    motor.setPosition(float("inf"))
    motor.setVelocity(4.0)
times = []
while robot.step(period) != -1 and robot.getTime() < 1.0 - 1e-9:
    times.append(round(robot.getTime(), 6))
for side in ("left", "right"):
    robot.getDevice(f"{side} wheel motor").setVelocity(0.0)
robot.step(period)
name = robot.getName()
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{name}.json"), "w") as out:
    json.dump({"times": times, "ps0": ps0.getValue(), "period": ps0.getSamplingPeriod()}, out)
