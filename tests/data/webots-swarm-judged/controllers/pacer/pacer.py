"""Drives straight on at the speed of its second argument (default 2 rad/s), stepping by the
milliseconds of its first (default: the world's basic time step), for at most 1 s of its own
clock; notes its steps, its clock and its synchronization field."""

import json
import os
import sys

from controller import Robot

robot = Robot()
time_step = int(sys.argv[1]) if len(sys.argv) > 1 else int(robot.getBasicTimeStep())
speed = float(sys.argv[2]) if len(sys.argv) > 2 else 2.0
for name in ("left wheel motor", "right wheel motor"):
    motor = robot.getDevice(name)
    motor.setPosition(float("inf"))
    motor.setVelocity(speed)
steps = 0
times = []
while robot.step(time_step) != -1:
    steps += 1
    times.append(robot.getTime())
    if robot.getTime() >= 1.0 - 1e-9:
        break
for name in ("left wheel motor", "right wheel motor"):
    robot.getDevice(name).setVelocity(0.0)
robot.step(time_step)
log = {
    "steps": steps,
    "times": times[:3],
    "last_time": times[-1],
    "synchronization": robot.getSynchronization(),
}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
