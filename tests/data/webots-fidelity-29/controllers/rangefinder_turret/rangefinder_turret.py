"""A 16 x 1 RangeFinder on the turret looking ahead at the arena's wall: logs its size, range and
the depth of its middle pixel."""

import json
import os

from controller import RangeFinder, Robot

robot = Robot()
time_step = int(robot.getBasicTimeStep())
finder = robot.getDevice("range-finder")
finder.enable(time_step)
for _ in range(3):
    robot.step(time_step)
image = finder.getRangeImage()
width = finder.getWidth()
log = {
    "width": width,
    "height": finder.getHeight(),
    "max_range": finder.getMaxRange(),
    "middle": None
    if image is None
    else RangeFinder.rangeImageGetDepth(image, width, width // 2, 0),
}
with open(os.path.join(os.environ.get("SWARM_LOG", "."), f"{robot.getName()}.json"), "w") as out:
    json.dump(log, out)
