"""Listens on channel 7, or on every channel (-1) if its name is "all", for five steps; writes the
messages it heard, with their signal strength, as JSON into $SWARM_LOG."""

import json
import os

from controller import Receiver, Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
receiver = robot.getDevice("rx")
if robot.getName() == "all":
    receiver.setChannel(Receiver.CHANNEL_BROADCAST)
receiver.enable(time_step)
heard = {}
for _ in range(5):
    robot.step(time_step)
    while receiver.getQueueLength() > 0:
        heard[receiver.getBytes().decode()] = receiver.getSignalStrength()
        receiver.nextPacket()
log = {"channel": receiver.getChannel(), "heard": heard}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
