"""Drives straight ahead (at ``CRUISE_SPEED`` rad/s, 4 by default) until its run ends;
records how many steps it had, whether ``Robot.step`` returned -1, the time of its first
step, its devices' names and its camera's width."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
for name in ("left wheel motor", "right wheel motor"):
    motor = robot.getDevice(name)
    motor.setPosition(float("inf"))
    motor.setVelocity(float(os.environ.get("CRUISE_SPEED", "4.0")))
steps = 0
first = None
ended = False
while steps < 90:
    if robot.step(time_step) == -1:
        ended = True
        break
    steps += 1
    first = robot.getTime() if first is None else first
with open(os.path.join(os.environ["SWARM_LOG"], f"{robot.getName()}.json"), "w") as log:
    devices = [robot.getDeviceByIndex(i).getName() for i in range(robot.getNumberOfDevices())]
    width = robot.getDevice("camera").getWidth()
    json.dump(
        {
            "steps": steps,
            "ended": ended,
            "first_step_time": first,
            "devices": devices,
            "camera_width": width,
        },
        log,
    )
