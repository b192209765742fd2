"""The world's walls as the occupancy grid a map server publishes, shared by both bridges.

A node that plans on a map (``move_base``'s or Nav2's global costmap, a node that waits for a map
before it drives) reads ``map`` (``nav_msgs/OccupancyGrid``), which a map server or a SLAM node
publishes beside a simulation, latched. mazesim knows its walls, so both bridges publish the map
themselves, once, as ``map_server`` does: every cell a wall box overlaps is occupied (100), the
others free (0), over the world's bounds and one cell around them, in the frame ``map``; ``map``
-> ``odom`` is the identity on ``/tf_static`` (the odometry is the simulator's pose in the world's
frame). The ROS 2 bridge encodes it (:mod:`mazesim.ros2.occupancy`); nothing here needs ROS.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import numpy.typing as npt

__all__ = ["MAP_FRAME", "MAP_RESOLUTION", "MAP_TOPIC", "OCCUPIED", "occupied_cells"]

MAP_TOPIC = "/map"
MAP_FRAME = "map"
#: Metres a cell: the walls of mazesim's worlds are 1 cm thick, so each is at least a cell.
MAP_RESOLUTION = 0.01
OCCUPIED = 100


def occupied_cells(
    world: Any, resolution: float = MAP_RESOLUTION
) -> tuple[npt.NDArray[np.int8], float, float]:
    """The occupancy of the world's cells, rows along y from the bottom, and the corner of cell
    (0, 0): ``(cells, x0, y0)``; ``cells`` is int8, 100 where a wall box overlaps the cell and 0
    elsewhere."""
    xmin, ymin, xmax, ymax = world.bounds
    x0 = math.floor(xmin / resolution) * resolution - resolution
    y0 = math.floor(ymin / resolution) * resolution - resolution
    width = int(math.ceil((xmax - x0) / resolution)) + 1
    height = int(math.ceil((ymax - y0) / resolution)) + 1
    xs = x0 + (np.arange(width) + 0.5) * resolution
    ys = y0 + (np.arange(height) + 0.5) * resolution
    cx, cy = np.meshgrid(xs, ys)
    cells = np.zeros((height, width), dtype=np.int8)
    half = resolution / 2.0
    for box_x, box_y, size_x, size_y, yaw, *_ in np.asarray(world.wall_boxes()).reshape(-1, 6):
        c, s = math.cos(yaw), math.sin(yaw)
        dx, dy = cx - box_x, cy - box_y
        along, across = c * dx + s * dy, -s * dx + c * dy
        # A cell overlaps an axis-aligned box when its centre is within half a cell of it; a
        # turned box is widened by half a cell's diagonal.
        margin = half if abs(s * c) < 1e-9 else half * math.sqrt(2.0)
        inside = (np.abs(along) <= size_x / 2.0 + margin) & (
            np.abs(across) <= size_y / 2.0 + margin
        )
        cells[inside] = OCCUPIED
    return cells, x0, y0
