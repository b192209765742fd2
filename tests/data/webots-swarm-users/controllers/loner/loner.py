"""Steps by the period of its first argument for 1 s of simulated time, turning on the spot at
2 rad/s; notes its synchronization, its step count and the times of its first steps."""

import json
import os
import sys

from controller import Robot

robot = Robot()
period = int(sys.argv[1])
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
left.setPosition(float("inf"))
right.setPosition(float("inf"))
left.setVelocity(2.0)
right.setVelocity(-2.0)
times = []
while robot.step(period) != -1 and robot.getTime() < 1.0 - 1e-9:
    times.append(round(robot.getTime(), 6))
log = {"synchronization": robot.getSynchronization(), "steps": len(times), "times": times[:3]}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
