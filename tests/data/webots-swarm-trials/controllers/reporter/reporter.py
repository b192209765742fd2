"""A supervisor that labels each robot's distance on the 3D view every step (setLabel), takes a
snapshot of the view at step 5 (exportImage) and saves the world at step 20 (worldSave), then
notes what it found on the disk."""

import json
import os

from controller import Supervisor

reporter = Supervisor()
time_step = int(reporter.getBasicTimeStep())
folder = os.environ.get("SWARM_LOG", ".")
robots = [reporter.getFromDef("ONE"), reporter.getFromDef("TWO")]
log = {}
steps = 0
while reporter.step(time_step) != -1 and steps < 25:
    steps += 1
    for index, node in enumerate(robots):
        x, y, _ = node.getPosition()
        reporter.setLabel(
            index, f"{index}: x={x:.3f}", 0.01, 0.02 + 0.05 * index, 0.08, 0xFF0000, 0.0, "Arial"
        )
    if steps == 5:
        reporter.exportImage(os.path.join(folder, "view.jpg"), 90)
    if steps == 20:
        log["saved"] = reporter.worldSave(os.path.join(folder, "saved.wbt"))
        log["x_one"] = robots[0].getPosition()[0]
log["files"] = sorted(n for n in os.listdir(folder) if not n.endswith(".json"))
with open(os.path.join(folder, "reporter.json"), "w") as out:
    json.dump(log, out)
