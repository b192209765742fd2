"""The world's walls as the occupancy grid a map server publishes on ``/map``.

A Nav2-style node (a planner, a costmap's static layer, a node that waits for a map before it
drives) reads ``/map`` (``nav_msgs/msg/OccupancyGrid``, reliable, transient local, depth 1), which
a map server or a SLAM node publishes beside a simulation. mazesim knows its walls, so the bridge
publishes the map itself, once, as ``map_server`` does (:mod:`mazesim.ros.occupancy`, shared
with the ROS 1 bridge): every cell a wall box overlaps is occupied (100), the others free (0),
over the world's bounds and one cell around them. The map's
frame is ``map``, and ``map`` -> ``odom`` is the identity on ``/tf_static``: the odometry is the
simulator's pose in the world's frame, so it never drifts from the map (a localisation node that
publishes ``map`` -> ``odom`` itself is not needed, and would disagree with none).

A robot in a namespace (``--namespace``, or each robot of a world of several) gets the same map
in its namespace too (``/west/map``, frame ``map``): Nav2 brought up in a namespace, as its
multi-robot launch files run it, has its map server publish there and its AMCL and costmaps read
``map`` relative to the namespace; a node reading the one global ``/map`` gets it as before.
"""

from __future__ import annotations

from typing import Any

from mazesim.ros.occupancy import MAP_FRAME, MAP_RESOLUTION, MAP_TOPIC, occupied_cells
from mazesim.ros2 import cdr

__all__ = [
    "MAP_FRAME",
    "MAP_RESOLUTION",
    "MAP_TOPIC",
    "map_topics",
    "occupancy_grid",
    "occupied_cells",
]


def map_topics(namespaces: list[str]) -> list[str]:
    """Where the bridge publishes the map: ``/map``, then ``<namespace>/map`` for each robot's
    namespace (``""``: none) in order, each once."""
    topics = [MAP_TOPIC]
    for namespace in namespaces:
        if namespace and namespace + MAP_TOPIC not in topics:
            topics.append(namespace + MAP_TOPIC)
    return topics


def occupancy_grid(world: Any, stamp: cdr.Stamp, resolution: float = MAP_RESOLUTION) -> bytes:
    """The ``/map`` message of ``world`` (frame ``map``), encoded."""
    cells, x0, y0 = occupied_cells(world, resolution)
    height, width = cells.shape
    origin = (x0, y0, 0.0, 0.0, 0.0, 0.0, 1.0)
    return cdr.encode_occupancy_grid(
        stamp, MAP_FRAME, resolution, (width, height), origin, cells.tobytes()
    )
