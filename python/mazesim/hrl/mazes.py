"""Cell mazes for training and evaluation: openings, shortest paths, door approaches, start poses.

A :class:`CellMaze` wraps :meth:`mazesim.World.cell_maze` of a ``[grid]`` world. Cells are
``(column, row)`` with row 0 on the north edge; directions are numbered counter-clockwise from
east, so direction ``d`` has the heading ``d * pi / 2``: 0 east, 1 north, 2 west, 3 south.

Training reads the maze (the learner never does): where the doors are, which way a turn leads,
and how far the goal is. :func:`world_with_start` makes a copy of a world with another start pose,
which is how a batch environment is put at any pose (:meth:`mazesim.BatchSimulator.set_world`).
"""

from __future__ import annotations

import hashlib
import math
import re
from collections import deque
from dataclasses import dataclass
from typing import cast

import numpy as np
import numpy.typing as npt

from mazesim._core import World
from mazesim.errors import InvalidArgumentError

__all__ = [
    "EAST",
    "NORTH",
    "SOUTH",
    "WEST",
    "CellMaze",
    "DoorApproach",
    "checkpoint_ids",
    "world_hash",
    "world_with_start",
]

EAST, NORTH, WEST, SOUTH = 0, 1, 2, 3
#: (column, row) step of each direction (rows grow southwards).
_STEP = {EAST: (1, 0), NORTH: (0, -1), WEST: (-1, 0), SOUTH: (0, 1)}


def checkpoint_ids(world: World) -> list[int]:
    """The ids of a world's checkpoints, in increasing order."""
    return sorted(int(cast(int, checkpoint["id"])) for checkpoint in world.checkpoints())


def world_hash(world: World) -> str:
    """The sha256 of the world's description (:meth:`mazesim.World.to_toml`), in hex."""
    return hashlib.sha256(world.to_toml().encode("utf-8")).hexdigest()


_START_TABLE = re.compile(r"^\[start\]\n(?:(?!\[)[^\n]*\n)*", re.MULTILINE)


def world_with_start(world: World, x: float, y: float, yaw: float) -> World:
    """A copy of ``world`` whose robot starts at ``(x, y, yaw)``.

    Args:
        world: The world to copy.
        x: Start x in metres.
        y: Start y in metres.
        yaw: Start heading in radians (counter-clockwise from +x).

    Returns:
        The same walls, paint, checkpoints and goal with a ``[start]`` table of that pose.
    """
    text = _START_TABLE.sub("", world.to_toml())
    start = f"\n[start]\nx = {float(x)!r}\ny = {float(y)!r}\nyaw = {float(yaw)!r}\n"
    return World.from_toml(text + start, source=f"{world.name} (start moved)")


@dataclass(frozen=True)
class DoorApproach:
    """A way into a door (a junction cell with three or four openings).

    Attributes:
        cell: The cell the robot starts in, next to the door.
        door: The door cell.
        heading: The direction from ``cell`` to ``door``.
        straight: ``cell`` is open only towards the door and straight behind (or a dead end), so
            nothing opens on its sides: the generator paints this approach's checkpoint in its
            middle (otherwise, after a corner or from a neighbouring door, across the edge
            between ``cell`` and ``door``).
    """

    cell: tuple[int, int]
    door: tuple[int, int]
    heading: int
    straight: bool


