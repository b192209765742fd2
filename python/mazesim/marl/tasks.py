"""The multi-robot tasks: how an episode's world is drawn, what each robot observes, its reward and
when it is done. Every rule works on arrays of N environments x R robots at once, so the native
batch (:class:`mazesim.marl.batch.MultiRobotBatch`) and a PettingZoo env (a batch of one) share
it.

``maze_goals``
    Every robot to its own goal in a maze it has never seen, without touching the walls or each
    other: the task of JaxNav (JaxMARL's navigation environment: differential-drive robots with
    range sensors in grid maps; Rutherford et al., "JaxMARL: Multi-Agent RL Environments and
    Algorithms in JAX", NeurIPS 2024 Datasets and Benchmarks), on e-pucks. Each episode draws a
    new cell maze (:func:`mazesim.generate_maze`, with loops), a start cell and a goal cell per
    robot (the starts distinct, the goals distinct, no robot's goal its own start), each start at
    its cell's centre facing a random direction; a goal is a disc of a third of a cell round its
    cell's centre, as in the single-robot tasks.

``aggregation``
    The swarm gathers into one cluster: the aggregation task of Gauci, Chen, Li, Dodd and Groß,
    "Self-organized aggregation without computation", The International Journal of Robotics
    Research 33(8), 2014, whose controllers ran on e-pucks. The robots start at random,
    non-overlapping poses in a square arena; the measure of the cluster is that paper's
    dispersion ``u = sum_i |p_i - centroid|^2 / (4 r^2)`` (r the body radius), reported in the
    infos and smallest for a tight cluster.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._core import MazeLayout, World, generate_maze
from mazesim._toml import dump_toml, load_toml
from mazesim.envs.navigation import start_and_goal_cells
from mazesim.errors import InvalidArgumentError, _bounded_number
from mazesim.maze import GoalDistance, PathDistanceTable

#: The layout of the tasks' mazes: the default one, without barcode checkpoints.
_WITHOUT_CHECKPOINTS = MazeLayout(checkpoints=False)

__all__ = [
    "AggregationTask",
    "finite_number",
    "EpisodeDraw",
    "MazeGoalsTask",
    "MultiRobotTask",
    "RobotStates",
    "agent_names",
    "dispersion",
    "robots_world",
]

#: The e-puck's largest raw proximity reading: observations divide ps0-ps7 by it.
PROXIMITY_MAX = 4095.0
#: Contact between two robots: centres at most this much farther apart than two body radii.
TOUCH_SLACK = 0.001


def agent_names(num_robots: int) -> list[str]:
    """The agents' names (and their robots' names in the world): ``epuck_0``, ``epuck_1``, ..."""
    return [f"epuck_{i}" for i in range(num_robots)]


def finite_number(name: str, value: Any, positive: bool = False) -> float:
    """A task parameter that is a number: finite (and above 0 with ``positive``), as a float
    (:func:`mazesim.errors._bounded_number`, the one check of such numbers).

    Raises:
        InvalidArgumentError: Another value (a ``WrongTypeError`` for no number at all).
    """
    return _bounded_number(name, value, above=0.0 if positive else None)


@dataclass(frozen=True)
class EpisodeDraw:
    """One environment's episode as drawn from its random stream.

    Attributes:
        world: The world, placing every robot at its start.
        seed: The simulator's seed for the episode (noise streams).
        goals: (R, 3) x, y, radius of each robot's goal disc (NaN rows for none).
    """

    world: World
    seed: int
    goals: npt.NDArray[np.float64]


@dataclass
class RobotStates:
    """What the simulator returned after a step, for N environments x R robots.

    Attributes:
        readings: (N, R, width) float32 raw sensor readings (distance sensors first).
        poses: (N, R, 3) float32 x, y, yaw.
        colliding: (N, R) bool, touching a wall or another robot in the step.
        actions: (N, R, 2) float32 the wheel speed fractions applied (0 after a reset).
    """

    readings: npt.NDArray[np.float32]
    poses: npt.NDArray[np.float32]
    colliding: npt.NDArray[np.bool_]
    actions: npt.NDArray[np.float32]


def robots_world(world_toml: str, starts: npt.NDArray[np.float64], name: str) -> World:
    """``world_toml`` with the robots ``epuck_0``... at ``starts`` ((R, 3) x, y, yaw) instead of
    its ``[start]`` and without its ``[goal]`` (each robot has its own), named ``name``."""
    layout = load_toml(world_toml, name)
    layout.pop("start", None)
    layout.pop("goal", None)
    if "name" in layout:
        layout["name"] = name
    grid = layout.get("grid", {})
    if "map" in grid:
        # The grid's own start and goal marks give way to the robots' starts and goals.
        grid["map"] = grid["map"].replace("S", " ").replace("G", " ")
    layout["robots"] = [
        *layout.get("robots", []),
        *(
            {"name": robot, "x": float(x), "y": float(y), "yaw": float(yaw)}
            for robot, (x, y, yaw) in zip(agent_names(len(starts)), starts)
        ),
    ]
    return World.from_toml(dump_toml(layout), source=name)


def dispersion(poses: npt.NDArray[np.float32], body_radius: float) -> npt.NDArray[np.float64]:
    """Gauci et al.'s dispersion of each environment's robots, ``sum_i |p_i - centroid|^2 /
    (4 r^2)``, from (N, R, 3) poses: (N,) float64."""
    xy = poses[..., :2].astype(np.float64)
    centred = xy - xy.mean(axis=1, keepdims=True)
    squared: npt.NDArray[np.float64] = (centred * centred).sum(axis=(1, 2))
    return squared / (4.0 * body_radius * body_radius)


def _in_robot_frame(
    poses: npt.NDArray[np.float32], targets: npt.NDArray[np.float64]
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """(forward, left) of ``targets`` (N, R, 2) in each robot's frame."""
    dx = targets[..., 0] - poses[..., 0].astype(np.float64)
    dy = targets[..., 1] - poses[..., 1].astype(np.float64)
    yaw = poses[..., 2].astype(np.float64)
    cos, sin = np.cos(yaw), np.sin(yaw)
    return cos * dx + sin * dy, -sin * dx + cos * dy


