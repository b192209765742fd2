"""The ``"plan"`` observation (``mazesim/UnseenMaze-v2``): the next waypoint of a path planned
through the maze as the robot knows it, the sides it has not seen assumed open."""

from __future__ import annotations

import copy
import math
import pickle
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
import pytest

gymnasium = pytest.importorskip("gymnasium")

import mazesim  # noqa: E402
import mazesim.maze as directions  # noqa: E402
from env_worlds import TRAP  # noqa: E402
from mazesim.envs import EPuckMazeEnv  # noqa: E402
from mazesim.envs.navigation import _waypoints  # noqa: E402
from mazesim.errors import InvalidArgumentError  # noqa: E402
from mazesim.maze import CellMaze, PathDistanceTable  # noqa: E402
from navigation_oracle import assumed_open_sides, planned_waypoints  # noqa: E402

#: Cells of TRAP (column, row from the north).
START, GOAL, SOUTH_WEST = (1, 1), (0, 0), (0, 1)


def _centre(cell: tuple[int, int]) -> tuple[float, float]:
    """The centre of a (column, row) cell of TRAP (row 0 north)."""
    return (cell[0] + 0.5) * 0.25, (1 - cell[1] + 0.5) * 0.25


def _index(cell: tuple[int, int]) -> int:
    """The row-major index of a cell of TRAP."""
    return cell[1] * 3 + cell[0]


@pytest.fixture
def trap(tmp_path: Path) -> str:
    path = tmp_path / "trap.toml"
    path.write_text(TRAP)
    return str(path)


def _known(maze: CellMaze, *visited: tuple[int, int]) -> npt.NDArray[np.bool_]:
    """(1, rows, cols, 4): the open sides of ``maze`` as a robot that visited ``visited`` knows
    them."""
    seen = np.zeros((1, maze.rows, maze.cols), dtype=bool)
    for column, row in visited:
        seen[0, row, column] = True
    return assumed_open_sides(maze.open_sides()[None], seen)


def _plan(maze: CellMaze, *visited: tuple[int, int]) -> npt.NDArray[np.float64]:
    """(cells, 2): the waypoints planned to GOAL through TRAP as known after ``visited``."""
    return planned_waypoints(
        _known(maze, *visited),
        np.array([GOAL]),
        np.array([_centre(GOAL)]),
        np.array([maze.origin]),
        np.array([maze.cell_size]),
    )[0]


def test_unvisited_sides_are_assumed_open_visited_ones_are_as_they_are(trap: str) -> None:
    maze = CellMaze(mazesim.load_world(trap))
    known = _known(maze, START)[0]
    assert not known[START[1], START[0], directions.NORTH]  # the start's own wall: seen
    assert known[SOUTH_WEST[1], SOUTH_WEST[0], directions.NORTH]  # not seen: assumed open ...
    assert not maze.is_open(SOUTH_WEST, directions.NORTH)  # ... but a wall
    assert (
        not known[0, 1, directions.SOUTH] and not known[1, 1, directions.NORTH]
    )  # both sides of a seen wall
    assert (
        not known[0, 2, directions.EAST] and not known[1, 0, directions.WEST]
    )  # the outer wall is known
    everything = _known(maze, *maze.cells())[0]
    assert np.array_equal(everything, maze.open_sides())
    with pytest.raises(InvalidArgumentError, match=r"shape \(1, 2, 3\), found shape \(1, 3, 2\)"):
        assumed_open_sides(maze.open_sides()[None], np.zeros((1, 3, 2), dtype=bool))


def test_the_plan_goes_through_unseen_sides_until_a_wall_is_found(trap: str) -> None:
    maze = CellMaze(mazesim.load_world(trap))
    goal = list(_centre(GOAL))
    planned = _plan(maze, START)
    assert planned[_index(START)].tolist() == list(_centre(SOUTH_WEST))  # west: the short way
    assert planned[_index(SOUTH_WEST)].tolist() == goal  # through the unseen side
    planned = _plan(maze, START, SOUTH_WEST)  # there the robot sees the wall north of it
    assert planned[_index(SOUTH_WEST)].tolist() == list(_centre(START))  # back east
    assert planned[_index(START)].tolist() == list(_centre((2, 1)))  # the true way round
    assert planned[_index((2, 1))].tolist() == list(_centre((2, 0)))
    assert planned[_index(GOAL)].tolist() == goal


@pytest.mark.parametrize("loops", [0.0, 0.4])
def test_with_every_cell_visited_the_plan_is_the_true_shortest_path(loops: float) -> None:
    worlds = [mazesim.generate_maze(5, 5, seed=seed, loops=loops) for seed in range(4)]
    mazes = [CellMaze(world) for world in worlds]
    tables = [PathDistanceTable.of_world(world) for world in worlds]
    planned = planned_waypoints(
        np.stack([maze.open_sides() for maze in mazes]),  # all four at once
        np.array([maze.goal_cell for maze in mazes]),
        np.array([table.goal[:2] for table in tables]),
        np.array([maze.origin for maze in mazes]),
        np.array([maze.cell_size for maze in mazes]),
    )
    for seed, table in enumerate(tables):
        assert np.array_equal(planned[seed], _waypoints(table)), seed


def _waypoint(env: EPuckMazeEnv, cell: tuple[int, int], yaw: float) -> tuple[float, float]:
    """The observed waypoint (forward, left, in cells) after moving the robot to a cell's centre
    facing ``yaw``."""
    env._simulator.set_pose(*_centre(cell), yaw)
    observation = env.step(np.zeros(2, dtype=np.float32))[0]
    value = dict(zip(env.observation_names, observation.tolist()))
    return value["waypoint_forward"], value["waypoint_left"]


