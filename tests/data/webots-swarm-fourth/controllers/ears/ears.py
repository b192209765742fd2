"""Three receivers, on channels 1, 2 and 3 (the last allowed on 3 only, and asked for 1):
notes what each heard."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
receivers = {name: robot.getDevice(name) for name in ("on1", "on2", "on3")}
for receiver in receivers.values():
    receiver.enable(time_step)
receivers["on3"].setChannel(1)
heard = {name: [] for name in receivers}
seen = {"on3_channel": receivers["on3"].getChannel()}
steps = 0
while robot.step(time_step) != -1 and steps < 10:
    steps += 1
    for name, receiver in receivers.items():
        while receiver.getQueueLength() > 0:
            heard[name].append(receiver.getString())
            receiver.nextPacket()
seen["heard"] = heard
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "ears.json"), "w") as out:
    json.dump(seen, out)
