"""The world's map on ``/map``: the walls' cells occupied, the robot's way free (the driver of
the lockstep tests reads it over DDS from a reader made after the bridge published it)."""

from __future__ import annotations

import math

import numpy as np

import mazesim
from mazesim.controllers import AvoidCollision
from mazesim.ros2.occupancy import MAP_RESOLUTION, occupied_cells


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
