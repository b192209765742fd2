"""An e-puck2 driving at 3 rad/s until its front time-of-flight sensor reads under 100
(millimetres, as Webots' e-puck2 tof lookup table gives them)."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
tof = robot.getDevice("tof")
tof.enable(time_step)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(3.0)
readings = []
stopped = None
while robot.step(time_step) != -1 and robot.getTime() < 8.0 - 1e-9:
    value = tof.getValue()
    readings.append(value)
    if stopped is None and value < 100.0:
        stopped = len(readings)
        left.setVelocity(0.0)
        right.setVelocity(0.0)
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "new_one.json"), "w") as out:
    json.dump({"stopped": stopped, "last": readings[-1]}, out)