def touching_robot(poses: npt.NDArray[np.float32], body_radius: float) -> npt.NDArray[np.bool_]:
    """(N, R) whether each robot touches another (centres within two radii and 1 mm)."""
    xy = poses[..., :2].astype(np.float64)
    gaps = np.linalg.norm(xy[:, :, None, :] - xy[:, None, :, :], axis=-1)
    r = gaps.shape[1]
    gaps[:, np.arange(r), np.arange(r)] = np.inf
    touching: npt.NDArray[np.bool_] = gaps.min(axis=2) <= 2.0 * body_radius + TOUCH_SLACK
    return touching


class MultiRobotTask:
    """A task's rules for N environments x R robots (see the module).

    Subclasses set ``name``, ``observation_names`` and the step limit, and implement
    :meth:`draw`, :meth:`observe` and :meth:`reward`.

    Args:
        num_robots: Robots per environment.
        max_cycles: Steps after which every robot still going is truncated.
        body_radius: The robots' body radius in metres.
    """

    name = ""
    observation_names: tuple[str, ...] = ()
    #: The fewest robots the task has a meaning with.
    min_robots = 2

    def __init__(self, num_robots: int, max_cycles: int, body_radius: float) -> None:
        body_radius = finite_number("body_radius", body_radius, positive=True)
        if not self.min_robots <= num_robots <= 64:
            raise InvalidArgumentError(
                f"expected {self.min_robots} to 64 robots, found {num_robots}"
            )
        if max_cycles < 1:
            raise InvalidArgumentError(f"expected max_cycles >= 1, found {max_cycles}")
        self.num_robots = num_robots
        self.max_cycles = max_cycles
        self.body_radius = body_radius

    def bind(self, num_envs: int) -> None:
        """Makes room for the per-environment state of ``num_envs`` environments."""

    def draw(self, rng: np.random.Generator) -> EpisodeDraw:
        """A new episode of one environment, drawn from its stream ``rng``."""
        raise NotImplementedError

    def start(self, env: int, draw: EpisodeDraw, poses: npt.NDArray[np.float32]) -> None:
        """Environment ``env`` begins the episode ``draw``; its robots are at ``poses`` (R, 3)."""

    def observe(self, states: RobotStates) -> npt.NDArray[np.float32]:
        """(N, R, width) float32 observations."""
        raise NotImplementedError

    def reward(
        self, states: RobotStates, live: npt.NDArray[np.bool_]
    ) -> tuple[npt.NDArray[np.float32], npt.NDArray[np.bool_], dict[str, npt.NDArray[Any]]]:
        """Rewards (N, R) of the step just taken, the robots it ends (N, R; among ``live``), and
        per-robot infos by key (N, R) arrays."""
        raise NotImplementedError

    def _proximity(self, states: RobotStates) -> npt.NDArray[np.float32]:
        return states.readings[..., :8] / np.float32(PROXIMITY_MAX)


