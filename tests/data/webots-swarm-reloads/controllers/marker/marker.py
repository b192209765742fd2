"""Drives forward at 3 rad/s, appending to NAME.log a line when it starts (with its clock and
customData), after its first step (clock, left wheel position) and when its run ends (clock,
steps taken)."""

import math
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
path = os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.log")


def note(line: str) -> None:
    with open(path, "a") as out:
        out.write(line + "\n")


note(f"start {robot.getTime():.3f} {robot.getCustomData()!r}")
left, right = robot.getDevice("left wheel motor"), robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(math.inf)
    motor.setVelocity(3.0)
encoder = robot.getDevice("left wheel sensor")
encoder.enable(time_step)
steps = 0
while robot.step(time_step) != -1:
    steps += 1
    if steps == 1:
        note(f"first {robot.getTime():.3f} {encoder.getValue():.3f}")
note(f"end {robot.getTime():.3f} {steps}")
