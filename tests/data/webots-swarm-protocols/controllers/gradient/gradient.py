"""Climbs the beacon's signal strength alone (run and tumble): drives on while the strength
rises by 0.3 % a step or more, else turns on the spot for 8 steps and drives 4 before it looks
again; stops once it is above 1 / 0.12^2."""

import json
import math
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
receiver = robot.getDevice("receiver")
receiver.enable(time_step)
wheels = [robot.getDevice(n) for n in ("left wheel motor", "right wheel motor")]
for wheel in wheels:
    wheel.setPosition(math.inf)
last = 0.0
turning = running = 0
log = {"first": None, "arrived": None, "strength": 0.0}
steps = 0
while robot.step(time_step) != -1:
    steps += 1
    strength = None
    while receiver.getQueueLength() > 0:
        strength = receiver.getSignalStrength()
        receiver.nextPacket()
    if strength is None:
        continue
    if log["first"] is None:
        log["first"] = strength
    log["strength"] = strength
    if strength > 1 / 0.12**2:
        if log["arrived"] is None:
            log["arrived"] = steps
        left = right = 0.0
    elif turning:
        turning -= 1
        left, right = -3.0, 3.0
    elif running:
        running -= 1
        left = right = 5.0
    elif strength < 1.003 * last:
        turning, running = 8, 4
        left, right = -3.0, 3.0
    else:
        left = right = 5.0
    last = strength
    wheels[0].setVelocity(left)
    wheels[1].setVelocity(right)
    if steps == 900:
        break
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
