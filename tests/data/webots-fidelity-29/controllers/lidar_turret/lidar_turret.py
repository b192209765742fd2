"""A 360-degree single-layer lidar on the turret: logs its resolution, layers and range, and
the nearest and farthest returns of its range image after a few steps."""

import json
import math
import os

from controller import Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
lidar = robot.getDevice("lidar")
lidar.enable(time_step)
before = lidar.getRangeImage()  # read before the first step, as a Gymnasium env's reset does
for _ in range(3):
    robot.step(time_step)
ranges = lidar.getRangeImage()
finite = [r for r in (ranges or []) if math.isfinite(r)]
log = {
    "resolution": lidar.getHorizontalResolution(),
    "layers": lidar.getNumberOfLayers(),
    "max_range": lidar.getMaxRange(),
    "fov": lidar.getFov(),
    "count": len(ranges or []),
    "nearest": min(finite) if finite else None,
    "farthest": max(finite) if finite else None,
    "before": [len(before), sorted(set(before))] if before is not None else None,
}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
