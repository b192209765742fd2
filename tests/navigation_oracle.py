"""The numpy navigation features the gymnasium tasks observed before the core computed them
(``mazesim._core.TaskFeatures``): the oracle the core's observations are checked against, bit
for bit, in ``tests/envs/test_task_features.py``, with its numpy planner (:func:`next_cells`,
:func:`assumed_open_sides`, :func:`planned_waypoints`)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._core import World
from mazesim.envs.navigation import NavigationFeatures, _waypoints
from mazesim.errors import InvalidArgumentError
from mazesim.maze import (
    EAST,
    NORTH,
    SOUTH,
    WEST,
    CellMaze,
    PathDistanceTable,
    _inside,
    breadth_first_distances,
)

_VISITS_SEEN = 3.0
_SIDES = 4
#: The (column, row) step of each direction (row 0 north).
_STEP = {EAST: (1, 0), NORTH: (0, -1), WEST: (-1, 0), SOUTH: (0, 1)}


def next_cells(
    open_sides: npt.NDArray[np.bool_], targets: npt.NDArray[np.int64]
) -> npt.NDArray[np.int64]:
    """The way to a target cell in K mazes of one shape.

    Args:
        open_sides: (K, rows, cols, 4) open sides, as for ``mazesim.maze.breadth_first_distances``.
        targets: (K, 2) the (column, row) target cell of each maze.

    Returns:
        (K, rows, cols, 2): the (column, row) of the next cell on a shortest path from each cell
        to its maze's target: across the first open side in direction order whose neighbour is
        one step nearer; -1, -1 in the target and in the cells that cannot reach it.
    """
    count, rows, cols, _ = open_sides.shape
    steps = breadth_first_distances(open_sides, targets)
    around = np.full((count, rows + 2, cols + 2), -2, dtype=np.int64)
    around[:, 1:-1, 1:-1] = steps
    step = np.array([_STEP[direction] for direction in range(_SIDES)])  # (column, row) steps
    neighbours = np.stack(
        [around[:, 1 + r : 1 + r + rows, 1 + c : 1 + c + cols] for c, r in step], axis=-1
    )
    nearer = open_sides & (neighbours == steps[..., None] - 1) & (steps[..., None] > 0)
    direction = nearer.argmax(axis=-1)
    row, column = np.indices((rows, cols))
    following = np.stack((column, row), axis=-1)[None] + step[direction]
    following[~nearer.any(axis=-1)] = -1
    return following


def assumed_open_sides(
    open_sides: npt.NDArray[np.bool_], visited: npt.NDArray[np.bool_]
) -> npt.NDArray[np.bool_]:
    """The open sides of K mazes as robots that have visited some of their cells know them.

    The sides of a visited cell are as they are (the robot saw them from inside, and so the side
    its neighbour shares with it); every other side is assumed open (the free-space assumption
    of a mapping robot); the grid's edge is known to be walled.

    Args:
        open_sides: (K, rows, cols, 4) the true open sides (``CellMaze.open_sides``).
        visited: (K, rows, cols) the cells each robot has been in.

    Raises:
        InvalidArgumentError: ``visited`` is not of the mazes' shape.
    """
    if visited.shape != open_sides.shape[:3]:
        raise InvalidArgumentError(
            f"expected visited cells of shape {open_sides.shape[:3]}, found shape {visited.shape}"
        )
    count, rows, cols, _ = open_sides.shape
    around = np.zeros((count, rows + 2, cols + 2), dtype=bool)
    around[:, 1:-1, 1:-1] = visited
    seen = np.stack(
        [
            visited | around[:, 1 + r : 1 + r + rows, 1 + c : 1 + c + cols]
            for c, r in (_STEP[direction] for direction in range(_SIDES))
        ],
        axis=-1,
    )
    return (open_sides | ~seen) & _inside(rows, cols)


def planned_waypoints(
    open_sides: npt.NDArray[np.bool_],
    goal_cells: npt.NDArray[np.int64],
    goals: npt.NDArray[np.float64],
    origins: npt.NDArray[np.float64],
    sizes: npt.NDArray[np.float64],
) -> npt.NDArray[np.float64]:
    """The next waypoint of every cell of K mazes of one shape on a shortest path to their goals.

    Args:
        open_sides: (K, rows, cols, 4) the open sides the path may take (the true ones, or
            :func:`assumed_open_sides`).
        goal_cells: (K, 2) the (column, row) goal cell of each maze.
        goals: (K, 2) the goal point (x, y) of each maze.
        origins: (K, 2) the south-west corner of each grid.
        sizes: (K,) the cell size of each maze.

    Returns:
        (K, rows * cols, 2) waypoints (x, y), cells row-major from the north-west: the centre of
        the next cell (:func:`next_cells`: the open neighbour nearest the goal, the
        first in direction order on a tie), the goal point in the goal cell and in cells from
        which it cannot be reached.
    """
    count, rows, cols, _ = open_sides.shape
    following = next_cells(open_sides, goal_cells).reshape(count, rows * cols, 2)
    points = np.empty((count, rows * cols, 2))
    points[..., 0] = origins[:, None, 0] + (following[..., 0] + 0.5) * sizes[:, None]
    points[..., 1] = origins[:, None, 1] + (rows - following[..., 1] - 0.5) * sizes[:, None]
    nowhere = following[..., 0] < 0
    points[nowhere] = np.broadcast_to(goals[:, None, :], points.shape)[nowhere]
    return points


class NumpyNavigationFeatures:
    """The numpy features of N environments of the kind of ``features`` (the core's), with its
    bounds and sensor scale."""

    def __init__(self, features: NavigationFeatures) -> None:
        num_envs, _, _, scale = features._arguments
        self.sensor_width = features.sensor_width
        self._scale = scale
        self.guided, self.plan = features.guided, features.plan
        self.pose, self.explore = features.pose, features.explore
        self.low, self.high = features.low, features.high
        self._goal = np.zeros((num_envs, 2))
        self._extent = np.ones(num_envs)
        self._corner = np.zeros((num_envs, 2))
        self._size = np.ones(num_envs)
        self._origin = np.zeros((num_envs, 2))
        self._shape = np.ones((num_envs, 2), dtype=np.intp)  # rows, cols
        self._cells = 1
        self._waypoints = np.zeros((num_envs, 1, 2))
        # The explored map: which sides of each cell are open (direction order), the visits of
        # each cell this episode, and the cell each robot was last seen in (-1: none yet).
        self._open = np.zeros((num_envs, 1, 4))
        self._visits = np.zeros((num_envs, 1))
        self._last = np.full(num_envs, -1, dtype=np.intp)
        # The plan: whether each environment has a cell maze to plan in, and its goal cell.
        self._plannable = np.zeros(num_envs, dtype=bool)
        self._goal_cells = np.zeros((num_envs, 2), dtype=np.int64)  # column, row

    def set(self, env: int | npt.NDArray[np.intp], world: World, table: PathDistanceTable) -> None:
        """Puts environment(s) ``env`` into ``world`` (whose distance table is ``table``)."""
        self._goal[env] = table.goal[:2]
        xmin, ymin, xmax, ymax = world.bounds
        self._extent[env] = max(xmax - xmin, ymax - ymin, 1e-6)
        self._corner[env] = (xmin, ymin)
        self._size[env] = table.cell_size
        self._origin[env] = table.origin
        self._shape[env] = (table.rows, table.cols)
        waypoints = _waypoints(table)
        cells = max(len(waypoints), table.rows * table.cols)
        if cells > self._cells:
            n = len(self._goal)
            grown = np.zeros((n, cells, 2))
            grown[:, : self._cells] = self._waypoints
            opened = np.zeros((n, cells, 4))
            opened[:, : self._cells] = self._open
            visits = np.zeros((n, cells))
            visits[:, : self._cells] = self._visits
            self._waypoints, self._open, self._visits = grown, opened, visits
            self._cells = cells
        self._waypoints[env, : len(waypoints)] = waypoints
        # The true open sides of the cells (all closed without a cell maze).
        maze = CellMaze(world) if self.explore and table.mode == "maze" else None
        if self.explore:
            sides = 0.0 if maze is None else maze.open_sides().reshape(-1, 4)
            self._open[env, : table.rows * table.cols] = sides
        if self.plan:
            self._plannable[env] = maze is not None
            if maze is not None:
                column, row = maze.cell_at(table.goal[0], table.goal[1])
                self._goal_cells[env] = (int(column), int(row))
        self.restart(env)

    def restart(self, env: int | npt.NDArray[np.intp]) -> None:
        """Forgets the explored map's visits of environment(s) ``env`` (a new episode); the plan
        is made again at the next observation, from the robot's first cell."""
        self._visits[env] = 0.0
        self._last[env] = -1

    def observe(
        self,
        readings: npt.NDArray[np.float32],
        poses: npt.NDArray[np.float32],
        previous: npt.NDArray[np.float32],
    ) -> npt.NDArray[np.float32]:
        """(N, width) observations from (N, sensor_width) raw readings, (N, 3) poses and the
        (N, 2) previous actions as wheel speed fractions."""
        x = poses[:, 0].astype(np.float64)
        y = poses[:, 1].astype(np.float64)
        yaw = poses[:, 2].astype(np.float64)
        cos, sin = np.cos(yaw), np.sin(yaw)
        cell = self._cell(x, y)
        if self.explore:
            discovered = self._visit(cell)
            if self.plan and discovered.size:
                self._replan(discovered)
        parts: list[npt.NDArray[Any]] = [readings / self._scale]
        for target, unit in self._targets(cell):
            dx, dy = target[:, 0] - x, target[:, 1] - y
            parts += [
                ((cos * dx + sin * dy) / unit)[:, None],
                ((cos * dy - sin * dx) / unit)[:, None],
            ]
        if self.explore:
            parts.append(self._explored(cell, yaw))
        if self.pose:
            parts += [
                ((x - self._corner[:, 0]) / self._extent)[:, None],
                ((y - self._corner[:, 1]) / self._extent)[:, None],
                cos[:, None],
                sin[:, None],
            ]
        parts.append(previous)
        out = np.concatenate(parts, axis=1).astype(np.float32)
        np.maximum(out, self.low, out=out)
        np.minimum(out, self.high, out=out)
        return out

    def _cell(self, x: npt.NDArray[np.float64], y: npt.NDArray[np.float64]) -> npt.NDArray[np.intp]:
        """The cell (row-major from the north-west) each robot is in."""
        rows, cols = self._shape[:, 0], self._shape[:, 1]
        col = np.clip(np.floor((x - self._origin[:, 0]) / self._size), 0, cols - 1)
        up = np.clip(np.floor((y - self._origin[:, 1]) / self._size), 0, rows - 1)
        return (rows - 1 - up.astype(np.intp)) * cols + col.astype(np.intp)

    def _targets(
        self, cell: npt.NDArray[np.intp]
    ) -> list[tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]]:
        targets = [(self._goal, self._extent)]
        if self.guided or self.plan:
            waypoint = self._waypoints[np.arange(len(cell)), cell]
            targets.append((waypoint, self._size))
        return targets

    def _visit(self, cell: npt.NDArray[np.intp]) -> npt.NDArray[np.intp]:
        """Counts a visit of each robot that entered ``cell`` since the last observation; the
        environments whose robot entered a cell for the first time this episode."""
        envs = np.arange(len(cell))
        entered = envs[cell != self._last]
        first = entered[self._visits[entered, cell[entered]] == 0.0]
        self._visits[entered, cell[entered]] += 1.0
        self._last = cell
        return first

    def _replan(self, envs: npt.NDArray[np.intp]) -> None:
        """Plans again the waypoints of environments ``envs`` through their mazes as their robots
        know them now (their visited cells), all mazes of a shape at once."""
        envs = envs[self._plannable[envs]]
        shapes = self._shape[envs]
        same = envs.size == 0 or bool((shapes == shapes[0]).all())  # as a rule, one shape
        for rows, cols in (shapes[:1] if same else np.unique(shapes, axis=0)).tolist():
            group = envs[(shapes[:, 0] == rows) & (shapes[:, 1] == cols)]
            cells = rows * cols
            opened = self._open[group, :cells].reshape(-1, rows, cols, 4) > 0.0
            visited = self._visits[group, :cells].reshape(-1, rows, cols) > 0.0
            self._waypoints[group, :cells] = planned_waypoints(
                assumed_open_sides(opened, visited),
                self._goal_cells[group],
                self._goal[group],
                self._origin[group],
                self._size[group],
            )

    def _explored(
        self, cell: npt.NDArray[np.intp], yaw: npt.NDArray[np.float64]
    ) -> npt.NDArray[np.float64]:
        """(N, 9): the sides of each robot's cell ahead, left, behind and right of it (the side
        its heading is nearest first), open or not; the visits this episode of the cells across
        them (0 across a wall) and of its own cell, each up to ``_VISITS_SEEN`` and scaled to 1.
        Entering a cell counts a visit (:meth:`_visit`, before)."""
        envs = np.arange(len(cell))
        facing = np.round(yaw / (0.5 * math.pi)).astype(np.intp) % 4
        sides = (facing[:, None] + np.arange(4)[None, :]) % 4  # ahead, left, behind, right
        opened = self._open[envs[:, None], cell[:, None], sides]
        cols = self._shape[:, 1]
        steps = np.array([1, -1, -1, 1])[sides] * np.where(sides % 2 == 0, 1, cols[:, None])
        across = np.clip(cell[:, None] + steps, 0, self._cells - 1)
        seen = np.minimum(self._visits[envs[:, None], across], _VISITS_SEEN) / _VISITS_SEEN
        here = np.minimum(self._visits[envs, cell], _VISITS_SEEN) / _VISITS_SEEN
        return np.concatenate((opened, opened * seen, here[:, None]), axis=1)