def test_the_observed_waypoint_changes_when_the_robot_finds_a_wall(trap: str) -> None:
    env = EPuckMazeEnv(world=trap, observation="plan", noise=False)
    env.reset(seed=0)
    assert env.observation_names[11:15] == [
        "goal_forward",
        "goal_left",
        "waypoint_forward",
        "waypoint_left",
    ]
    # In the start cell facing east: the plan leads west, behind the robot.
    assert _waypoint(env, START, 0.0) == pytest.approx((-1.0, 0.0), abs=1e-5)
    # In the south-west cell, facing north: its north wall is seen, the plan leads back east.
    assert _waypoint(env, SOUTH_WEST, math.pi / 2) == pytest.approx((0.0, -1.0), abs=1e-5)
    assert _waypoint(env, START, 0.0) == pytest.approx((1.0, 0.0), abs=1e-5)
    # The guided waypoint, on the true path, leads east from the first step.
    guided = EPuckMazeEnv(world=trap, observation="guided", noise=False)
    guided.reset(seed=0)
    assert _waypoint(guided, START, 0.0) == pytest.approx((1.0, 0.0), abs=1e-5)
    # A new episode forgets the map: west again.
    env.reset(seed=1)
    assert _waypoint(env, START, 0.0) == pytest.approx((-1.0, 0.0), abs=1e-5)


def _trace(seed: int, steps: int) -> list[Any]:
    env = gymnasium.make("mazesim/UnseenMaze-v2")
    observation, _ = env.reset(seed=seed)
    rng = np.random.default_rng(seed)
    trace = [observation]
    for _ in range(steps):
        action = (0.6 + 0.4 * rng.uniform(-1, 1, 2)).astype(np.float32)
        trace.append(env.step(action)[0])
    return trace


def test_same_seed_same_plan() -> None:
    first, again, other = _trace(3, 150), _trace(3, 150), _trace(4, 150)
    assert all(np.array_equal(a, b) for a, b in zip(first, again, strict=True))
    assert not all(np.array_equal(a, b) for a, b in zip(first, other, strict=True))


def test_native_vector_env_equals_sync_while_plans_change() -> None:
    num_envs = 5
    options = {"max_episode_steps": 400}
    native = gymnasium.make_vec(
        "mazesim/UnseenMaze-v2", num_envs, vectorization_mode="vector_entry_point", **options
    )
    sync = gymnasium.make_vec(
        "mazesim/UnseenMaze-v2", num_envs, vectorization_mode="sync", **options
    )
    names = native.unwrapped.observation_names
    waypoint = [names.index("waypoint_forward"), names.index("waypoint_left")]
    first, expected = native.reset(seed=11)[0], sync.reset(seed=11)[0]
    assert np.array_equal(first, expected)
    rng = np.random.default_rng(11)
    jumps = 0
    previous = first[:, waypoint]
    for step in range(900):
        actions = (0.6 + 0.4 * rng.uniform(-1, 1, (num_envs, 2))).astype(np.float32)
        mine, theirs = native.step(actions), sync.step(actions)
        for a, b in zip(mine[:4], theirs[:4]):
            assert a.dtype == b.dtype and np.array_equal(a, b), step
        # A new plan (or a new cell) moves the waypoint by a large step at once.
        jumps += int((np.abs(mine[0][:, waypoint] - previous).max(axis=1) > 0.5).sum())
        previous = mine[0][:, waypoint]
    assert jumps > num_envs
    native.close()
    sync.close()


def test_a_rule_that_follows_the_plan_reaches_every_goal() -> None:
    # Turn towards the waypoint, drive when it is roughly ahead: every unseen maze is solved,
    # so the observation carries what a memoryless policy needs (uniform random actions reach
    # about 1 goal in 100 in the same time).
    num_envs = 16
    envs = gymnasium.make_vec(
        "mazesim/UnseenMaze-v2", num_envs, vectorization_mode="vector_entry_point"
    )
    names = envs.unwrapped.observation_names
    forward, left = names.index("waypoint_forward"), names.index("waypoint_left")
    observations, _ = envs.reset(seed=5)
    ended = np.zeros(num_envs, dtype=bool)
    reached = np.zeros(num_envs, dtype=bool)
    for _ in range(3000):  # the time limit: every episode has ended by then
        angle = np.arctan2(observations[:, left], observations[:, forward])
        drive = np.where(np.abs(angle) > 0.5, 0.0, 0.8)
        actions = np.stack([drive - angle, drive + angle], axis=1).clip(-1, 1).astype(np.float32)
        observations, _, terminated, truncated, _ = envs.step(actions)
        reached |= terminated & ~ended
        ended |= terminated | truncated
        if ended.all():
            break
    assert reached.all()
    envs.close()


def test_a_copy_goes_on_with_the_same_map_and_plan() -> None:
    env = gymnasium.make("mazesim/UnseenMaze-v2")
    env.reset(seed=8)
    forward = np.array([0.7, 0.75], dtype=np.float32)
    for _ in range(120):  # a few cells in: visits and a plan of this episode
        env.step(forward)
    twin = copy.deepcopy(env)
    again = pickle.loads(pickle.dumps(env))
    for step in range(300):
        expected = env.step(forward)[0]
        assert np.array_equal(twin.step(forward)[0], expected), step
        assert np.array_equal(again.step(forward)[0], expected), step
