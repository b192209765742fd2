"""A relay: "first" sends 1 after its first step; the others forward each number they hear,
plus one, on the next channel (first on 1, second hears 1 and sends on 2, third hears 2)."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
name = robot.getName()
order = ["first", "second", "third"].index(name)
emitter = robot.getDevice("emitter")
receiver = robot.getDevice("receiver")
receiver.enable(time_step)
emitter.setChannel(order + 1)
receiver.setChannel(order)
heard = []
steps = 0
while robot.step(time_step) != -1 and steps < 10:
    steps += 1
    if order == 0 and steps == 1:
        emitter.send("1")
    while receiver.getQueueLength() > 0:
        value = int(receiver.getString())
        receiver.nextPacket()
        heard.append([steps, value])
        emitter.send(str(value + 1))
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{name}.json"), "w") as out:
    json.dump({"heard": heard}, out)
