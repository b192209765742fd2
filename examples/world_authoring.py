"""World authoring: build a world in Python, save it, load it back, drive it and draw it.

A world is a TOML text (see docs/world-format.md). Here a corridor maze is written as an ASCII
grid, with a barcode checkpoint and a dark floor patch added from Python data; the world is
saved, loaded again like any world file, driven by the report's avoid-collision rule, and drawn
with the robot's path into ``world-authoring/my-maze.png``.

Run it with ``python examples/world_authoring.py [OUT_DIR]``; then try
``mazesim demo --world world-authoring/my-maze.toml``.
"""

import os
import sys

import mazesim
from mazesim.controllers import AvoidCollision
from mazesim.plotting import save_trajectory_png

out_dir = sys.argv[1] if len(sys.argv) > 1 else "world-authoring"
os.makedirs(out_dir, exist_ok=True)

maze_rows = [
    "+--+--+--+--+",
    "|S       |  |",
    "+--+--+  +  +",
    "|G          |",
    "+--+--+--+--+",
]
checkpoint = {"id": 1, "code": "10110", "center": [0.625, 0.375], "yaw": 0.0}
patch = {"center": [0.125, 0.125], "size": [0.2, 0.2], "reflectance": 0.2}

toml_text = f'''format = "mazesim-world"
version = 1
name = "my-maze"

[floor]
reflectance = 0.36

[grid]
cell_size = 0.25
wall_thickness = 0.01
map = """
{chr(10).join(maze_rows)}
"""

[[paint]]
shape = "rect"
center = {patch["center"]}
size = {patch["size"]}
reflectance = {patch["reflectance"]}

[[checkpoints]]
id = {checkpoint["id"]}
code = "{checkpoint["code"]}"
center = {checkpoint["center"]}
yaw = {checkpoint["yaw"]}
width = 0.23
'''

world = mazesim.World.from_toml(toml_text, source="my-maze")  # errors name line and field
path = os.path.join(out_dir, "my-maze.toml")
world.save(path)  # written atomically
loaded = mazesim.load_world(path)
assert loaded == world, "a saved world loads back equal"
print(f"saved {path}: start (x, y, yaw) {loaded.start}, goal (x, y, radius) {loaded.goal}")
print(f"{len(loaded.wall_boxes())} wall boxes, {len(loaded.checkpoints())} checkpoint(s)")

sim = mazesim.Simulator(loaded, robot="e-puck", seed=0)
controller = AvoidCollision()
xs, ys = [], []
for _ in range(400):
    sim.step(*controller(sim.distance_sensors()))
    x, y, _yaw = sim.pose
    xs.append(x)
    ys.append(y)
picture = os.path.join(out_dir, "my-maze.png")
save_trajectory_png(loaded, xs, ys, picture, title="my-maze: 400 steps of avoid-collision")
print(f"drove {sim.distance_travelled:.2f} m with {sim.collisions} collision(s); drew {picture}")
