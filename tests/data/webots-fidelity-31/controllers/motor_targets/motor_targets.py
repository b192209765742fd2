"""Sets targets and too high a velocity on the e-puck's wheels and reads them back."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
initial = left.getTargetPosition()
left.setPosition(float("inf"))
right.setPosition(2.0)
left.setVelocity(100.0)
robot.step(time_step)
log = {
    "initial": initial,
    "left_target": str(left.getTargetPosition()),
    "right_target": right.getTargetPosition(),
    "left_velocity": left.getVelocity(),
    "max_velocity": left.getMaxVelocity(),
}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