class MazeGoalsTask(MultiRobotTask):
    """Every robot to its own goal in an unseen maze (``maze_goals``; see the module).

    Observation of each robot, 12 float32 values: ps0-ps7 / 4095; its goal in its own frame
    (forward, left) in units of the maze's larger side; its previous action (wheel speed
    fractions; 0, 0 after a reset).

    Reward of a robot for a step: ``progress_reward`` per metre of progress along the shortest
    path through the maze to its goal, ``step_penalty`` (negative), ``goal_reward`` on reaching
    its goal (its centre in the goal disc), ``collision_penalty`` on a step touching a wall or
    another robot. The robot is done on reaching its goal and, with ``end_on_collision``, on its
    first contact; it then stands still (its wheels stopped) until the episode ends, where it
    still is an obstacle to the others. Without ``end_on_collision`` the penalty comes with every
    step in contact and the robot goes on.

    Args:
        num_robots: Robots per maze.
        maze_size: (columns, rows) of the generated mazes.
        loops: Share of extra openings in the mazes (0: perfect mazes).
        max_cycles: Step limit of an episode.
        body_radius: The robots' body radius in metres.
        end_on_collision: Whether a robot's first contact ends its episode.
        goal_reward: Reward on reaching the goal.
        collision_penalty: Reward of a step in contact (negative).
        progress_reward: Reward per metre of progress along the shortest path.
        step_penalty: Reward of every step (negative).
    """

    name = "maze_goals_v0"
    #: One robot alone in the maze is the task's single-agent case, as JaxNav allows.
    min_robots = 1
    observation_names = (
        *(f"ps{i}" for i in range(8)),
        "goal_forward",
        "goal_left",
        "previous_left",
        "previous_right",
    )

    def __init__(
        self,
        num_robots: int = 3,
        maze_size: tuple[int, int] = (4, 4),
        loops: float = 0.5,
        max_cycles: int = 300,
        body_radius: float = 0.037,
        end_on_collision: bool = True,
        goal_reward: float = 10.0,
        collision_penalty: float = -5.0,
        progress_reward: float = 10.0,
        step_penalty: float = -0.01,
    ) -> None:
        super().__init__(num_robots, max_cycles, body_radius)
        columns, rows = (int(v) for v in maze_size)
        if columns * rows < num_robots or min(columns, rows) < 2 or max(columns, rows) > 200:
            raise InvalidArgumentError(
                f"expected a maze of 2 to 200 cells a side (generate_maze's sizes) and as many "
                f"cells as robots ({num_robots}), found {columns} x {rows}"
            )
        self.maze_size = (columns, rows)
        self.loops = finite_number("loops", loops)
        self.end_on_collision = end_on_collision
        # NaN or infinite weights made every reward NaN.
        self.goal_reward = finite_number("goal_reward", goal_reward)
        self.collision_penalty = finite_number("collision_penalty", collision_penalty)
        self.progress_reward = finite_number("progress_reward", progress_reward)
        self.step_penalty = finite_number("step_penalty", step_penalty)
        self.bind(1)

    def bind(self, num_envs: int) -> None:
        r = self.num_robots
        self._distance: GoalDistance | None = None
        self._num_envs = num_envs
        self._goals = np.zeros((num_envs, r, 2))
        self._side = np.ones((num_envs, 1))
        self._previous = np.zeros((num_envs, r))

    def draw(self, rng: np.random.Generator) -> EpisodeDraw:
        columns, rows = self.maze_size
        maze_seed = int(rng.integers(2**31))
        sim_seed = int(rng.integers(2**63))
        maze_world = generate_maze(
            columns, rows, seed=maze_seed, loops=self.loops, layout=_WITHOUT_CHECKPOINTS
        )
        maze, cells = start_and_goal_cells(maze_world)
        r = self.num_robots
        starts_at = rng.choice(len(cells), size=r, replace=False)
        goals_at = rng.choice(len(cells), size=r, replace=False)
        # No robot's goal in its own start cell: a robot whose goal is its start swaps goals with
        # the next robot (the cyclic shift of a derangement), deterministically.
        for i in range(r):
            if goals_at[i] == starts_at[i]:
                j = (i + 1) % r
                goals_at[i], goals_at[j] = goals_at[j], goals_at[i]
        yaws = rng.uniform(-math.pi, math.pi, size=r)
        starts = np.zeros((r, 3))
        goals = np.zeros((r, 3))
        for i in range(r):
            row, column = cells[int(starts_at[i])]
            starts[i, :2] = maze.center((column, row))
            starts[i, 2] = yaws[i]
            row, column = cells[int(goals_at[i])]
            goals[i, :2] = maze.center((column, row))
            goals[i, 2] = maze.cell_size / 3.0
        world = robots_world(maze_world.to_toml(), starts, f"maze-goals-{maze_seed}")
        return EpisodeDraw(world, sim_seed, goals)

    def start(self, env: int, draw: EpisodeDraw, poses: npt.NDArray[np.float32]) -> None:
        r = self.num_robots
        tables = [
            PathDistanceTable.of_world(draw.world, tuple(float(v) for v in goal))  # type: ignore[arg-type]
            for goal in draw.goals
        ]
        if self._distance is None:
            self._distance = GoalDistance(self._num_envs * r, tables[0])
        for i, table in enumerate(tables):
            self._distance.set(env * r + i, table)
        self._goals[env] = draw.goals[:, :2]
        xmin, ymin, xmax, ymax = draw.world.bounds
        self._side[env] = max(xmax - xmin, ymax - ymin)
        distances, _ = self._distance.evaluate(self._flat(poses, env))
        self._previous[env] = distances[env * r : (env + 1) * r]

    def _flat(self, poses: npt.NDArray[np.float32], env: int) -> npt.NDArray[np.float32]:
        """(N * R, 3) poses of every robot, ``poses`` (R, 3) written in environment ``env``'s."""
        every = np.zeros((self._num_envs, self.num_robots, 3), np.float32)
        every[env] = poses
        return every.reshape(-1, 3)

    def observe(self, states: RobotStates) -> npt.NDArray[np.float32]:
        forward, left = _in_robot_frame(states.poses, self._goals)
        goal = np.stack((forward, left), axis=-1) / self._side[:, :, None]
        parts = (self._proximity(states), goal.astype(np.float32), states.actions)
        return np.concatenate(parts, axis=-1)

    def reward(
        self, states: RobotStates, live: npt.NDArray[np.bool_]
    ) -> tuple[npt.NDArray[np.float32], npt.NDArray[np.bool_], dict[str, npt.NDArray[Any]]]:
        assert self._distance is not None, "start() comes before reward()"
        n, r = live.shape
        distances, reached = self._distance.evaluate(states.poses.reshape(-1, 3))
        distances = distances.reshape(n, r)
        reached = reached.reshape(n, r) & live
        progress = self._previous - distances
        self._previous = distances
        contact = states.colliding & live
        reward = (
            self.progress_reward * progress
            + self.step_penalty
            + np.where(reached, self.goal_reward, 0.0)
            + np.where(contact, self.collision_penalty, 0.0)
        )
        ended = reached | (contact if self.end_on_collision else np.zeros_like(contact))
        infos = {
            "is_success": reached,
            "colliding": contact,
            "touching_robot": touching_robot(states.poses, self.body_radius) & live,
            "distance_to_goal": distances,
        }
        return np.where(live, reward, 0.0).astype(np.float32), ended & live, infos


