"""The task suite: every registered task passes gymnasium's checker, random starts and goals,
the goal-conditioned observations, and the native vector env equal to SyncVectorEnv on them."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

from gymnasium.utils.env_checker import check_env  # noqa: E402

import mazesim  # noqa: E402
from env_worlds import CORRIDOR  # noqa: E402
from mazesim.envs import TASKS, EPuckMazeEnv  # noqa: E402
from mazesim.envs.navigation import with_start_and_goal  # noqa: E402
from mazesim.errors import InvalidArgumentError  # noqa: E402
from mazesim.maze import CellMaze  # noqa: E402


@pytest.mark.parametrize("task", TASKS, ids=[task.env_id for task in TASKS])
def test_every_task_passes_check_env(task: Any) -> None:
    env = gymnasium.make(task.env_id)
    assert env.spec.max_episode_steps == task.max_episode_steps
    check_env(env.unwrapped)
    observation, _ = env.reset(seed=0)
    assert env.observation_space.contains(observation)
    env.close()


def test_tiers_run_from_one_fixed_maze_to_unseen_mazes() -> None:
    assert [task.tier for task in TASKS] == [0, 1, 2, 3, 4]
    assert TASKS[0].options == {}  # EPuckMaze-v0 as it was
    first = gymnasium.make("mazesim/MazeFixed-v1").unwrapped
    starts = {(first.reset(seed=s)[1]["pose"].tobytes()) for s in range(3)}
    assert len(starts) == 1  # tier 1: one start
    unseen = gymnasium.make("mazesim/UnseenMaze-v1").unwrapped
    walls = set()
    for seed in range(3):
        unseen.reset(seed=seed)
        walls.add(unseen.world.wall_boxes().tobytes())
    assert len(walls) == 3  # tier 3: a new maze every episode


def test_random_start_and_goal_are_distinct_cells_drawn_from_the_seed() -> None:
    env = EPuckMazeEnv(world="seed-maze", start_goal="random", observation="goal")
    seen = set()
    for seed in range(8):
        env.reset(seed=seed)
        maze = env.world.cell_maze()
        assert maze is not None and maze["start"] != maze["goal"]
        x, y, yaw = env.world.start
        col, row = maze["start"]
        assert (x, y) == pytest.approx((0.125 + 0.25 * col, 0.125 + 0.25 * (4 - row)))
        seen.add((maze["start"], maze["goal"], yaw))
    assert len(seen) == 8
    again = EPuckMazeEnv(world="seed-maze", start_goal="random")
    again.reset(seed=7)
    assert again.world == env.world
    # The walls and barcodes are seed-maze's.
    assert np.array_equal(env.world.wall_boxes(), mazesim.load_world("seed-maze").wall_boxes())


def test_random_start_and_goal_always_join() -> None:
    # seed-maze's cells (1, 1), (3, 1), (1, 3) and (3, 3) are walled in: never a start or a goal.
    env = EPuckMazeEnv(world="seed-maze", start_goal="random", observation="goal")
    cells = set()
    for seed in range(120):
        env.reset(seed=seed)
        maze = CellMaze(env.world)
        assert maze.start_cell is not None and maze.goal_cell is not None
        column, row = maze.goal_cell
        assert maze.distances_from(maze.start_cell)[row, column] > 0
        cells |= {maze.start_cell, maze.goal_cell}
    assert cells == {(c, r) for c in range(5) for r in range(5)} - {(1, 1), (3, 1), (1, 3), (3, 3)}


def test_tiers_1_to_3_act_every_128_ms_and_tier_2_observes_the_pose() -> None:
    for env_id in ("mazesim/MazeFixed-v1", "mazesim/MazeRandomGoal-v1", "mazesim/UnseenMaze-v1"):
        assert gymnasium.make(env_id).unwrapped.metadata["render_fps"] == 1000 / 128
    env = gymnasium.make("mazesim/MazeRandomGoal-v1").unwrapped
    observation, info = env.reset(seed=3)
    value = dict(zip(env.observation_names, observation.tolist()))
    x, y, yaw = info["pose"].tolist()
    assert value["x"] == pytest.approx(x / 1.25, abs=0.02)  # seed-maze's bounds span 1.25 m
    assert value["y"] == pytest.approx(y / 1.25, abs=0.02)
    assert (value["heading_cos"], value["heading_sin"]) == pytest.approx(
        (math.cos(yaw), math.sin(yaw)), abs=1e-6
    )
    assert "x" not in gymnasium.make("mazesim/MazeFixed-v1").unwrapped.observation_names


def test_with_start_and_goal_moves_both() -> None:
    world = with_start_and_goal(mazesim.generate_maze(5, 5, seed=1), (2, 3), (0, 0), 0.5)
    maze = world.cell_maze()
    assert maze is not None and maze["start"] == (3, 2) and maze["goal"] == (0, 0)
    assert world.start == pytest.approx((0.875, 0.625, 0.5))
    assert world.goal[:2] == pytest.approx((0.125, 1.125))


def test_goal_and_waypoint_are_in_the_robots_frame(tmp_path: Any) -> None:
    path = tmp_path / "corridor.toml"
    path.write_text(CORRIDOR)
    env = EPuckMazeEnv(world=str(path), observation="guided", noise=False)
    observation, _ = env.reset(seed=0)
    names = env.observation_names
    value = dict(zip(names, observation.tolist()))
    # The start faces east, the goal two cells east: ahead, not aside; the waypoint one cell ahead.
    xmin, ymin, xmax, ymax = env.world.bounds  # the goal in units of the larger side
    assert value["goal_forward"] == pytest.approx(0.5 / max(xmax - xmin, ymax - ymin), abs=1e-3)
    assert value["goal_left"] == pytest.approx(0.0, abs=1e-3)
    assert value["waypoint_forward"] == pytest.approx(1.0, abs=1e-3)
    assert value["previous_left"] == value["previous_right"] == 0.0
    assert 0.0 < value["ps0"] < 0.1  # normalised: nothing near
    action = np.array([0.5, -0.25], dtype=np.float32)
    value = dict(zip(names, env.step(action)[0].tolist()))
    assert (value["previous_left"], value["previous_right"]) == (0.5, -0.25)


def test_bad_task_options_raise() -> None:
    with pytest.raises(InvalidArgumentError, match="observation"):
        EPuckMazeEnv(observation="pixels")
    with pytest.raises(InvalidArgumentError, match="start_goal"):
        EPuckMazeEnv(start_goal="anywhere")
    with pytest.raises(InvalidArgumentError, match="cell maze"):
        EPuckMazeEnv(world="arena", start_goal="random").reset(seed=0)


@pytest.mark.parametrize("env_id", ["mazesim/MazeRandomGoal-v1", "mazesim/UnseenMazeGuided-v0"])
@pytest.mark.parametrize("action_mode", ["continuous", "discrete"])
def test_native_vector_env_equals_sync_on_the_tasks(env_id: str, action_mode: str) -> None:
    num_envs = 4
    options = {"max_episode_steps": 80, "action_mode": action_mode}
    native = gymnasium.make_vec(
        env_id, num_envs, vectorization_mode="vector_entry_point", **options
    )
    sync = gymnasium.make_vec(env_id, num_envs, vectorization_mode="sync", **options)
    assert native.single_observation_space == sync.single_observation_space
    first, expected = native.reset(seed=4)[0], sync.reset(seed=4)[0]
    assert np.array_equal(first, expected)
    native.action_space.seed(4)
    for step in range(200):
        actions = native.action_space.sample()
        mine, theirs = native.step(actions), sync.step(actions)
        for a, b in zip(mine[:4], theirs[:4]):
            assert a.dtype == b.dtype and np.array_equal(a, b), step
        assert mine[4].keys() == theirs[4].keys()
        assert all(np.array_equal(mine[4][k], theirs[4][k]) for k in mine[4]), step
    assert math.isfinite(float(first.sum()))