#: Ties between sides in a dead end's back-wall test go north, east, south, west.
_TIE_ORDER = {NORTH: 0, EAST: 1, SOUTH: 2, WEST: 3}


def cell_targets(maze: CellMaze, goal: tuple[int, int]) -> npt.NDArray[np.float64]:
    """The goal-distance table's interpolation targets of every cell, as Python computed them
    before the core did (``World.distance_targets``): sides in direction order, then the goal
    point."""
    steps = maze.distances_from(goal)
    size = maze.cell_size
    unreachable = (int(steps.max()) + 1) * size
    targets = []
    for cell in maze.cells():
        column, row = cell
        values = [math.nan] * (_SIDES + 1)
        targets.append(values)
        if steps[row, column] < 0:
            values[:_SIDES] = [unreachable] * _SIDES
            continue
        here = float(steps[row, column]) * size
        for direction in maze.openings(cell):
            next_column, next_row = maze.neighbour(cell, direction)
            if steps[next_row, next_column] >= 0:
                values[direction] = 0.5 * (here + float(steps[next_row, next_column]) * size)
        if cell == goal:
            values[_SIDES] = 0.0
            continue
        known = [(v, side) for side, v in enumerate(values[:_SIDES]) if not math.isnan(v)]
        if known and all(value <= here for value, _ in known):
            nearest = min(known, key=lambda item: (item[0], _TIE_ORDER[item[1]]))[1]
            back = (nearest + 2) % _SIDES
            if math.isnan(values[back]):
                values[back] = here + 0.5 * size
    return np.array(targets, dtype=np.float64)


def largest_connected_cells(maze: CellMaze) -> list[tuple[int, int]]:
    """The (row, column) cells of the largest set of cells joined by open sides, as Python found
    them before the core did (``World.connected_cells``)."""
    best: list[tuple[int, int]] = []
    seen = np.zeros((maze.rows, maze.cols), dtype=bool)
    for column, row in maze.cells():
        if seen[row, column]:
            continue
        reach = maze.distances_from((column, row)) >= 0
        seen |= reach
        if int(reach.sum()) > len(best):
            best = [(int(r), int(c)) for r, c in zip(*np.nonzero(reach), strict=True)]
    return best
