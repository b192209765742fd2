"""Listens on the e-puck's receiver for 60 steps, noting each packet's text and the step whose
end found it in the queue."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
receiver = robot.getDevice("receiver")
receiver.enable(time_step)
heard = []
steps = 0
while robot.step(time_step) != -1 and steps < 60:
    steps += 1
    while receiver.getQueueLength() > 0:
        heard.append([steps, receiver.getString().rstrip("\x00")])
        receiver.nextPacket()
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump({"heard": heard}, out)
