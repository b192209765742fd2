"""Releases the wheels with setAvailableTorque(0) while asking for 5 rad/s, then gives the
torque back: the wheels turn only once they have torque."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
motors = [robot.getDevice("left wheel motor"), robot.getDevice("right wheel motor")]
sensors = [m.getPositionSensor() for m in motors]
for motor, sensor in zip(motors, sensors):
    sensor.enable(time_step)
    motor.setPosition(float("inf"))
    motor.setAvailableTorque(0.0)
    motor.setVelocity(5.0)
log = {"available_released": motors[0].getAvailableTorque(), "max": motors[0].getMaxTorque()}
steps = 0
while robot.step(time_step) != -1 and steps < 20:
    steps += 1
    if steps == 10:
        log["released"] = [s.getValue() for s in sensors]
        for motor in motors:
            motor.setAvailableTorque(motor.getMaxTorque())
        log["available_given"] = motors[0].getAvailableTorque()
log["driven"] = [s.getValue() for s in sensors]
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
