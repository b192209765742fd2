"""The task suite: every registered task passes gymnasium's checker, random starts and goals,
the goal-conditioned observations, and the native vector env equal to SyncVectorEnv on them."""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

from gymnasium.utils.env_checker import check_env  # noqa: E402

import mazesim  # noqa: E402
from env_worlds import CORRIDOR  # noqa: E402
from mazesim.envs import TASKS, EPuckMazeEnv  # noqa: E402
from mazesim.envs.navigation import draw_start_and_goal  # noqa: E402
from mazesim.errors import InvalidArgumentError, UnknownNameError  # noqa: E402
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
    assert [task.tier for task in TASKS] == [0, 1, 2, 3, 3, 4]
    assert TASKS[0].options == {}  # EPuckMaze-v0 as it was
    first = gymnasium.make("mazesim/MazeFixed-v1").unwrapped
    starts = {(first.reset(seed=s)[1]["pose"].tobytes()) for s in range(3)}
    assert len(starts) == 1  # tier 1: one start
    unseen = gymnasium.make("mazesim/UnseenMazeExplore-v0").unwrapped
    walls = set()
    for seed in range(3):
        unseen.reset(seed=seed)
        walls.add(unseen.world.wall_boxes().tobytes())
    assert len(walls) == 3  # tier 3: a new maze every episode
    assert gymnasium.make("mazesim/UnseenMazeExplore-v0").unwrapped.options.observation == "explore"
    planned = gymnasium.make("mazesim/UnseenMaze-v2").unwrapped
    assert planned.options.observation == "plan" and planned.metadata["render_fps"] == 1000 / 32
    names = planned.observation_names
    assert names[: len(unseen.observation_names) - 2] != unseen.observation_names[:-2]
    assert set(unseen.observation_names) | {"waypoint_forward", "waypoint_left"} == set(names)


def test_random_start_and_goal_are_distinct_cells_drawn_from_the_seed() -> None:
    env = EPuckMazeEnv(world="seed-maze", start_goal="random", observation="goal")
    seed_maze = mazesim.load_world("seed-maze")
    maze = CellMaze(seed_maze)
    seen = set()
    for seed in range(8):
        _, info = env.reset(seed=seed)
        x, y, yaw = info["pose"].tolist()
        goal = env._simulator.goal
        assert goal is not None
        start_cell = tuple(int(v) for v in maze.cell_at(x, y))
        goal_cell = tuple(int(v) for v in maze.cell_at(goal[0], goal[1]))
        assert start_cell != goal_cell
        assert (x, y) == pytest.approx(maze.center(start_cell), abs=1e-6)
        assert goal == pytest.approx((*maze.center(goal_cell), 0.25 / 3))
        seen.add((start_cell, goal_cell, round(yaw, 5)))
    assert len(seen) == 8
    again = EPuckMazeEnv(world="seed-maze", start_goal="random")
    assert np.array_equal(again.reset(seed=7)[1]["pose"], env.reset(seed=7)[1]["pose"])
    # The world is seed-maze itself: start and goal belong to the simulator.
    assert env.world == seed_maze


def test_random_start_and_goal_always_join() -> None:
    # seed-maze's cells (1, 1), (3, 1), (1, 3) and (3, 3) are walled in: never a start or a goal.
    world = mazesim.load_world("seed-maze")
    maze = CellMaze(world)
    rng = np.random.default_rng(0)
    cells = set()
    for _ in range(150):
        drawn = draw_start_and_goal(world, rng)
        start = tuple(int(v) for v in maze.cell_at(drawn.start[0], drawn.start[1]))
        goal = tuple(int(v) for v in maze.cell_at(drawn.goal[0], drawn.goal[1]))
        assert maze.distances_from(start)[goal[1], goal[0]] > 0
        cells |= {start, goal}
    assert cells == {(c, r) for c in range(5) for r in range(5)} - {(1, 1), (3, 1), (1, 3), (3, 3)}


