"""Keeps its slot (x, y of its arguments) in the leader's frame, steering by the relative pose
a supervisor sends it."""

import json
import math
import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
slot_x, slot_y = float(sys.argv[1]), float(sys.argv[2])
left, right = robot.getDevice("left wheel motor"), robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(math.inf)
    motor.setVelocity(0.0)
receiver = robot.getDevice("receiver")
receiver.enable(time_step)
name = robot.getName()
while robot.step(time_step) != -1:
    while receiver.getQueueLength() > 0:
        message = json.loads(receiver.getString())
        receiver.nextPacket()
        if message["to"] != name:
            continue
        x, y, yaw = message["pose"]
        ex, ey = slot_x - x, slot_y - y
        fx = math.cos(yaw) * ex + math.sin(yaw) * ey
        fy = -math.sin(yaw) * ex + math.cos(yaw) * ey
        forward = 3.0 + 40.0 * fx
        turn = 40.0 * fy - 2.0 * yaw
        wheels = [forward - turn, forward + turn]
        wheels = [max(-6.28, min(6.28, w)) for w in wheels]
        left.setVelocity(wheels[0])
        right.setVelocity(wheels[1])
