"""The world's map on ``/map``: the walls' cells occupied, the robot's way free (the driver of
the lockstep tests reads it over DDS from a reader made after the bridge published it)."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

import mazesim
from mazesim.controllers import AvoidCollision
from mazesim.ros2.occupancy import MAP_RESOLUTION, occupied_cells
from ros2_support import MAZESIM, TWO_ROBOTS, needs_namespace, needs_ros2, run_in_namespace


def _cell(x: float, y: float, x0: float, y0: float) -> tuple[int, int]:
    return int((y - y0) / MAP_RESOLUTION), int((x - x0) / MAP_RESOLUTION)


def test_every_wall_box_is_occupied_and_the_robot_s_way_is_free() -> None:
    world = mazesim.load_world("seed-maze")
    cells, x0, y0 = occupied_cells(world)
    assert set(np.unique(cells).tolist()) == {0, 100}
    for cx, cy, sx, sy, yaw, _ in np.asarray(world.wall_boxes()).reshape(-1, 6):
        # The maze's walls are turned by quarter turns: their extents along x and y.
        assert abs(math.sin(2 * yaw)) < 1e-9
        sx, sy = (sy, sx) if abs(math.sin(yaw)) > 0.5 else (sx, sy)
        # Every cell whose centre is inside a wall is occupied.
        rows = slice(
            *(
                int(v)
                for v in np.ceil(
                    (
                        (cy - sy / 2 - y0) / MAP_RESOLUTION - 0.5,
                        (cy + sy / 2 - y0) / MAP_RESOLUTION - 0.5,
                    )
                )
            )
        )
        cols = slice(
            *(
                int(v)
                for v in np.ceil(
                    (
                        (cx - sx / 2 - x0) / MAP_RESOLUTION - 0.5,
                        (cx + sx / 2 - x0) / MAP_RESOLUTION - 0.5,
                    )
                )
            )
        )
        assert (cells[rows, cols] == 100).all()
        assert cells[_cell(cx, cy, x0, y0)] == 100
    # The robot (a 3.7 cm disc) drives 600 steps of Alg. 1 without its centre's cell occupied.
    simulator = mazesim.Simulator(world, robot="e-puck", seed=0)
    avoid = AvoidCollision()
    for _ in range(600):
        simulator.step(*avoid(simulator.distance_sensors()))
        x, y, _ = simulator.pose
        assert cells[_cell(x, y, x0, y0)] == 0
    # And the cells next to the walls' faces are free: the grid is not thicker than a cell more.
    assert (cells == 100).sum() * MAP_RESOLUTION**2 < sum(
        (sx + 2 * MAP_RESOLUTION) * (sy + 2 * MAP_RESOLUTION)
        for _, _, sx, sy, _, _ in np.asarray(world.wall_boxes()).reshape(-1, 6)
    )  # the sizes turned or not: the areas are the same
    assert math.isclose(MAP_RESOLUTION, 0.01)


#: Reads the map on each topic given (reliable, transient local, depth 1, as Nav2's map
#: server's subscribers do), each reader made once the one before has its map; prints per
#: topic its frame, width and height, and whether its bytes equal the first topic's.
_READ_MAPS = """
import sys, time
from rosbags.typesys import Stores, get_typestore
from mazesim.ros2.node import Node
from mazesim.ros2.qos import TopicQos
store = get_typestore(Stores.ROS2_HUMBLE)
node = Node("namespaced_map_reader")
first = None
for topic in sys.argv[1:]:
    reader = node.reader(topic, "nav_msgs/msg/OccupancyGrid", TopicQos(True, True, 1))
    deadline = time.monotonic() + 60  # a ceiling for a hang: the loop ends on the map
    found = []
    while not found and time.monotonic() < deadline:
        found = reader.take(1)
        time.sleep(0.01)
    if not found:
        print(f"{topic}:nothing", flush=True)
        continue
    grid = store.deserialize_cdr(found[0], "nav_msgs/msg/OccupancyGrid")
    first = found[0] if first is None else first
    same = found[0] == first
    print(f"{topic}:{grid.header.frame_id}:{grid.info.width}x{grid.info.height}:{same}", flush=True)
"""


@needs_ros2
@needs_namespace
def test_each_robot_of_a_world_of_several_has_the_map_in_its_namespace(tmp_path: Path) -> None:
    # Nav2 brought up in a robot's namespace (its multi-robot launch files) reads `map`
    # relative to the namespace, where its own map server would publish it: the bridge
    # published the world's map on /map alone, and such a node waited in silence.
    world = tmp_path / "two.toml"
    world.write_text(TWO_ROBOTS)
    cells, _, _ = occupied_cells(mazesim.load_world(str(world)))
    height, width = cells.shape
    result = run_in_namespace(
        [[*MAZESIM, "ros2", "bridge", "--world", str(world)]],
        [sys.executable, "-c", _READ_MAPS, "/map", "/west/map", "/east_1/map"],
        grace=2.0,
    )
    assert result.stdout.split() == [
        f"{topic}:map:{width}x{height}:True" for topic in ("/map", "/west/map", "/east_1/map")
    ], result.stderr