class AggregationTask(MultiRobotTask):
    """The swarm gathers into one cluster (``aggregation``; see the module).

    Observation of each robot, 16 float32 values: ps0-ps7 / 4095; the nearest other robot's range
    (in units of the arena's side) and bearing (cosine, sine) in its frame; the same of the
    centroid of the other robots (what an e-puck's range-and-bearing board gives of its
    neighbours); its previous action.

    Reward of a robot for a step: minus its distance in metres to the centroid of the swarm, so
    a tight cluster earns most; no robot is ever done before the step limit (``max_cycles``).
    The infos give ``dispersion`` (Gauci et al.'s, every robot the same value) and the contacts.

    Args:
        num_robots: Robots in the arena.
        arena_side: Inner side of the square arena in metres.
        max_cycles: Step limit of an episode.
        body_radius: The robots' body radius in metres.
    """

    name = "aggregation_v0"
    observation_names = (
        *(f"ps{i}" for i in range(8)),
        "nearest_range",
        "nearest_cos",
        "nearest_sin",
        "centroid_range",
        "centroid_cos",
        "centroid_sin",
        "previous_left",
        "previous_right",
    )
    #: Wall thickness of the arena in metres.
    WALL = 0.01

    def __init__(
        self,
        num_robots: int = 5,
        arena_side: float = 1.0,
        max_cycles: int = 300,
        body_radius: float = 0.037,
    ) -> None:
        super().__init__(num_robots, max_cycles, body_radius)
        # A NaN, infinite or negative side was taken, and reset failed blaming the seed.
        arena_side = finite_number("arena_side", arena_side, positive=True)
        free = (arena_side - 2 * body_radius) ** 2
        if free < 4.0 * num_robots * (2 * body_radius) ** 2:
            raise InvalidArgumentError(
                f"expected an arena with room for {num_robots} robots, found a side of "
                f"{arena_side} m"
            )
        self.arena_side = float(arena_side)
        self._toml = self._arena_toml()

    def _arena_toml(self) -> str:
        half, wall = self.arena_side / 2.0, self.WALL
        middle = half + wall / 2.0
        span = self.arena_side + 2.0 * wall
        walls = [
            {"center": [cx, cy], "size": [sx, sy]}
            for cx, cy, sx, sy in (
                (0.0, middle, span, wall),
                (0.0, -middle, span, wall),
                (middle, 0.0, wall, span),
                (-middle, 0.0, wall, span),
            )
        ]
        layout = {"format": "mazesim-world", "version": 1, "name": "aggregation", "walls": walls}
        return dump_toml(layout)

    def draw(self, rng: np.random.Generator) -> EpisodeDraw:
        sim_seed = int(rng.integers(2**63))
        r = self.num_robots
        reach = self.arena_side / 2.0 - self.body_radius - 0.005
        apart = 2.0 * self.body_radius + 0.01
        starts = np.zeros((r, 3))
        placed = 0
        while placed < r:
            x, y = rng.uniform(-reach, reach, size=2)
            gaps = np.hypot(starts[:placed, 0] - x, starts[:placed, 1] - y)
            if np.all(gaps >= apart):
                starts[placed] = (x, y, rng.uniform(-math.pi, math.pi))
                placed += 1
        world = robots_world(self._toml, starts, "aggregation")
        return EpisodeDraw(world, sim_seed, np.full((r, 3), np.nan))

    def observe(self, states: RobotStates) -> npt.NDArray[np.float32]:
        xy = states.poses[..., :2].astype(np.float64)
        n, r, _ = xy.shape
        offsets = xy[:, None, :, :] - xy[:, :, None, :]  # (N, R, R, 2): robot j seen from i
        ranges = np.linalg.norm(offsets, axis=-1)
        ranges[:, np.arange(r), np.arange(r)] = np.inf
        nearest = ranges.argmin(axis=2)
        nearest_xy = np.take_along_axis(xy[:, None, :, :].repeat(r, 1), nearest[..., None, None], 2)
        others = (xy.sum(axis=1, keepdims=True) - xy) / (r - 1)
        parts = [self._proximity(states)]
        for target in (nearest_xy[:, :, 0, :], others):
            forward, left = _in_robot_frame(states.poses, target)
            distance = np.hypot(forward, left)
            safe = np.maximum(distance, 1e-9)
            parts.append(
                np.stack((distance / self.arena_side, forward / safe, left / safe), axis=-1).astype(
                    np.float32
                )
            )
        parts.append(states.actions)
        return np.concatenate(parts, axis=-1)

    def reward(
        self, states: RobotStates, live: npt.NDArray[np.bool_]
    ) -> tuple[npt.NDArray[np.float32], npt.NDArray[np.bool_], dict[str, npt.NDArray[Any]]]:
        xy = states.poses[..., :2].astype(np.float64)
        to_centroid = np.linalg.norm(xy - xy.mean(axis=1, keepdims=True), axis=-1)
        spread = dispersion(states.poses, self.body_radius)
        infos = {
            "dispersion": np.repeat(spread[:, None], live.shape[1], axis=1),
            "colliding": states.colliding & live,
            "touching_robot": touching_robot(states.poses, self.body_radius) & live,
            "distance_to_centroid": to_centroid,
        }
        reward = np.where(live, -to_centroid, 0.0).astype(np.float32)
        return reward, np.zeros_like(live), infos
