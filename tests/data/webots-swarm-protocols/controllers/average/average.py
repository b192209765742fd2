"""Average consensus over the radio: each robot broadcasts its value within 0.35 m and moves
it towards every value it hears (weight 0.3 a neighbour). With "leave" as its second argument
the robot drives away after its 60th step, out of its neighbour's range."""

import json
import math
import os
import sys

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
name = robot.getName()
value = float(sys.argv[1])
leaves = len(sys.argv) > 2 and sys.argv[2] == "leave"
emitter, receiver = robot.getDevice("emitter"), robot.getDevice("receiver")
emitter.setRange(0.35)
receiver.enable(time_step)
left, right = robot.getDevice("left wheel motor"), robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(math.inf)
    motor.setVelocity(0.0)
log = {"start": value, "heard": {}, "strengths": [], "values": [], "range": emitter.getRange()}
steps = 0
emitter.send(json.dumps({"from": name, "value": value}))
while robot.step(time_step) != -1:
    steps += 1
    total = 0.0
    while receiver.getQueueLength() > 0:
        packet = json.loads(receiver.getString())
        if steps <= 2:
            log["strengths"].append(receiver.getSignalStrength())
        log["heard"].setdefault(packet["from"], []).append(steps)
        total += 0.3 * (packet["value"] - value)
        receiver.nextPacket()
    value += total
    log["values"].append(value)
    if leaves and steps == 60:
        left.setVelocity(6.0)
        right.setVelocity(6.0)
    if steps == 250:
        break
    emitter.send(json.dumps({"from": name, "value": value}))
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{name}.json"), "w") as out:
    json.dump(log, out)
