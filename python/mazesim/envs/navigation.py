"""Goal-conditioned tasks: random start and goal cells, and the observations that make a maze
learnable by a memoryless policy.

Start and goal
    With ``start_goal="random"`` every episode moves the start and the goal of its cell maze to two
    distinct cells drawn from the env's RNG (the start at the centre of its cell, facing a uniformly
    random direction). The world itself is rewritten (:func:`with_start_and_goal`), so the reward,
    the termination, the pictures and the barcodes all follow.

Observations (``observation=``)
    ``"sensors"``: the raw readings (``mazesim/EPuckMaze-v0``, see :mod:`mazesim.envs.spaces`).
    ``"goal"``: float32 values of order 1, in this order:

    - every sensor reading divided by its table's largest value (e-puck ps0-ps7: raw / 4095, about
      0.016 with nothing in range, 1 at contact; gs0-gs2: raw / 1000);
    - the goal's position in the robot's frame (forward, left), in units of the maze's larger side;
    - the previous action as wheel speed fractions (0, 0 after a reset).

    ``"guided"``: ``"goal"`` plus, before the previous action, the next waypoint of the shortest
    path in the robot's frame (forward, left) in cells: the centre of the neighbouring cell on the
    way to the goal, or the goal itself in the goal cell.

    What a real e-puck could have: its readings and its previous action, yes; the goal's relative
    position, from wheel odometry and a known goal (it drifts, the simulator's does not); the
    waypoint needs a map and a position in it, as a robot that reads the floor barcodes at the
    junctions of a known maze has (the report's checkpoints), so it is a privileged observation.
"""

from __future__ import annotations

import math
import re
from typing import Any, cast

import numpy as np
import numpy.typing as npt
from gymnasium import spaces

from mazesim._core import RobotProfile, World
from mazesim.envs.spaces import NOISE_MARGIN, sensor_ranges
from mazesim.errors import InvalidArgumentError
from mazesim.maze import EAST, NORTH, SOUTH, WEST, CellMaze, PathDistanceTable

__all__ = [
    "OBSERVATIONS",
    "START_GOALS",
    "NavigationFeatures",
    "draw_start_and_goal",
    "navigation_features",
    "with_start_and_goal",
]

#: The accepted values of ``observation``.
OBSERVATIONS = ("sensors", "goal", "guided")
#: The accepted values of ``start_goal``.
START_GOALS = ("world", "random")
#: Bound of the waypoint's coordinates in cells (a neighbour's centre is at most 1.5 cells off).
_WAYPOINT_BOUND = 2.0
#: The (column, row-up) step across each side of a cell, by maze's direction codes (the side
#: order of the distance table).
_SIDE_STEPS = {EAST: (1.0, 0.0), NORTH: (0.0, 1.0), WEST: (-1.0, 0.0), SOUTH: (0.0, -1.0)}


def navigation_features(
    observation: str,
    num_envs: int,
    robot: RobotProfile,
    world: World,
    table: PathDistanceTable,
    pose: bool = False,
) -> NavigationFeatures | None:
    """The features of an ``observation`` kind for N environments all in ``world`` at first
    (with the robot's pose if ``pose``); None for ``"sensors"``."""
    if observation == "sensors":
        return None
    features = NavigationFeatures(num_envs, robot, observation == "guided", pose)
    features.set(np.arange(num_envs), world, table)
    return features


def draw_start_and_goal(world: World, rng: np.random.Generator) -> World:
    """``world`` with its start and goal in two distinct random cells of its maze that join each
    other, the start facing a random direction; draws three numbers from ``rng``.

    The start is drawn among the cells of the largest connected set of cells (every cell in a
    generated maze; seed-maze has four walled-in cells), the goal among the others of that set.

    Raises:
        InvalidArgumentError: The world has no cell maze, or no two cells join.
    """
    if world.cell_maze() is None:
        raise InvalidArgumentError(
            f'expected a world with a cell maze for start_goal="random", found {world.name!r}'
        )
    cells = _largest_connected_cells(CellMaze(world))
    if len(cells) < 2:
        raise InvalidArgumentError(
            f'expected two cells that join each other for start_goal="random", found none in '
            f"{world.name!r}"
        )
    start = int(rng.integers(len(cells)))
    goal = int(rng.integers(len(cells) - 1))
    goal += goal >= start
    yaw = float(rng.uniform(-math.pi, math.pi))
    return with_start_and_goal(world, cells[start], cells[goal], yaw)


def _largest_connected_cells(maze: CellMaze) -> list[tuple[int, int]]:
    """The (row, column) cells of the largest set of cells joined by open sides, row-major from
    the north-west (the first such set if two are as large)."""
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


def with_start_and_goal(
    world: World, start: tuple[int, int], goal: tuple[int, int], yaw: float
) -> World:
    """A copy of a cell-maze world with the start at the centre of cell ``start`` facing ``yaw``
    and the goal in cell ``goal`` (cells as (row from the north, column))."""
    maze = world.cell_maze()
    assert maze is not None
    size = float(maze["cell_size"])  # type: ignore[arg-type]
    origin_x, origin_y = (float(v) for v in maze["origin"])  # type: ignore[attr-defined]
    rows = int(maze["rows"])  # type: ignore[call-overload]
    text = re.sub(r"\n\[start\]\n(?:[a-z]+ = [^\n]*\n)*", "\n", world.to_toml())
    head, found, rest = text.partition('map = """\n')
    grid, _, tail = rest.partition('"""')
    lines = [list(line.replace("S", " ").replace("G", " ")) for line in grid.split("\n")]
    for mark, (row, col) in (("S", start), ("G", goal)):
        lines[2 * row + 1][3 * col + 1] = mark
    x = origin_x + (start[1] + 0.5) * size
    y = origin_y + (rows - 1 - start[0] + 0.5) * size
    first_table = head.index("\n[") + 1  # the start table goes before the first table
    head = (
        f"{head[:first_table]}[start]\nx = {x!r}\ny = {y!r}\nyaw = {yaw!r}\n\n{head[first_table:]}"
    )
    grid = "\n".join("".join(line) for line in lines)
    return World.from_toml(head + found + grid + '"""' + tail, source=f"<{world.name}>")


