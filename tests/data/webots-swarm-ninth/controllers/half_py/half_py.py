"""Steps with stepBegin / stepEnd, as Webots' R2023b API lets a controller work while the world
steps: before each step it sends how many steps it has done and sets its wheels to 2 rad/s; it
stops after 50 steps."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
emitter = robot.getDevice("emitter")
motors = [robot.getDevice(name) for name in ("left wheel motor", "right wheel motor")]
for motor in motors:
    motor.setPosition(float("inf"))
done = 0
results = []
while done < 50:
    emitter.send(f"py:{done}")
    for motor in motors:
        motor.setVelocity(2.0)
    if robot.stepBegin(time_step) == -1:
        break
    # Work done here overlaps the world's step in Webots.
    results.append(robot.stepEnd())
    done += 1
for motor in motors:
    motor.setVelocity(0.0)
robot.step(time_step)
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "half_py.json"), "w") as out:
    json.dump({"done": done, "results": sorted(set(results)), "time": robot.getTime()}, out)
