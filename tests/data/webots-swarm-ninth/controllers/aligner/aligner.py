"""Heading alignment, the first rule of flocking: each step it sends the yaw its InertialUnit
reads and turns towards the circular mean of its own and every heading it heard, driving at
1 rad/s; after 200 steps it writes the yaws it read."""

import json
import math
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
imu = robot.getDevice("imu")
imu.enable(time_step)
emitter = robot.getDevice("emitter")
receiver = robot.getDevice("receiver")
receiver.enable(time_step)
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
yaws = []
steps = 0
while robot.step(time_step) != -1 and steps < 200:
    steps += 1
    yaw = imu.getRollPitchYaw()[2]
    yaws.append(yaw)
    sx, sy = math.cos(yaw), math.sin(yaw)
    while receiver.getQueueLength() > 0:
        other = float(receiver.getString().rstrip("\x00"))
        receiver.nextPacket()
        sx += math.cos(other)
        sy += math.sin(other)
    error = math.atan2(math.sin(math.atan2(sy, sx) - yaw), math.cos(math.atan2(sy, sx) - yaw))
    turn = max(-1.0, min(1.0, 2.0 * error))
    left.setVelocity(1.0 - turn)
    right.setVelocity(1.0 + turn)
    emitter.send(repr(yaw))
left.setVelocity(0.0)
right.setVelocity(0.0)
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump({"yaws": yaws}, out)
