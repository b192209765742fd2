"""The one cell-maze model: openings, shortest paths, door approaches, and the goal distance.

A :class:`CellMaze` wraps :meth:`mazesim.World.cell_maze` of a ``[grid]`` world. Cells are
``(column, row)`` with row 0 on the north edge; directions are numbered counter-clockwise from
east, so direction ``d`` has the heading ``d * pi / 2``: 0 east, 1 north, 2 west, 3 south. This
is the package's only direction convention and :func:`breadth_first_distances` its only maze
breadth-first search (:meth:`CellMaze.distances_from` for one maze, many mazes at once).

Training reads the maze (the learner never does): where the doors are, which way a turn leads,
and how far the goal is. :class:`GoalDistance` is the shortest-path distance to the goal that the
environments' reward uses (:mod:`mazesim.envs.reward`).
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass
from typing import cast

import numpy as np
import numpy.typing as npt

from mazesim._core import RobotProfile, Simulator, World
from mazesim._sizes import index_array
from mazesim.errors import InvalidArgumentError, _shown

__all__ = [
    "EAST",
    "NORTH",
    "SOUTH",
    "WEST",
    "CellMaze",
    "DoorApproach",
    "GoalDistance",
    "PathDistanceTable",
    "blocked_start",
    "breadth_first_distances",
    "checkpoint_ids",
    "looks_like_grid_map",
    "navigator_problems",
    "refuse_blocked_start",
    "world_hash",
    "world_source",
]

EAST, NORTH, WEST, SOUTH = 0, 1, 2, 3
#: Sides of a cell (the four directions); a goal-distance row has one more target, the goal.
_SIDES = 4
_TARGETS = _SIDES + 1
#: Smallest distance used in an inverse-distance weight (metres), so a side never divides by zero.
_NEAREST = 1e-9
#: (column, row) step of each direction (rows grow southwards).
_STEP = {EAST: (1, 0), NORTH: (0, -1), WEST: (-1, 0), SOUTH: (0, 1)}


def checkpoint_ids(world: World) -> list[int]:
    """The ids of a world's checkpoints, in increasing order."""
    return sorted(int(cast(int, checkpoint["id"])) for checkpoint in world.checkpoints())


def navigator_problems(world: World, *, show_command: str | None = None) -> list[str]:
    """What keeps the hierarchical navigator (and the flat baseline) from learning ``world``,
    each said with what to change; empty when it can learn it.

    A maze without checkpoints is told the ``[[checkpoints]]`` tables to paste, on lines of
    their own; with ``show_command`` (``"mazesim show my-maze.toml"``), for a message of one
    line, it is told to run that command, which prints them.

    The navigator needs a ``[grid]`` cell maze, a goal, a start cell from which the goal can be
    reached along the cells, a start pose inside the maze and clear of its walls, and barcode
    checkpoints: its higher level decides only where it reads
    one, so in a world without any it would drive, learn nothing and save a navigator that
    cannot be evaluated.
    """
    if world.cell_maze() is None:
        return [
            "it has no [grid] cell maze: draw the maze as a [grid] map (docs/world-format.md) or "
            "generate one with mazesim.generate_maze"
        ]
    problems = []
    maze = CellMaze(world)
    if world.goal is None or maze.goal_cell is None:
        problems.append(
            "it has no goal: put a G in a cell of the [grid] map, or add a [goal] table with a "
            "center inside the maze"
        )
    elif maze.start_cell is None:
        between = maze.cells_touching(float(world.start[0]), float(world.start[1]))
        if len(between) > 1:  # outside the maze (none): _start_problem says so
            cells = " and ".join(f"(column {c}, row {r})" for c, r in between)
            centres = " or ".join("({:g}, {:g})".format(*maze.center(cell)) for cell in between)
            problems.append(
                f"its start ({float(world.start[0]):g}, {float(world.start[1]):g}) is on the "
                f"line between the cells {cells}, so it is in none of them: move the [start] "
                f"pose to a cell's centre, {centres}"
            )
    else:
        marked = maze.marked_start
        if marked is not None and marked != maze.start_cell:
            problems.append(
                f"its [start] pose ({float(world.start[0]):g}, {float(world.start[1]):g}) is in "
                f"the cell (column {maze.start_cell[0]}, row {maze.start_cell[1]}), but the S of "
                f"the [grid] map is in (column {marked[0]}, row {marked[1]}), and the robot "
                "starts at the [start] pose: delete the [start] table to start at the S, or move "
                "the S to the pose's cell"
            )
        column, row = maze.goal_cell
        if maze.distances_from(maze.start_cell)[row, column] < 0:
            problems.append(
                f"its goal (cell column {column}, row {row}) cannot be reached from the start "
                f"(cell column {maze.start_cell[0]}, row {maze.start_cell[1]}): open a way "
                "through the walls of the [grid] map, or move S or G"
            )
    start = _start_problem(world, maze)
    if start is not None:
        problems.append(start)
    if not world.checkpoints():
        problems.append(_checkpoints_problem(world, show_command))
    return problems