class NavigationFeatures:
    """The ``"goal"`` and ``"guided"`` observations of N environments (see the module).

    The single env runs it with N = 1, so single and vector envs agree bit for bit.

    Args:
        num_envs: Number of environments.
        robot: The robot profile.
        guided: Whether the observation holds the waypoint.
        pose: Whether the observation holds the robot's pose in the maze.
    """

    def __init__(
        self, num_envs: int, robot: RobotProfile, guided: bool, pose: bool = False
    ) -> None:
        ranges = sensor_ranges(robot)
        distance, ground = robot.distance_sensor_names, robot.ground_sensor_names
        scale = [ranges.distance_max] * len(distance) + [ranges.ground_max] * len(ground)
        self.sensor_width = len(scale)
        self._scale = np.array(scale, dtype=np.float64)
        self.guided = guided
        self.pose = pose
        extra = ["goal_forward", "goal_left"]
        low, high = [-1.5, -1.5], [1.5, 1.5]
        if guided:
            extra += ["waypoint_forward", "waypoint_left"]
            low += [-_WAYPOINT_BOUND, -_WAYPOINT_BOUND]
            high += [_WAYPOINT_BOUND, _WAYPOINT_BOUND]
        if pose:
            extra += ["x", "y", "heading_cos", "heading_sin"]
            low += [0.0, 0.0, -1.0, -1.0]
            high += [1.0, 1.0, 1.0, 1.0]
        extra += ["previous_left", "previous_right"]
        low += [-1.0, -1.0]
        high += [1.0, 1.0]
        self.names = [*distance, *ground, *extra]
        self.low = np.array([0.0] * self.sensor_width + low, dtype=np.float32)
        self.high = np.array([NOISE_MARGIN] * self.sensor_width + high, dtype=np.float32)
        self._goal = np.zeros((num_envs, 2))
        self._extent = np.ones(num_envs)
        self._corner = np.zeros((num_envs, 2))
        self._size = np.ones(num_envs)
        self._origin = np.zeros((num_envs, 2))
        self._shape = np.ones((num_envs, 2), dtype=np.intp)  # rows, cols
        self._cells = 1
        self._waypoints = np.zeros((num_envs, 1, 2))

    @property
    def space(self) -> spaces.Space[npt.NDArray[np.float32]]:
        """The observation space of one environment."""
        box = spaces.Box(self.low, self.high, dtype=np.float32)
        return cast("spaces.Space[npt.NDArray[np.float32]]", box)

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
        if len(waypoints) > self._cells:
            grown = np.zeros((len(self._goal), len(waypoints), 2))
            grown[:, : self._cells] = self._waypoints
            self._waypoints, self._cells = grown, len(waypoints)
        self._waypoints[env, : len(waypoints)] = waypoints

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
        parts: list[npt.NDArray[Any]] = [readings / self._scale]
        for target, unit in self._targets(x, y):
            dx, dy = target[:, 0] - x, target[:, 1] - y
            parts += [
                ((cos * dx + sin * dy) / unit)[:, None],
                ((cos * dy - sin * dx) / unit)[:, None],
            ]
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

    def _targets(
        self, x: npt.NDArray[np.float64], y: npt.NDArray[np.float64]
    ) -> list[tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]]:
        targets = [(self._goal, self._extent)]
        if self.guided:
            rows, cols = self._shape[:, 0], self._shape[:, 1]
            col = np.clip(np.floor((x - self._origin[:, 0]) / self._size), 0, cols - 1)
            up = np.clip(np.floor((y - self._origin[:, 1]) / self._size), 0, rows - 1)
            cell = (rows - 1 - up.astype(np.intp)) * cols + col.astype(np.intp)
            waypoint = self._waypoints[np.arange(len(x)), cell]
            targets.append((waypoint, self._size))
        return targets


def _waypoints(table: PathDistanceTable) -> npt.NDArray[np.float64]:
    """The next waypoint (x, y) of each cell of a distance table (row-major from the north-west):
    the centre of the open neighbour across the side of least distance, the goal in the goal cell
    (and everywhere without a maze)."""
    goal = np.array(table.goal[:2], dtype=np.float64)
    if table.mode != "maze":
        return goal[None, :].copy()
    size = table.cell_size
    points = np.zeros((table.rows * table.cols, 2))
    for cell, values in enumerate(table.targets):
        row, col = divmod(cell, table.cols)
        if not math.isnan(values[4]):
            points[cell] = goal
            continue
        sides = np.where(np.isnan(values[:4]), np.inf, values[:4])
        step_x, step_up = _SIDE_STEPS[int(np.argmin(sides))]
        points[cell] = (
            table.origin[0] + (col + 0.5 + step_x) * size,
            table.origin[1] + (table.rows - 1 - row + 0.5 + step_up) * size,
        )
    return points
