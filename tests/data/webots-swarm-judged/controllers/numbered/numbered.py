"""One controller for four e-pucks named as Webots names copies ("e-puck", "e-puck(1)", ...):
each takes its number from its name, a role from its customData (default "worker"), and
writes "<number>:<role>:<step>" to its customData every step; robot 0 broadcasts on channel 1
and the others count what they hear."""

import json
import os
import re

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
name = robot.getName()
match = re.search(r"\((\d+)\)$", name)
number = int(match.group(1)) if match else 0
role = robot.getCustomData() or "worker"
emitter = robot.getDevice("emitter")
receiver = robot.getDevice("receiver")
emitter.setChannel(1)
receiver.setChannel(1)
receiver.enable(time_step)
heard = 0
first = None
steps = 0
while robot.step(time_step) != -1 and steps < 20:
    steps += 1
    robot.setCustomData(f"{number}:{role}:{steps}")
    if number == 0:
        emitter.send(f"from {number} at {steps}")
    while receiver.getQueueLength() > 0:
        heard += 1
        first = first or receiver.getString()
        receiver.nextPacket()
log = {"number": number, "role": role, "heard": heard, "first": first, "steps": steps}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"robot{number}.json"), "w") as out:
    json.dump(log, out)
