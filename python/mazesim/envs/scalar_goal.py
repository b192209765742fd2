"""The shortest-path distance to the goal of one environment, in plain Python floats.

:class:`~mazesim.envs.reward.GoalDistance` evaluates N environments with numpy; for one
environment its two dozen array operations cost more than the simulation step itself. This is the
same arithmetic on Python floats, operation for operation in the same order (IEEE double
arithmetic on scalars rounds exactly as numpy's float64 ufuncs do element-wise), so the single env
and the native vector env still agree bit for bit.
"""

from __future__ import annotations

import math

from mazesim.maze import EAST, NORTH, SOUTH, WEST, PathDistanceTable

__all__ = ["ScalarGoalDistance"]

#: As in mazesim.envs.reward: the smallest distance in an inverse-distance weight (metres).
_NEAREST = 1e-9


class ScalarGoalDistance:
    """The shortest-path distance to the goal in one world, for one robot at a time.

    Args:
        table: The world's distance table.
    """

    def __init__(self, table: PathDistanceTable) -> None:
        self.mode = table.mode
        self._goal_x, self._goal_y = float(table.goal[0]), float(table.goal[1])
        radius = float(table.goal[2])
        self._goal_r2 = radius * radius if table.mode != "none" else -1.0
        self._size = float(table.cell_size)
        self._origin_x, self._origin_y = (float(v) for v in table.origin)
        self._last_row = table.rows - 1
        self._last_col = table.cols - 1
        self._cols = table.cols
        # Per cell: (value, presence) of each side, in maze's direction order, and the goal point.
        self._cells: list[tuple[tuple[float, float], ...]] = [
            tuple(
                (0.0, 0.0) if math.isnan(value) else (float(value), 1.0) for value in row.tolist()
            )
            for row in table.targets
        ]

    def evaluate(self, x: float, y: float) -> tuple[float, bool]:
        """The shortest-path distance in metres from (x, y), and whether (x, y) lies in the goal
        disc. ``x`` and ``y`` are the float32 pose as Python floats."""
        gx = x - self._goal_x
        gy = y - self._goal_y
        to_goal2 = gx * gx + gy * gy
        reached = to_goal2 <= self._goal_r2
        mode = self.mode
        if mode == "maze":
            return self._along(x, y, math.sqrt(to_goal2)), reached
        if mode == "straight":
            return math.sqrt(to_goal2), reached
        return 0.0, reached

    def _along(self, x: float, y: float, to_goal: float) -> float:
        """Shepard's interpolation inside the cell of (x, y) (see :mod:`mazesim.envs.reward`)."""
        size = self._size
        origin_x, origin_y = self._origin_x, self._origin_y
        col = min(max(math.floor((x - origin_x) / size), 0), self._last_col)
        up = min(max(math.floor((y - origin_y) / size), 0), self._last_row)
        half = 0.5 * size
        u = x - (origin_x + (col + 0.5) * size)
        v = y - (origin_y + (up + 0.5) * size)
        cell = self._cells[(self._last_row - up) * self._cols + col]
        north, east, south, west, goal = cell[NORTH], cell[EAST], cell[SOUTH], cell[WEST], cell[4]
        w0 = north[1] / max(half - v, _NEAREST)
        w1 = east[1] / max(half - u, _NEAREST)
        w2 = south[1] / max(half + v, _NEAREST)
        w3 = west[1] / max(half + u, _NEAREST)
        w4 = goal[1] / max(to_goal, _NEAREST)
        weighted = w0 * north[0] + w1 * east[0] + w2 * south[0] + w3 * west[0] + w4 * goal[0]
        return weighted / (w0 + w1 + w2 + w3 + w4)