def _checkpoints_problem(world: World, show_command: str | None) -> str:
    """What to add to a world without barcode checkpoints: the ``[[checkpoints]]`` tables that
    :func:`mazesim.generate_maze` would place on its maze, ready to paste, or, for a maze without
    a junction, where to open one."""
    why = "it has no barcode checkpoints, and the navigator decides only where it reads one"
    tables = world.junction_checkpoints()
    if not tables:
        return (
            f"{why}, and its maze has no junction (a cell with three or four openings) to put one "
            "before: open a wall of the [grid] map so that a corridor branches, or draw the maze "
            "with mazesim.generate_maze"
        )
    if show_command is not None:
        return (
            f"{why}: add the [[checkpoints]] tables, one on every way into every junction as "
            f"mazesim.generate_maze places them, that this command prints: {show_command}"
        )
    count = tables.count("[[checkpoints]]")
    floor = (
        "the grey [floor] of generated mazes (on a white one the codes' ends do not show) and "
        if tables.startswith("[floor]")
        else ""
    )
    return (
        f"{why}: add {floor}these {count} [[checkpoints]] (one on every way into every junction, "
        "as mazesim.generate_maze places them) at the end of the world file:\n\n" + tables.strip()
    )


def _start_problem(world: World, maze: CellMaze) -> str | None:
    """What keeps the robot from starting at the world's start pose (outside the maze's cells, or
    in a wall), said with what to change; None when it can start there."""
    x, y = float(world.start[0]), float(world.start[1])
    east, north = (
        maze.origin[0] + maze.cols * maze.cell_size,
        maze.origin[1] + maze.rows * maze.cell_size,
    )
    if not (maze.origin[0] <= x <= east and maze.origin[1] <= y <= north):
        return (
            f"its start ({x:g}, {y:g}) is outside the maze, which spans x {maze.origin[0]:g} to "
            f"{east:g} and y {maze.origin[1]:g} to {north:g}: {_MOVE_START_IN_A_MAZE}"
        )
    return blocked_start(world)


_MOVE_START_IN_A_MAZE = (
    "move the [start] pose to the middle of a cell, or put an S in a cell of the [grid] map"
)

#: The words of the core's refusal of a pose in or against a wall (its ``check_free``).
_NOT_CLEAR = "is clear of the walls"


def blocked_start(world: World, robot: str | RobotProfile = "e-puck") -> str | None:
    """What keeps ``robot`` from starting at the world's start pose (in or against a wall): the
    pose, how far into the wall, and what to change in the world; None when it can start there.

    Raises:
        InvalidArgumentError: ``robot`` cannot drive in ``world`` for another reason.
    """
    try:
        Simulator(world, robot=robot)
    except InvalidArgumentError as blocked:
        if _NOT_CLEAR not in str(blocked):
            raise
        fix = (
            _MOVE_START_IN_A_MAZE
            if world.cell_maze() is not None
            else "move the [start] pose to open floor, farther from every wall than the robot's "
            "radius"
        )
        return f"{blocked}: {fix}"
    return None


def refuse_blocked_start(world: World, name: str, robot: str | RobotProfile = "e-puck") -> None:
    """Refuses a world, loaded from ``name`` (a built-in name or a world file), whose start pose
    puts ``robot`` in or against a wall: one message for every command that loads a world, naming
    the world, its file, the pose and what to change, before the simulator refuses it.

    Raises:
        InvalidArgumentError: :func:`blocked_start` finds the start blocked.
    """
    problem = blocked_start(world, robot)
    if problem is not None:
        raise InvalidArgumentError(f"world {world_source(world, name)}: {problem}")


def world_source(world: World, name: str) -> str:
    """The world and where it was loaded from, for messages: ``seed-maze`` for a built-in
    world, ``'my-maze' (worlds/my-maze.toml)`` for a file."""
    return name if name == world.name else f"{_shown(world.name)} ({name})"


