"""A supervisor that reads both robots' positions and velocities every step, as a swarm's
logger does."""

import json
import os

from controller import Supervisor

supervisor = Supervisor()
time_step = int(supervisor.getBasicTimeStep())
robots = {name: supervisor.getFromDef(name) for name in ("SLOW", "FAST")}
track = {name: [] for name in robots}
speeds = {name: [] for name in robots}
times = []
while supervisor.step(time_step) != -1 and len(times) < 60:
    times.append(supervisor.getTime())
    for name, node in robots.items():
        track[name].append(node.getPosition()[:2])
        velocity = node.getVelocity()
        speeds[name].append([velocity[0], velocity[1], velocity[5]])
with open(os.path.join(os.environ.get("SWARM_LOG", "."), "tracker.json"), "w") as log:
    json.dump({"times": times, "track": track, "speeds": speeds}, log)
