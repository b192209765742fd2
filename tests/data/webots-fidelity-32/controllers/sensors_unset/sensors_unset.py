"""Enables the e-puck's GPS, inertial unit, compass, touch sensor, gyro and accelerometer, reads
them before the first step and after it, and writes what it read as JSON into $SWARM_LOG."""

import json
import math
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
gps = robot.getDevice("gps")
inertial = robot.getDevice("inertial unit")
compass = robot.getDevice("compass")
gyro = robot.getDevice("gyro")
accelerometer = robot.getDevice("accelerometer")
touch = robot.getDevice("touch sensor")
devices = (gps, inertial, compass, touch, gyro, accelerometer)
for device in devices:
    device.enable(time_step)


def readings():
    return {
        "gps": gps.getValues(),
        "speed": gps.getSpeed(),
        "roll_pitch_yaw": inertial.getRollPitchYaw(),
        "quaternion": inertial.getQuaternion(),
        "compass": compass.getValues(),
        "gyro": gyro.getValues(),
        "accelerometer": accelerometer.getValues(),
        "touch": touch.getValues(),
    }


def shown(values):
    """NaN as the text "nan" (JSON has no NaN)."""
    if isinstance(values, list):
        return [shown(v) for v in values]
    return "nan" if math.isnan(values) else values


before = readings()
robot.step(time_step)
after = readings()
log = {
    "before": {k: shown(v) for k, v in before.items()},
    "after": {k: shown(v) for k, v in after.items()},
    "periods": [d.getSamplingPeriod() for d in devices],
}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