class CellMaze:
    """The cells and walls of a grid world.

    Args:
        world: A world with a ``[grid]`` maze.

    Raises:
        InvalidArgumentError: The world has no cell maze.
    """

    def __init__(self, world: World) -> None:
        maze = world.cell_maze()
        if maze is None:
            raise InvalidArgumentError(
                f"expected a world with a [grid] cell maze, found none in {world.name!r}"
            )
        self.rows = int(cast(int, maze["rows"]))
        self.cols = int(cast(int, maze["cols"]))
        self.cell_size = float(cast(float, maze["cell_size"]))
        origin = cast("tuple[float, float]", maze["origin"])
        self.origin = (float(origin[0]), float(origin[1]))
        self.horizontal = np.asarray(maze["horizontal"], dtype=bool)
        self.vertical = np.asarray(maze["vertical"], dtype=bool)
        start = cast("tuple[int, int] | None", maze["start"])
        goal = cast("tuple[int, int] | None", maze["goal"])
        self.start_cell = None if start is None else (int(start[0]), int(start[1]))
        self.goal_cell = None if goal is None else (int(goal[0]), int(goal[1]))

    def is_open(self, cell: tuple[int, int], direction: int) -> bool:
        """True when no wall closes ``cell`` on side ``direction``."""
        column, row = cell
        if direction == EAST:
            return not self.vertical[row, column + 1]
        if direction == WEST:
            return not self.vertical[row, column]
        if direction == NORTH:
            return not self.horizontal[row, column]
        return not self.horizontal[row + 1, column]

    def openings(self, cell: tuple[int, int]) -> list[int]:
        """The open directions of a cell, in direction order."""
        return [d for d in range(4) if self.is_open(cell, d)]

    def neighbour(self, cell: tuple[int, int], direction: int) -> tuple[int, int]:
        """The cell next to ``cell`` in ``direction`` (whether or not a wall is between)."""
        step_column, step_row = _STEP[direction]
        return cell[0] + step_column, cell[1] + step_row

    def cells(self) -> list[tuple[int, int]]:
        """Every cell, row by row from the north-west corner."""
        return [(column, row) for row in range(self.rows) for column in range(self.cols)]

    def center(self, cell: tuple[int, int]) -> tuple[float, float]:
        """The world coordinates of a cell's centre."""
        column, row = cell
        return (
            self.origin[0] + (column + 0.5) * self.cell_size,
            self.origin[1] + (self.rows - row - 0.5) * self.cell_size,
        )

    def cell_at(self, x: npt.ArrayLike, y: npt.ArrayLike) -> tuple[npt.NDArray[np.int64], ...]:
        """The (column, row) arrays of the cells holding the points (clipped to the grid)."""
        column = np.floor((np.asarray(x) - self.origin[0]) / self.cell_size).astype(np.int64)
        row_from_south = np.floor((np.asarray(y) - self.origin[1]) / self.cell_size)
        row = (self.rows - 1 - row_from_south).astype(np.int64)
        return np.clip(column, 0, self.cols - 1), np.clip(row, 0, self.rows - 1)

    def distances_from(self, cell: tuple[int, int]) -> npt.NDArray[np.int64]:
        """Breadth-first cell distances from ``cell``, shape (rows, cols); -1 where unreachable."""
        distance = np.full((self.rows, self.cols), -1, dtype=np.int64)
        distance[cell[1], cell[0]] = 0
        queue = deque([cell])
        while queue:
            here = queue.popleft()
            for direction in self.openings(here):
                there = self.neighbour(here, direction)
                if distance[there[1], there[0]] < 0:
                    distance[there[1], there[0]] = distance[here[1], here[0]] + 1
                    queue.append(there)
        return distance

    def shortest_path_length(self) -> float:
        """Metres from the start cell's centre to the goal cell's centre along the cells."""
        if self.start_cell is None or self.goal_cell is None:
            raise InvalidArgumentError("expected a maze with a start and a goal cell")
        moves = self.distances_from(self.start_cell)[self.goal_cell[1], self.goal_cell[0]]
        if moves < 0:
            raise InvalidArgumentError("the goal cell cannot be reached from the start cell")
        return float(moves) * self.cell_size

    def is_door(self, cell: tuple[int, int]) -> bool:
        """A door is a junction: a cell with three or four openings."""
        return len(self.openings(cell)) >= 3

    def door_approaches(self) -> list[DoorApproach]:
        """Every (cell, door) pair where the cell opens into a door, in cell order."""
        approaches = []
        for door in self.cells():
            if not self.is_door(door):
                continue
            for side in self.openings(door):
                cell = self.neighbour(door, side)
                heading = (side + 2) % 4
                open_sides = self.openings(cell)
                straight = set(open_sides) <= {heading, side}
                approaches.append(DoorApproach(cell, door, heading, straight))
        return approaches

    def code_centre(self, approach: DoorApproach) -> tuple[float, float]:
        """Where the generator paints the middle of an approach's code: the middle of a straight
        approach cell, else the middle of the edge between the cell and the door."""
        x, y = self.center(approach.cell)
        if approach.straight:
            return x, y
        shift = self.cell_size / 2.0
        angle = self.heading_of(approach.heading)
        return x + shift * round(math.cos(angle)), y + shift * round(math.sin(angle))

    def heading_of(self, direction: int) -> float:
        """The heading in radians of a direction number."""
        return direction * math.pi / 2.0
