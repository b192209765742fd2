"""An e-puck2 that stands still and notes its ToF reading, its ps0 and ps7 and the ToF's type,
then backs off at 2 rad/s for 20 steps and notes them again."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
tof = robot.getDevice("tof")
tof.enable(time_step)
sensors = [robot.getDevice(f"ps{i}") for i in (0, 7)]
for sensor in sensors:
    sensor.enable(time_step)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(0.0)
log = {"type": tof.getType(), "generic": tof.getType() == tof.GENERIC}
steps = 0
while robot.step(time_step) != -1 and steps < 30:
    steps += 1
    if steps == 2:
        log["still"] = [tof.getValue(), *[s.getValue() for s in sensors]]
        left.setVelocity(-2.0)
        right.setVelocity(-2.0)
    if steps == 22:
        log["backed"] = [tof.getValue(), *[s.getValue() for s in sensors]]
        left.setVelocity(0.0)
        right.setVelocity(0.0)
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
