"""A supervisor that runs two trials of its own robot with a reset between them, as a learning
loop does: it records what the reset restores (the clock, the robot's place, its motors'
position control, the noise of its rear sensors, which face a wall) and when."""

import json
import math
import os

from controller import Supervisor

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
motors = [supervisor.getDevice(name) for name in ("left wheel motor", "right wheel motor")]
rear = [supervisor.getDevice(name) for name in ("ps3", "ps4")]
for sensor in rear:
    sensor.enable(time_step)
me = supervisor.getSelf()
translation = me.getField("translation")


def still_readings():
    readings = []
    for _ in range(5):
        supervisor.step(time_step)
        readings.append([sensor.getValue() for sensor in rear])
    return readings


def drive():
    for motor in motors:
        motor.setPosition(math.inf)
        motor.setVelocity(4.0)
    for _ in range(20):
        supervisor.step(time_step)


seen = {"first_trial": still_readings()}
drive()
seen["driven"] = translation.getSFVec3f()
supervisor.simulationReset()
seen["after_call"] = {"time": supervisor.getTime(), "translation": translation.getSFVec3f()}
supervisor.step(time_step)
seen["after_step"] = {
    "time": supervisor.getTime(),
    "translation": translation.getSFVec3f(),
    "position": me.getPosition(),
    "target": motors[0].getTargetPosition(),
}
seen["second_trial"] = still_readings()
seen["held"] = me.getPosition()
drive()
seen["driven_again"] = translation.getSFVec3f()
with open(os.path.join(os.environ["SWARM_LOG"], "trial_reset.json"), "w") as log:
    json.dump(seen, log)
