"""Emitters with allowedChannels: "tx" ([1 3]) sends "a" on channel 1, is asked for channel 2
(refused) and sends "b", then moves to 3 and sends "c"; "misfiled" (channel 5, allowed
[2 4]) sends "d" on the channel Webots gave it."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
tx = robot.getDevice("tx")
misfiled = robot.getDevice("misfiled")
seen = {"misfiled_channel": misfiled.getChannel()}
steps = 0
while robot.step(time_step) != -1 and steps < 10:
    steps += 1
    if steps == 1:
        tx.send("a")
    if steps == 2:
        tx.setChannel(2)
        seen["after_asking_2"] = tx.getChannel()
        tx.send("b")
    if steps == 3:
        tx.setChannel(3)
        seen["after_asking_3"] = tx.getChannel()
        tx.send("c")
    if steps == 4:
        misfiled.send("d")
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "talker.json"), "w") as out:
    json.dump(seen, out)
