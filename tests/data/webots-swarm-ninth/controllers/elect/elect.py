"""Leader election by signal strength: for 3 steps each robot sends its name and sums the
strengths of the names it hears in the third step's queue (how central it stands); for 3 more
steps it sends that score; the leader is the best score heard or its own (ties to the smaller
name). Notes every neighbour's direction too."""

import json
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
name = robot.getName()
emitter = robot.getDevice("emitter")
receiver = robot.getDevice("receiver")
receiver.enable(time_step)
score = 0.0
scores = {}
directions = {}
steps = 0
while robot.step(time_step) != -1 and steps < 8:
    steps += 1
    while receiver.getQueueLength() > 0:
        kind, sender, *rest = receiver.getString().split(":")
        if sender != name and kind == "ping" and steps == 3:
            score += receiver.getSignalStrength()
            directions[sender] = list(receiver.getEmitterDirection())
        elif sender != name and kind == "score":
            scores[sender] = float(rest[0])
        receiver.nextPacket()
    if steps < 3:
        emitter.send(f"ping:{name}")
    elif steps < 7:
        emitter.send(f"score:{name}:{score!r}")
scores[name] = score
leader = min(scores, key=lambda who: (-scores[who], who))
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{name}.json"), "w") as out:
    log = {"score": score, "leader": leader, "heard": sorted(scores), "directions": directions}
    json.dump(log, out)
