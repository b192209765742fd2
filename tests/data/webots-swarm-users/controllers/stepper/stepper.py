"""Steps by the period in ms of its first argument, its receiver sampling at that period; sends
its name and time after each step and notes its step times and, per packet, the time it was
read, the sender and the time it was sent."""

import json
import os
import sys

from controller import Robot

robot = Robot()
period = int(sys.argv[1])
emitter = robot.getDevice("emitter")
receiver = robot.getDevice("receiver")
receiver.enable(period)
times, heard = [], []
while robot.step(period) != -1 and robot.getTime() < 0.5 - 1e-9:
    now = round(robot.getTime(), 6)
    times.append(now)
    while receiver.getQueueLength() > 0:
        name, sent = receiver.getString().split("@")
        heard.append([now, name, float(sent)])
        receiver.nextPacket()
    emitter.send(f"{robot.getName()}@{now}")
log = {"times": times[:6], "steps": len(times), "heard": heard}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
