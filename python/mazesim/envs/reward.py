"""The environments' reward: goal bonus, collision penalty and progress along the shortest path.

The reward of one control step is::

    reward = progress * (d_before - d_after) - collision * colliding + goal * reached

where ``d`` is the shortest-path distance from the robot's centre to the goal in metres (below),
``colliding`` is 1 while the body touches a wall (so every step spent against a wall costs the
penalty) and ``reached`` is 1 on the step the robot's centre enters the goal disc, which ends the
episode. Because the progress term is a difference of one potential, ``d``, a detour or a loop earns
nothing overall: an episode's progress reward sums to ``progress * (d_start - d_end)``.

The distance ``d`` on a cell maze (a world with a ``[grid]``, such as ``seed-maze`` and every
generated maze) is measured in two stages. A breadth-first search over the open cells counts the
cells from each cell to the goal cell; a cell ``k`` cells away lies at ``D = k * cell_size``, its
centre being that far from the goal along the corridors. Inside a cell, ``d`` blends the values of
the cell's open sides, each the mean of the ``D`` of the two cells it joins, and of the goal point
(0) in the goal cell, with weights inversely proportional to the distance from the robot to each
side (Shepard's interpolation). So ``d`` is continuous across open sides, falls linearly along a
straight corridor and bends smoothly round corners; a dead end gets its back wall as one more side,
half a cell farther than its centre, so backing into it still costs. In a world without a cell maze
``d`` is the straight-line distance to the goal, and in a world without a goal it is 0 (no progress
reward and no termination).

Everything here is vectorised over environments, and a single environment runs the same code on
arrays of one row, so the native vector environment and a ``SyncVectorEnv`` agree bit for bit.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from mazesim.errors import InvalidArgumentError

if TYPE_CHECKING:
    from mazesim._core import World

__all__ = ["GoalDistance", "PathDistanceTable", "RewardWeights", "step_reward"]

#: Side order of the interpolation targets: north, east, south, west, then the goal point.
_SIDES = ("north", "east", "south", "west")
_TARGETS = len(_SIDES) + 1
#: Smallest distance used in an inverse-distance weight (metres), so a side never divides by zero.
_NEAREST = 1e-9


@dataclass(frozen=True)
class RewardWeights:
    """The documented weights of the reward.

    Attributes:
        goal: Bonus on the step the robot's centre enters the goal disc.
        collision: Penalty for every control step the body touches a wall.
        progress: Reward per metre gained along the shortest path to the goal (negative when the
            robot moves away from the goal).
    """

    goal: float = 10.0
    collision: float = 0.1
    progress: float = 10.0

    def __post_init__(self) -> None:
        for name in ("goal", "collision", "progress"):
            value = getattr(self, name)
            if not isinstance(value, (int, float)) or not math.isfinite(value):
                raise InvalidArgumentError(
                    f"expected a finite number for the {name} reward weight, found {value!r}"
                )


@dataclass(frozen=True)
class PathDistanceTable:
    """What the distance to the goal needs to know about one world.

    Attributes:
        mode: ``"maze"`` (cell maze), ``"straight"`` (straight line to the goal) or ``"none"``
            (no goal).
        rows: Cell rows (1 without a maze).
        cols: Cell columns (1 without a maze).
        cell_size: Side of a cell in metres (1.0 without a maze).
        origin: World position of the grid's south-west corner.
        goal: (x, y, radius) of the goal disc, or (0, 0, -1) without a goal.
        targets: (rows * cols, 5) values of the north, east, south and west sides and of the goal
            point for each cell (row-major from the north-west cell), NaN where a side is no target.
    """

    mode: str
    rows: int
    cols: int
    cell_size: float
    origin: tuple[float, float]
    goal: tuple[float, float, float]
    targets: npt.NDArray[np.float64]

    @classmethod
    def of_world(cls, world: World) -> PathDistanceTable:
        """Builds the table of a world: a breadth-first search over its cell maze, if it has one."""
        goal = world.goal
        if goal is None:
            return cls("none", 1, 1, 1.0, (0.0, 0.0), (0.0, 0.0, -1.0), np.full((1, _TARGETS), 0.0))
        maze = world.cell_maze()
        if maze is None:
            targets = np.full((1, _TARGETS), np.nan)
            return cls("straight", 1, 1, 1.0, (0.0, 0.0), goal, targets)
        horizontal = np.asarray(maze["horizontal"], dtype=bool)
        vertical = np.asarray(maze["vertical"], dtype=bool)
        rows, cols = vertical.shape[0], horizontal.shape[1]
        size = float(maze["cell_size"])  # type: ignore[arg-type]
        origin_x, origin_y = (float(v) for v in maze["origin"])  # type: ignore[attr-defined]
        goal_cell = maze.get("goal")
        if goal_cell is None:
            col = min(max(int((goal[0] - origin_x) // size), 0), cols - 1)
            row = rows - 1 - min(max(int((goal[1] - origin_y) // size), 0), rows - 1)
        else:
            col, row = (int(v) for v in goal_cell)  # type: ignore[attr-defined]
        targets = _cell_targets(horizontal, vertical, (row, col), size)
        return cls("maze", rows, cols, size, (origin_x, origin_y), goal, targets)


def _cell_targets(
    horizontal: npt.NDArray[np.bool_],
    vertical: npt.NDArray[np.bool_],
    goal: tuple[int, int],
    size: float,
) -> npt.NDArray[np.float64]:
    """The interpolation targets of every cell (see the module's description)."""
    rows, cols = vertical.shape[0], horizontal.shape[1]
    north_walls, west_walls = horizontal.tolist(), vertical.tolist()
    # (side, row, col) of each cell reached through an open side, sides as in _SIDES.
    links: list[list[list[tuple[int, int, int]]]] = [[[] for _ in range(cols)] for _ in range(rows)]
    for row in range(rows):
        for col in range(cols):
            out = links[row][col]
            if row > 0 and not north_walls[row][col]:
                out.append((0, row - 1, col))
            if col < cols - 1 and not west_walls[row][col + 1]:
                out.append((1, row, col + 1))
            if row < rows - 1 and not north_walls[row + 1][col]:
                out.append((2, row + 1, col))
            if col > 0 and not west_walls[row][col]:
                out.append((3, row, col - 1))
    steps = [[-1] * cols for _ in range(rows)]
    steps[goal[0]][goal[1]] = 0
    queue = deque([goal])
    while queue:
        row, col = queue.popleft()
        for _, next_row, next_col in links[row][col]:
            if steps[next_row][next_col] < 0:
                steps[next_row][next_col] = steps[row][col] + 1
                queue.append((next_row, next_col))
    unreachable = (max(max(line) for line in steps) + 1) * size
    nan = math.nan
    targets = []
    for row in range(rows):
        for col in range(cols):
            values = [nan] * _TARGETS
            targets.append(values)
            if steps[row][col] < 0:
                values[: len(_SIDES)] = [unreachable] * len(_SIDES)
                continue
            here = steps[row][col] * size
            for side, next_row, next_col in links[row][col]:
                if steps[next_row][next_col] >= 0:
                    values[side] = 0.5 * (here + steps[next_row][next_col] * size)
            if (row, col) == goal:
                values[len(_SIDES)] = 0.0
                continue
            sides = [(value, side) for side, value in enumerate(values[: len(_SIDES)])]
            known = [(value, side) for value, side in sides if not math.isnan(value)]
            if known and all(value <= here for value, _ in known):
                back = (min(known)[1] + 2) % len(_SIDES)
                if math.isnan(values[back]):
                    values[back] = here + 0.5 * size
    return np.array(targets, dtype=np.float64)


class GoalDistance:
    """The shortest-path distances to the goal of N environments, each in its own world.

    Args:
        num_envs: Number of environments.
        table: The table every environment starts with.
    """

    def __init__(self, num_envs: int, table: PathDistanceTable) -> None:
        self.num_envs = num_envs
        self._cells = table.rows * table.cols
        self._modes = [table.mode] * num_envs
        self._kinds = frozenset(self._modes)
        self._has_goal = np.zeros(num_envs, dtype=bool)
        self._last_row = np.zeros(num_envs)
        self._last_col = np.zeros(num_envs)
        self._cols = np.zeros(num_envs, dtype=np.intp)
        self._size = np.zeros(num_envs)
        self._origin_x = np.zeros(num_envs)
        self._origin_y = np.zeros(num_envs)
        self._goal_x = np.zeros(num_envs)
        self._goal_y = np.zeros(num_envs)
        self._goal_r2 = np.zeros(num_envs)
        # Per env and cell: the 5 target values (0 where absent), then 5 presence flags (0 or 1).
        self._targets = np.zeros((num_envs * self._cells, 2 * _TARGETS))
        self._first_cell = np.arange(num_envs, dtype=np.intp) * self._cells
        self.set(np.arange(num_envs), table)

    def set(self, envs: npt.NDArray[np.intp] | int, table: PathDistanceTable) -> None:
        """Puts the environments ``envs`` (indices) into the world described by ``table``."""
        cells = table.rows * table.cols
        if cells > self._cells:
            grown = np.zeros((self.num_envs, cells, 2 * _TARGETS))
            grown[:, : self._cells] = self._targets.reshape(self.num_envs, self._cells, -1)
            self._targets = grown.reshape(self.num_envs * cells, -1)
            self._first_cell = np.arange(self.num_envs, dtype=np.intp) * cells
            self._cells = cells
        for env in np.atleast_1d(envs):
            self._modes[int(env)] = table.mode
        if self._kinds != {table.mode}:
            self._kinds = frozenset(self._modes)
        self._has_goal[envs] = table.mode != "none"
        self._last_row[envs] = table.rows - 1
        self._last_col[envs] = table.cols - 1
        self._cols[envs] = table.cols
        self._size[envs] = table.cell_size
        self._origin_x[envs], self._origin_y[envs] = table.origin
        self._goal_x[envs], self._goal_y[envs] = table.goal[0], table.goal[1]
        self._goal_r2[envs] = table.goal[2] * table.goal[2] if table.mode != "none" else -1.0
        present = ~np.isnan(table.targets)
        rows = np.concatenate((np.where(present, table.targets, 0.0), present), axis=1)
        view = self._targets.reshape(self.num_envs, self._cells, -1)
        view[envs, :cells] = rows

    def evaluate(
        self, poses: npt.NDArray[np.float32]
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.bool_]]:
        """Shortest-path distances (N,) in metres to the goal from (N, 3) ``poses``, and whether
        each robot's centre lies in its goal disc."""
        x = poses[:, 0].astype(np.float64)
        y = poses[:, 1].astype(np.float64)
        gx = x - self._goal_x
        gy = y - self._goal_y
        to_goal2 = gx * gx + gy * gy
        to_goal = np.sqrt(to_goal2)
        reached = to_goal2 <= self._goal_r2
        modes = self._kinds
        if modes == {"none"}:
            return np.zeros(self.num_envs), reached
        if modes == {"straight"}:
            return to_goal, reached
        size = self._size
        col = np.minimum(np.maximum(np.floor((x - self._origin_x) / size), 0.0), self._last_col)
        up = np.minimum(np.maximum(np.floor((y - self._origin_y) / size), 0.0), self._last_row)
        half = 0.5 * size
        u = x - (self._origin_x + (col + 0.5) * size)
        v = y - (self._origin_y + (up + 0.5) * size)
        cell = (self._last_row - up).astype(np.intp) * self._cols + col.astype(np.intp)
        targets = np.take(self._targets, self._first_cell + cell, axis=0)
        gaps = np.stack((half - v, half - u, half + v, half + u, to_goal), axis=1)
        weights = targets[:, _TARGETS:] / np.maximum(gaps, _NEAREST)
        terms = weights * targets[:, :_TARGETS]
        weighted = terms[:, 0] + terms[:, 1] + terms[:, 2] + terms[:, 3] + terms[:, 4]
        total = weights[:, 0] + weights[:, 1] + weights[:, 2] + weights[:, 3] + weights[:, 4]
        along = weighted / total
        if modes == {"maze"}:
            return along, reached
        maze = np.array([mode == "maze" for mode in self._modes])
        return np.where(maze, along, np.where(self._has_goal, to_goal, 0.0)), reached


def step_reward(
    weights: RewardWeights,
    before: npt.NDArray[np.float64],
    after: npt.NDArray[np.float64],
    colliding: npt.NDArray[np.bool_],
    reached: npt.NDArray[np.bool_],
) -> npt.NDArray[np.float64]:
    """The reward of one control step for each environment (see the module's description)."""
    return (
        weights.progress * (before - after)
        - weights.collision * colliding.astype(np.float64)
        + weights.goal * reached.astype(np.float64)
    )
