"""Goal-conditioned tasks: random start and goal cells, and the observations that make a maze
learnable by a memoryless policy.

Start and goal
    With ``start_goal="random"`` every episode moves the start and the goal of its cell maze to two
    distinct cells that join, drawn from the env's RNG (the start at the centre of its cell, facing
    a uniformly random direction; :func:`draw_start_and_goal`). The simulator gets them as its
    own start and goal (``set_starts_at`` and ``set_goals_at`` of the batch engine), the world
    is not changed; the reward, the termination and the pictures follow.

Observations (``observation=``)
    ``"sensors"``: the raw readings (``mazesim/EPuckMaze-v0``, see :mod:`mazesim.envs.spaces`).
    ``"goal"``: float32 values of order 1, in this order:

    - every sensor reading divided by its table's largest value (e-puck ps0-ps7: raw / 4095, about
      0.016 with nothing in range, 1 at contact; gs0-gs2: raw / 1000);
    - the goal's position in the robot's frame (forward, left), in units of the maze's larger side;
    - the previous action as wheel speed fractions (0, 0 after a reset).

    ``"explore"``: ``"goal"`` plus, before the previous action, the map explored in this episode
    round the robot: whether the sides of its cell ahead, left, behind and right of it are open,
    the visits of the cells across them (0 across a wall) and of its own cell, up to 3, scaled
    to 1.

    ``"guided"``: ``"goal"`` plus, before the previous action, the next waypoint of the shortest
    path in the robot's frame (forward, left) in cells: the centre of the neighbouring cell on the
    way to the goal, or the goal itself in the goal cell.

    ``"plan"``: ``"explore"`` plus, after the goal, the next waypoint (forward, left, in cells) of
    the shortest path to the goal through the maze **as the robot knows it in this episode**:
    the sides of the cells it has visited are as they are, every side it has not seen is assumed
    open (the free-space assumption of a mapping robot, as in D* Lite), the outer wall is known.
    The path is planned again whenever the robot enters a cell for the first time (the only
    moment its map changes), by a breadth-first search in the core (per environment and step as
    every feature here: :class:`mazesim._core.TaskFeatures`); the waypoint is the
    centre of the neighbouring cell on that path, or the goal in the goal cell. Following it the
    robot reaches the goal of any maze whose goal can be reached: each plan either gets there or
    leads into a cell not visited yet.

    The ``"plan"`` observation of the e-puck (``mazesim/UnseenMaze-v2``), 26 values:

    =====  ==========================  ==================================================
    index  name                        value
    =====  ==========================  ==================================================
    0-7    ps0-ps7                     proximity readings / 4095 (0 to 1.25)
    8-10   gs0-gs2                     ground readings / 1000 (0 to 1.25)
    11-12  goal_forward, goal_left     the goal in the robot's frame, in units of the
                                       maze's larger side (-1.5 to 1.5)
    13-14  waypoint_forward,           the planned waypoint in the robot's frame, in
           waypoint_left               cells (-2 to 2)
    15-18  open_ahead ... open_right   1 where that side of the robot's cell is open
                                       (ahead, left, behind, right), else 0
    19-22  visits_ahead ...            visits of the cell across that side this
           visits_right                episode, up to 3, / 3 (0 across a wall)
    23     visits_here                 visits of the robot's own cell, up to 3, / 3
    24-25  previous_left,              the previous action (wheel speed fractions)
           previous_right
    =====  ==========================  ==================================================

    ``"guided"`` has indices 0 to 14 and the previous action at 15-16; ``"explore"`` has 0 to
    12, then the map (as 15 to 23 here) and the previous action; ``env.observation_names`` lists
    them for any robot.

    What a real e-puck could have: its readings and its previous action, yes; the goal's relative
    position, from wheel odometry and a known goal (it drifts, the simulator's does not). The
    explored map and the plan need what a mapping robot builds itself: odometry to tell which cell
    it is in, its IR sensors for the walls of that cell (they see a wall a few centimetres away;
    the e-puck2's time-of-flight sensor ahead up to 2 m), the maze's size and cell size, and a
    breadth-first search over at most 25 cells on entering a new one. The ``"guided"`` waypoint
    needs the true map and a position in it, as a robot that reads the floor barcodes at the
    junctions of a known maze has (the report's checkpoints), so it is a privileged observation.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any, cast

import numpy as np
import numpy.typing as npt
from gymnasium import spaces

from mazesim._core import RobotProfile, TaskFeatures, World
from mazesim.envs.spaces import NOISE_MARGIN, sensor_ranges
from mazesim.errors import InvalidArgumentError, _shown
from mazesim.maze import (
    EAST,
    NORTH,
    SOUTH,
    WEST,
    CellMaze,
    PathDistanceTable,
)

__all__ = [
    "OBSERVATIONS",
    "START_GOALS",
    "NavigationFeatures",
    "StartAndGoal",
    "distance_table",
    "draw_start_and_goal",
    "navigation_features",
    "start_and_goal_cells",
]

#: The accepted values of ``observation``.
OBSERVATIONS = ("sensors", "goal", "explore", "guided", "plan")
#: The accepted values of ``start_goal``.
START_GOALS = ("world", "random")
#: Bound of the waypoint's coordinates in cells (a neighbour's centre is at most 1.5 cells off).
_WAYPOINT_BOUND = 2.0
#: The sides of the explored map's observation, relative to the robot's heading.
_RELATIVE_SIDES = ("ahead", "left", "behind", "right")
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
    features = NavigationFeatures(
        num_envs,
        robot,
        observation == "guided",
        pose,
        explore=observation in ("explore", "plan"),
        plan=observation == "plan",
    )
    features.set(np.arange(num_envs), world, table)
    return features


@dataclass(frozen=True)
class StartAndGoal:
    """An episode's start pose and goal disc, given to the simulator (``set_start`` /
    ``set_goal``, ``set_starts_at`` / ``set_goals_at``); the world itself is not changed.

    Attributes:
        start: x, y (metres) and yaw (radians) of the start pose.
        goal: x, y and radius (metres) of the goal disc.
    """

    start: tuple[float, float, float]
    goal: tuple[float, float, float]


def draw_start_and_goal(world: World, rng: np.random.Generator) -> StartAndGoal:
    """A start and a goal in two distinct random cells of ``world``'s maze that join each other,
    the start at its cell's centre facing a random direction, the goal a disc of a third of a cell
    round its cell's centre (as a ``G`` of a world's map); draws three numbers from ``rng``.

    The start is drawn among the cells of the largest connected set of cells (every cell in a
    generated maze; seed-maze has four walled-in cells), the goal among the others of that set.

    Raises:
        InvalidArgumentError: The world has no cell maze, or no two cells join.
    """
    maze, cells = _cells_of(_Same(world))
    start = int(rng.integers(len(cells)))
    goal = int(rng.integers(len(cells) - 1))
    goal += goal >= start
    yaw = float(rng.uniform(-math.pi, math.pi))
    (start_row, start_col), (goal_row, goal_col) = cells[start], cells[goal]
    start_x, start_y = maze.center((start_col, start_row))
    goal_x, goal_y = maze.center((goal_col, goal_row))
    return StartAndGoal((start_x, start_y, yaw), (goal_x, goal_y, maze.cell_size / 3.0))


class _Same:
    """A world as a cache key: equal only to itself (worlds are immutable and not hashable); the
    key holds the world, so its id is not reused while it is cached."""

    __slots__ = ("world",)

    def __init__(self, world: World) -> None:
        self.world = world

    def __hash__(self) -> int:
        return id(self.world)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, _Same) and other.world is self.world


#: Worlds whose start and goal cells and distance tables are kept (a fixed world's are drawn
#: again every episode; a random maze's episode is long beside the cost of making them).
_CACHED_WORLDS = 32


@functools.lru_cache(maxsize=_CACHED_WORLDS)
def _cells_of(world: _Same) -> tuple[CellMaze, list[tuple[int, int]]]:
    return start_and_goal_cells(world.world)


@functools.lru_cache(maxsize=4 * _CACHED_WORLDS)
def _table_of(world: _Same, goal: tuple[float, float, float] | None) -> PathDistanceTable:
    return PathDistanceTable.of_world(world.world, goal)


def distance_table(world: World, goal: tuple[float, float, float] | None) -> PathDistanceTable:
    """:meth:`PathDistanceTable.of_world` of ``world`` and ``goal`` (None: the world's own),
    kept for the worlds used lately: every episode of a fixed world with random goals asks for
    one of a few tables again. The table is shared: read it, do not change it."""
    return _table_of(_Same(world), goal)


def start_and_goal_cells(world: World) -> tuple[CellMaze, list[tuple[int, int]]]:
    """The cell maze of ``world`` and the (row, column) cells :func:`draw_start_and_goal` draws
    from: those of its largest set of cells joined by open sides.

    Raises:
        InvalidArgumentError: The world has no cell maze, or no two cells join.
    """
    if world.cell_maze() is None:
        raise InvalidArgumentError(
            f'expected a world with a cell maze for start_goal="random", found {_shown(world.name)}'
        )
    maze = CellMaze(world)
    # The largest set of cells joined by open sides, row-major from the north-west (the first
    # such set if two are as large), found in the core.
    cells = [(row, column) for row, column in world.connected_cells().tolist()]
    if len(cells) < 2:
        raise InvalidArgumentError(
            f'expected two cells that join each other for start_goal="random", found none in '
            f"{_shown(world.name)}"
        )
    return maze, cells


class NavigationFeatures:
    """The ``"goal"``, ``"explore"``, ``"guided"`` and ``"plan"`` observations of N environments
    (see the module), computed per step in the core (:class:`mazesim._core.TaskFeatures`).

    The single env runs it with N = 1 (``observe_one``), so single and vector envs agree bit
    for bit; each environment's values depend on its own state alone.

    Args:
        num_envs: Number of environments.
        robot: The robot profile.
        guided: Whether the observation holds the waypoint.
        pose: Whether the observation holds the robot's pose in the maze.
        explore: Whether the observation holds the explored map round the robot's cell.
        plan: Whether the observation holds the waypoint planned through the maze as the robot
            knows it (instead of ``guided``'s through the true maze).
    """

    def __init__(
        self,
        num_envs: int,
        robot: RobotProfile,
        guided: bool,
        pose: bool = False,
        explore: bool = False,
        plan: bool = False,
    ) -> None:
        ranges = sensor_ranges(robot)
        distance, ground = robot.distance_sensor_names, robot.ground_sensor_names
        scale = [ranges.distance_max] * len(distance) + [ranges.ground_max] * len(ground)
        self.sensor_width = len(scale)
        self.guided = guided
        self.plan = plan
        self.pose = pose
        self.explore = explore
        extra = ["goal_forward", "goal_left"]
        low, high = [-1.5, -1.5], [1.5, 1.5]
        if guided or plan:
            extra += ["waypoint_forward", "waypoint_left"]
            low += [-_WAYPOINT_BOUND, -_WAYPOINT_BOUND]
            high += [_WAYPOINT_BOUND, _WAYPOINT_BOUND]
        if explore:
            extra += [f"open_{side}" for side in _RELATIVE_SIDES]
            extra += [f"visits_{side}" for side in _RELATIVE_SIDES] + ["visits_here"]
            low += [0.0] * 9
            high += [1.0] * 9
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
        kind = "plan" if plan else "explore" if explore else "guided" if guided else "goal"
        self._arguments = (num_envs, kind, pose, np.array(scale, dtype=np.float64))
        self._core = TaskFeatures(*self._arguments, self.low, self.high)
        self._tables: list[PathDistanceTable | None] = [None] * num_envs
        self._bind()

    @property
    def core(self) -> TaskFeatures:
        """The core's features, for :meth:`mazesim._core.Simulator.step_task`: a single env's
        step and its observation in one call."""
        return self._core

    def _bind(self) -> None:
        """Binds ``observe_one(readings, pose, left, right, max_speed)``: the observation of
        environment 0 from its float32 readings and pose, the previous action being the wheel
        speeds ``left`` and ``right`` over ``max_speed`` in float32 (as the vector env's
        ``speeds / max_speed``); then the shortest-path distance in metres from the pose to the
        goal and whether the pose is in the goal disc, as
        :meth:`mazesim.maze.GoalDistance.evaluate_one` gives them. The core's method itself, with
        no Python call between (a single env calls it every step)."""
        self.observe_one = functools.partial(self._core.observe_env, 0)

    def __getstate__(self) -> dict[str, Any]:
        """What pickling and copying keep: everything, the core's features as their state."""
        state = self.__dict__.copy()
        state["_core"] = self._core.state()
        state.pop("observe_one", None)
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        core_state = state.pop("_core")
        self.__dict__.update(state)
        self._core = TaskFeatures(*self._arguments, self.low, self.high)
        self._core.restore(core_state)
        self._bind()
        for env, table in enumerate(self._tables):
            if table is not None:
                self._set_goal(env, table)

    def _set_goal(self, env: int, table: PathDistanceTable) -> None:
        self._tables[env] = table
        self._core.set_goal(
            env,
            table.mode,
            np.array(table.goal, dtype=np.float64),
            table.cell_size,
            np.array(table.origin, dtype=np.float64),
            (table.rows, table.cols),
            np.ascontiguousarray(table.targets, dtype=np.float64),
        )

    @property
    def space(self) -> spaces.Space[npt.NDArray[np.float32]]:
        """The observation space of one environment."""
        box = spaces.Box(self.low, self.high, dtype=np.float32)
        return cast("spaces.Space[npt.NDArray[np.float32]]", box)

    def set(self, env: int | npt.NDArray[np.intp], world: World, table: PathDistanceTable) -> None:
        """Puts environment(s) ``env`` into ``world`` (whose distance table is ``table``)."""
        xmin, ymin, xmax, ymax = world.bounds
        extent = max(xmax - xmin, ymax - ymin, 1e-6)
        place = np.array(
            [*table.goal[:2], extent, xmin, ymin, table.cell_size, *table.origin], dtype=np.float64
        )
        # The true shortest path's waypoints ("guided"; the plan makes its own before it is
        # first read, and the other kinds observe none).
        goal = np.array([table.goal[:2]], dtype=np.float64)
        waypoints = _waypoints(table) if self.guided else goal
        # The true open sides of the cells (all closed without a cell maze), and the goal cell
        # the plan heads for.
        maze = CellMaze(world) if self.explore and table.mode == "maze" else None
        sides: npt.NDArray[np.float64] | None = None
        if self.explore:
            cells = table.rows * table.cols
            known = np.zeros((cells, 4)) if maze is None else maze.open_sides().reshape(-1, 4)
            sides = np.ascontiguousarray(known, dtype=np.float64)
        goal_cell = None
        if self.plan and maze is not None:
            column, row = maze.cell_at(table.goal[0], table.goal[1])
            goal_cell = int(row) * table.cols + int(column)
        for one in np.atleast_1d(env).tolist():
            self._core.set_env(one, place, table.rows, table.cols, waypoints, sides, goal_cell)
            self._set_goal(one, table)

    def restart(self, env: int | npt.NDArray[np.intp]) -> None:
        """Forgets the explored map's visits of environment(s) ``env`` (a new episode); the plan
        is made again at the next observation, from the robot's first cell."""
        for one in np.atleast_1d(env).tolist():
            self._core.restart(one)

    def observe(
        self,
        readings: npt.NDArray[np.float32],
        poses: npt.NDArray[np.float32],
        previous: npt.NDArray[np.float32],
    ) -> npt.NDArray[np.float32]:
        """(N, width) observations from (N, sensor_width) raw readings, (N, 3) poses and the
        (N, 2) previous actions as wheel speed fractions (float32 arrays)."""
        return self._core.observe(readings, poses, previous)


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