def test_the_drawn_goal_ends_the_episode_and_shapes_the_reward() -> None:
    env = EPuckMazeEnv(world="seed-maze", start_goal="random", observation="goal", noise=False)
    _, info = env.reset(seed=2)
    goal = env._simulator.goal
    assert goal is not None and goal[:2] != mazesim.load_world("seed-maze").goal[:2]
    x, y, _ = info["pose"].tolist()
    maze = CellMaze(env.world)
    start = tuple(int(v) for v in maze.cell_at(x, y))
    cells = maze.distances_from(start)[tuple(int(v) for v in maze.cell_at(goal[0], goal[1]))[::-1]]
    assert info["distance_to_goal"] == pytest.approx(0.25 * cells, abs=1e-6)
    # Moved onto its goal, the robot ends the episode there.
    env._simulator.set_pose(goal[0], goal[1], 0.0)
    _, reward, terminated, _, info = env.step(np.zeros(2, dtype=np.float32))
    assert terminated and info["is_success"] and reward > 9.0


def test_tiers_1_to_3_act_every_128_ms_and_tier_2_observes_the_pose() -> None:
    for env_id in (
        "mazesim/MazeFixed-v1",
        "mazesim/MazeRandomGoal-v1",
        "mazesim/UnseenMazeExplore-v0",
    ):
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
    with pytest.raises(UnknownNameError, match="observation"):
        EPuckMazeEnv(observation="pixels")
    with pytest.raises(UnknownNameError, match="start_goal"):
        EPuckMazeEnv(start_goal="anywhere")
    with pytest.raises(InvalidArgumentError, match="cell maze"):
        EPuckMazeEnv(world="arena", start_goal="random").reset(seed=0)


@pytest.mark.parametrize(
    "env_id", ["mazesim/MazeRandomGoal-v1", "mazesim/UnseenMaze-v2", "mazesim/UnseenMazeGuided-v0"]
)
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


def test_the_explored_map_counts_visits_round_the_robot(tmp_path: Any) -> None:
    path = tmp_path / "corridor.toml"
    path.write_text(CORRIDOR)  # three cells west to east, the start facing east in the first
    env = EPuckMazeEnv(world=str(path), observation="explore", noise=False)
    observation, _ = env.reset(seed=0)
    names = env.observation_names
    value = dict(zip(names, observation.tolist()))
    sides = ("ahead", "left", "behind", "right")
    assert [value[f"open_{side}"] for side in sides] == [1.0, 0.0, 0.0, 0.0]
    assert [value[f"visits_{side}"] for side in sides] == [0.0] * 4
    assert value["visits_here"] == pytest.approx(1 / 3)
    forward = np.array([1.0, 1.0], dtype=np.float32)
    while True:  # drive east into the middle cell
        value = dict(zip(names, env.step(forward)[0].tolist()))
        if value["open_behind"] == 1.0:
            break
    assert [value[f"open_{side}"] for side in sides] == [1.0, 0.0, 1.0, 0.0]
    assert value["visits_behind"] == pytest.approx(1 / 3) and value["visits_ahead"] == 0.0
    # Turned round (west), the first cell is ahead now, still visited once.
    env._simulator.set_pose(0.375, 0.125, math.pi)
    value = dict(zip(names, env.step(np.zeros(2, dtype=np.float32))[0].tolist()))
    assert value["visits_ahead"] == pytest.approx(1 / 3) and value["visits_behind"] == 0.0
    # A new episode forgets the visits.
    value = dict(zip(names, env.reset(seed=1)[0].tolist()))
    assert value["visits_here"] == pytest.approx(1 / 3) and value["visits_ahead"] == 0.0


def test_the_learning_tier_is_made_without_a_warning_and_its_former_id_still_works() -> None:
    # Registered as UnseenMaze-v1, gymnasium called it out of date beside UnseenMaze-v2.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        env = gymnasium.make("mazesim/UnseenMazeExplore-v0")
    with pytest.warns(DeprecationWarning, match="out of date"):
        former = gymnasium.make("mazesim/UnseenMaze-v1")
    assert former.unwrapped.options == env.unwrapped.options
    assert former.spec.max_episode_steps == env.spec.max_episode_steps == 1000
    assert (former.reset(seed=3)[0] == env.reset(seed=3)[0]).all()
