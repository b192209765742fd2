"""An e-puck that drives at the wheel speed its customData holds, writes its own customData
once (after its twentieth step) and records what it read at each step."""

import json
import os

from controller import Robot

robot = Robot()
motors = [robot.getDevice(f"{side} wheel motor") for side in ("left", "right")]
for motor in motors:
    motor.setPosition(float("inf"))
seen = []
while robot.step(32) != -1 and len(seen) < 40:
    data = robot.getCustomData()
    seen.append(data)
    try:
        speed = float(data)
    except ValueError:
        speed = 0.0
    for motor in motors:
        motor.setVelocity(speed)
    if len(seen) == 20:
        robot.setCustomData("mine")
with open(os.path.join(os.environ["SWARM_LOG"], "worker.json"), "w") as log:
    json.dump(seen, log)