#: The characters of a ``[grid]`` map: corners, walls, open sides, start and goal.
_GRID_MAP_CHARACTERS = frozenset("+-| SG")


def looks_like_grid_map(text: str) -> bool:
    """Whether ``text`` is a maze drawn as a ``[grid]`` map (docs/world-format.md) and nothing
    else: two rows or more of ``+``, ``-``, ``|``, spaces, ``S`` and ``G``, the first a row of
    corners and walls (``+--+--+``)."""
    rows = [row.rstrip() for row in text.strip("\n").splitlines()]
    if len(rows) < 2 or not rows[0].lstrip().startswith("+-"):
        return False
    return all(set(row) <= _GRID_MAP_CHARACTERS for row in rows)


def _cells_along(position: float, count: int) -> list[int]:
    """The cells (0 to ``count - 1``) whose span [k, k + 1] holds ``position`` (in cells): one
    inside a cell, two on the line between cells (within a billionth of a cell), none outside."""
    nearest = round(position)
    if abs(position - nearest) <= 1e-9:
        return [k for k in (nearest - 1, nearest) if 0 <= k < count]
    inside = math.floor(position)
    return [inside] if 0 <= inside < count else []


def world_hash(world: World) -> str:
    """The sha256 of the world's description (:meth:`mazesim.World.to_toml`), in hex."""
    return hashlib.sha256(world.to_toml().encode("utf-8")).hexdigest()


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
                f"expected a world with a [grid] cell maze, found none in {_shown(world.name)} "
                "(its "
                "walls are boxes, as every imported Webots world's are): draw the maze as a [grid] "
                "map of +--+ and | in a .toml world file (docs/world-format.md), or generate one "
                "with mazesim.generate_maze"
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
        self.goal_cell = None if goal is None else (int(goal[0]), int(goal[1]))
        #: The cell of the map's S, or None when the map has none.
        self.marked_start = None if start is None else (int(start[0]), int(start[1]))
        #: The start cell: the cell holding the robot's start pose (the S's centre, or the
        #: [start] pose, which wins), or the S's cell for a pose on its edge; None for a pose
        #: outside the maze or on the line between two cells without an S.
        holding = self.cells_touching(float(world.start[0]), float(world.start[1]))
        self.start_cell = holding[0] if len(holding) == 1 else None
        if len(holding) > 1 and self.marked_start in holding:
            self.start_cell = self.marked_start

    def cells_touching(self, x: float, y: float) -> list[tuple[int, int]]:
        """The cells whose square holds the point (x, y), edges included: one for a point inside
        a cell, two or four for a point on the line between cells, none outside the maze."""
        column = (x - self.origin[0]) / self.cell_size
        row_from_south = (y - self.origin[1]) / self.cell_size
        columns = _cells_along(column, self.cols)
        rows = [self.rows - 1 - each for each in _cells_along(row_from_south, self.rows)]
        return [(c, r) for r in rows for c in columns]

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

    def open_sides(self) -> npt.NDArray[np.bool_]:
        """(rows, cols, 4): whether each side of each cell is open, sides in direction order
        (:meth:`is_open` of every cell at once)."""
        sides = np.empty((self.rows, self.cols, 4), dtype=bool)
        sides[..., EAST] = ~self.vertical[:, 1:]
        sides[..., NORTH] = ~self.horizontal[:-1]
        sides[..., WEST] = ~self.vertical[:, :-1]
        sides[..., SOUTH] = ~self.horizontal[1:]
        return sides

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
        """Breadth-first cell distances from ``cell``, shape (rows, cols); -1 where unreachable
        (:func:`breadth_first_distances` of this one maze)."""
        return breadth_first_distances(self.open_sides()[None], np.array([cell]))[0]

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

    def heading_of(self, direction: int) -> float:
        """The heading in radians of a direction number."""
        return direction * math.pi / 2.0


