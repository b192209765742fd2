"""A radio hub with two emitters: after each step it sends "low:K" on "low" (channel 1) and
"high:K" on "high" (channel 2); after its 20th step it moves "low" to channel 2."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
low = robot.getDevice("low")
high = robot.getDevice("high")
steps = 0
while robot.step(time_step) != -1 and steps < 40:
    steps += 1
    if steps == 21:
        low.setChannel(2)
    low.send(f"low:{steps}")
    high.send(f"high:{steps}")
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "hub.json"), "w") as out:
    json.dump({"channels": [low.getChannel(), high.getChannel()]}, out)
