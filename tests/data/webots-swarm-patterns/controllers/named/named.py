"""One controller, three roles: a robot named "leader" calls out every step, "worker_N" robots
drive forward once they have heard it, and a robot whose customData names a role plays it (a
"scout" turns on the spot)."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
name = robot.getName()
role = robot.getCustomData() or name.split("_")[0]
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
for motor in (left, right):
    motor.setPosition(float("inf"))
    motor.setVelocity(0.0)
emitter = robot.getDevice("emitter")
receiver = robot.getDevice("receiver")
receiver.enable(time_step)
heard = []
steps = 0
while robot.step(time_step) != -1 and steps < 40:
    steps += 1
    if role == "leader":
        emitter.send(f"leader {steps}")
    while receiver.getQueueLength() > 0:
        heard.append(receiver.getString())
        receiver.nextPacket()
    if role == "worker" and heard:
        left.setVelocity(3.0)
        right.setVelocity(3.0)
    if role == "scout":
        left.setVelocity(-2.0)
        right.setVelocity(2.0)
log = {"name": name, "role": role, "heard": len(heard), "first": heard[:1], "steps": steps}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{name}.json"), "w") as out:
    json.dump(log, out)
