"""An e-puck2 that drives forward until its time-of-flight sensor reads less than 100 mm."""

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
    motor.setVelocity(4.0)
readings = []
stopped_at = None
steps = 0
while robot.step(time_step) != -1 and steps < 120:
    steps += 1
    readings.append(tof.getValue())
    if stopped_at is None and readings[-1] < 100.0:
        stopped_at = steps
        left.setVelocity(0.0)
        right.setVelocity(0.0)
log = {
    "name": robot.getName(),
    "first": readings[0],
    "last": readings[-1],
    "stopped_at": stopped_at,
    "min_value": tof.getMinValue(),
    "max_value": tof.getMaxValue(),
    "table": tof.getLookupTable(),
    "max_speed": left.getMaxVelocity(),
}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