def breadth_first_distances(
    open_sides: npt.NDArray[np.bool_], sources: npt.NDArray[np.int64]
) -> npt.NDArray[np.int64]:
    """Breadth-first cell distances in K mazes of one shape, each from its own source cell.

    Args:
        open_sides: (K, rows, cols, 4) whether each side of each cell is open, sides in direction
            order (:meth:`CellMaze.open_sides`); the sides on the grid's edge count as walls.
        sources: (K, 2) the (column, row) cell each search starts from.

    Returns:
        (K, rows, cols) steps from the source cell along open sides; -1 where unreachable.
    """
    count, rows, cols, _ = open_sides.shape
    cells = rows * cols
    opened = (open_sides & _inside(rows, cols)).reshape(count, cells, _SIDES).tolist()
    offsets = list(enumerate(_STEP[d][0] + _STEP[d][1] * cols for d in range(_SIDES)))
    sources = np.asarray(sources).reshape(count, 2)
    sources = np.stack(
        [
            index_array(sources[:, 0], "source columns", cols),
            index_array(sources[:, 1], "source rows", rows),
        ],
        axis=1,
    )
    distances = np.empty((count, cells), dtype=np.int64)
    for maze, (column, row) in enumerate(sources.tolist()):
        sides = opened[maze]
        distance = [-1] * cells
        source = row * cols + column
        distance[source] = 0
        queue = [source]
        for here in queue:  # the queue grows while it is read: breadth first
            step = distance[here] + 1
            for side, offset in offsets:
                there = here + offset
                if sides[here][side] and distance[there] < 0:
                    distance[there] = step
                    queue.append(there)
        distances[maze] = distance
    return distances.reshape(count, rows, cols)


def _inside(rows: int, cols: int) -> npt.NDArray[np.bool_]:
    """(rows, cols, 4): False on the sides that lie on the grid's edge."""
    inside = np.ones((rows, cols, _SIDES), dtype=bool)
    inside[:, -1, EAST] = inside[0, :, NORTH] = inside[:, 0, WEST] = inside[-1, :, SOUTH] = False
    return inside


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
        targets: (rows * cols, 5) values of the east, north, west and south sides and of the goal
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
    def of_world(
        cls, world: World, goal: tuple[float, float, float] | None = None
    ) -> PathDistanceTable:
        """Builds the table of a world: a breadth-first search over its cell maze, if it has one.

        Args:
            world: The world.
            goal: The goal disc (x, y, radius) instead of the world's (an environment's own goal,
                ``BatchSimulator.set_goals_at``); its cell is the goal cell.
        """
        own = goal is not None
        goal = goal if goal is not None else world.goal
        if goal is None:
            return cls("none", 1, 1, 1.0, (0.0, 0.0), (0.0, 0.0, -1.0), np.full((1, _TARGETS), 0.0))
        maze = world.cell_maze()
        if maze is None:
            targets = np.full((1, _TARGETS), np.nan)
            return cls("straight", 1, 1, 1.0, (0.0, 0.0), goal, targets)
        cells = CellMaze(world)
        if own or cells.goal_cell is None:
            columns, rows = cells.cell_at(goal[0], goal[1])
            goal_cell = (int(columns), int(rows))
        else:
            goal_cell = cells.goal_cell
        # The interpolation targets of every cell, computed in the core (a new random maze
        # every episode makes a table every reset).
        targets = world.distance_targets(goal_cell[1] * cells.cols + goal_cell[0])
        return cls("maze", cells.rows, cells.cols, cells.cell_size, cells.origin, goal, targets)


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

    def evaluate_one(self, x: float, y: float) -> tuple[float, bool]:
        """:meth:`evaluate` of environment 0 at (x, y), the float32 pose as Python floats."""
        poses = np.zeros((self.num_envs, 3), dtype=np.float32)
        poses[0, :2] = x, y
        distances, reached = self.evaluate(poses)
        return float(distances[0]), bool(reached[0])

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
        gaps = np.stack((half - u, half - v, half + u, half + v, to_goal), axis=1)
        weights = targets[:, _TARGETS:] / np.maximum(gaps, _NEAREST)
        terms = weights * targets[:, :_TARGETS]
        # Summed north, east, south, west, goal: the order the environments' rewards were
        # pinned with (floating-point sums depend on their order).
        n, e, s, w = NORTH, EAST, SOUTH, WEST
        weighted = terms[:, n] + terms[:, e] + terms[:, s] + terms[:, w] + terms[:, _SIDES]
        total = weights[:, n] + weights[:, e] + weights[:, s] + weights[:, w] + weights[:, _SIDES]
        along = weighted / total
        if modes == {"maze"}:
            return along, reached
        maze = np.array([mode == "maze" for mode in self._modes])
        return np.where(maze, along, np.where(self._has_goal, to_goal, 0.0)), reached
