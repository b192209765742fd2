"""The task observations the core computes (``mazesim._core.TaskFeatures``) equal, bit for bit,
those of the numpy code the tasks observed before (``tests/navigation_oracle.py``): every kind
of observation, with and without the pose, over random mazes of several shapes, worlds without a
cell maze, random goals and robots wandering from cell to cell (visits, plans made again),
headings of every quadrant and poses off the grid."""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
import pytest

pytest.importorskip("gymnasium")

import mazesim  # noqa: E402
from mazesim.envs.navigation import NavigationFeatures, draw_start_and_goal  # noqa: E402
from mazesim.errors import InvalidArgumentError  # noqa: E402
from mazesim.maze import GoalDistance, PathDistanceTable  # noqa: E402
from navigation_oracle import NumpyNavigationFeatures  # noqa: E402

ROBOT = mazesim.RobotProfile.builtin("e-puck")
#: (guided, pose, explore, plan) of each observation kind, with and without the pose.
KINDS = [
    (guided, pose, explore, plan)
    for guided, explore, plan in (
        (False, False, False),
        (False, True, False),
        (True, False, False),
        (False, True, True),
    )
    for pose in (False, True)
]
NUM_ENVS = 6
STEPS = 120


def _world(rng: np.random.Generator) -> mazesim.World:
    """A random maze of 2 to 6 cells a side, seed-maze, or a world without a cell maze."""
    pick = rng.integers(0, 10)
    if pick == 0:
        return mazesim.World.builtin("seed-maze")
    if pick == 1:
        return mazesim.World.builtin("arena")
    width, height = rng.integers(2, 7, size=2)
    return mazesim.generate_maze(int(width), int(height), seed=int(rng.integers(0, 2**31)))


def _table(world: mazesim.World, rng: np.random.Generator) -> PathDistanceTable:
    if world.cell_maze() is not None and rng.random() < 0.7:
        return PathDistanceTable.of_world(world, draw_start_and_goal(world, rng).goal)
    return PathDistanceTable.of_world(world)


def _poses(
    worlds: list[mazesim.World], positions: npt.NDArray[np.float64], rng: np.random.Generator
) -> npt.NDArray[np.float32]:
    """Moves each robot a random step (now and then a whole cell, now and then off the world)
    and draws its heading: any angle, a multiple of 45 degrees (rounding ties) or beyond pi."""
    poses = np.empty((len(worlds), 3), dtype=np.float32)
    for env, world in enumerate(worlds):
        xmin, ymin, xmax, ymax = world.bounds
        step = rng.choice([0.02, 0.25, 0.6], p=[0.6, 0.35, 0.05])
        positions[env] += rng.normal(0.0, step, size=2)
        positions[env] = np.clip(positions[env], (xmin - 0.1, ymin - 0.1), (xmax + 0.1, ymax + 0.1))
        kind = rng.integers(0, 3)
        yaw = (
            rng.uniform(-math.pi, math.pi)
            if kind == 0
            else rng.integers(-8, 9) * math.pi / 4
            if kind == 1
            else rng.uniform(-10.0, 10.0)
        )
        poses[env] = (positions[env, 0], positions[env, 1], yaw)
    return poses


@pytest.mark.parametrize("kind", KINDS, ids=lambda k: "-".join(str(int(v)) for v in k))
@pytest.mark.parametrize("seed", range(4))
def test_core_features_equal_the_numpy_oracle(
    kind: tuple[bool, bool, bool, bool], seed: int
) -> None:
    guided, pose, explore, plan = kind
    rng = np.random.default_rng(1000 * seed + sum(v << i for i, v in enumerate(kind)))
    worlds = [_world(rng) for _ in range(NUM_ENVS)]
    tables = [_table(world, rng) for world in worlds]
    core = NavigationFeatures(NUM_ENVS, ROBOT, guided, pose, explore=explore, plan=plan)
    oracle = NumpyNavigationFeatures(core)
    for env in range(NUM_ENVS):
        for features in (core, oracle):
            features.set(env, worlds[env], tables[env])
    positions = np.array([world.start[:2] for world in worlds], dtype=np.float64)
    width = core.sensor_width
    for step in range(STEPS):
        if step % 40 == 39:  # a new episode (and now and then a new world) for some envs
            envs = np.flatnonzero(rng.random(NUM_ENVS) < 0.5)
            for env in envs.tolist():
                if rng.random() < 0.5:
                    worlds[env] = _world(rng)
                    tables[env] = _table(worlds[env], rng)
                    core.set(env, worlds[env], tables[env])
                    oracle.set(env, worlds[env], tables[env])
            core.restart(envs)
            oracle.restart(envs)
        readings = rng.uniform(0.0, 4500.0, size=(NUM_ENVS, width)).astype(np.float32)
        poses = _poses(worlds, positions, rng)
        previous = rng.uniform(-1.0, 1.0, size=(NUM_ENVS, 2)).astype(np.float32)
        expected = oracle.observe(readings, poses, previous)
        found = core.observe(readings, poses, previous)
        assert found.dtype == np.float32 and found.shape == expected.shape
        np.testing.assert_array_equal(found.view(np.uint32), expected.view(np.uint32))


def test_the_single_env_path_equals_the_batch_path() -> None:
    """``observe_one`` (one env, the previous action from wheel speeds) equals ``observe``."""
    rng = np.random.default_rng(7)
    world = mazesim.generate_maze(5, 5, seed=3)
    table = PathDistanceTable.of_world(world)
    one = NavigationFeatures(1, ROBOT, False, False, explore=True, plan=True)
    batch = NavigationFeatures(1, ROBOT, False, False, explore=True, plan=True)
    one.set(0, world, table)
    batch.set(0, world, table)
    max_speed = np.float32(6.28)
    positions = np.array([world.start[:2]])
    for _ in range(200):
        readings = rng.uniform(0.0, 4500.0, size=(1, one.sensor_width)).astype(np.float32)
        pose = _poses([world], positions, rng)
        speeds = (rng.uniform(-1.0, 1.0, size=(1, 2)) * max_speed).astype(np.float32)
        found, _, _ = one.observe_one(readings[0], pose[0], *speeds[0].tolist(), float(max_speed))
        expected = batch.observe(readings, pose, speeds / max_speed)[0]
        np.testing.assert_array_equal(found.view(np.uint32), expected.view(np.uint32))


def test_bad_arrays_are_invalid_argument_errors() -> None:
    features = NavigationFeatures(2, ROBOT, True)
    good = np.zeros((2, features.sensor_width), np.float32)
    with pytest.raises(InvalidArgumentError, match="readings"):
        features.observe(good[:1], np.zeros((2, 3), np.float32), np.zeros((2, 2), np.float32))
    with pytest.raises(InvalidArgumentError, match="poses"):
        features.observe(good, np.zeros((2, 3), np.float64), np.zeros((2, 2), np.float32))
    with pytest.raises(InvalidArgumentError, match="environment index"):
        features._core.restart(2)


@pytest.mark.parametrize("seed", range(3))
def test_the_core_goal_distance_equals_the_numpy_one(seed: int) -> None:
    """The distance and the goal test ``observe_one`` gives equal ``GoalDistance``'s, which the
    vector env computes with numpy: random mazes and goals, seed-maze, a world without a maze."""
    rng = np.random.default_rng(seed)
    features = NavigationFeatures(1, ROBOT, False)
    readings = np.zeros(features.sensor_width, np.float32)
    for _ in range(8):
        world = _world(rng)
        table = _table(world, rng)
        features.set(0, world, table)
        numpy_goal = GoalDistance(1, table)
        positions = np.array([world.start[:2]], dtype=np.float64)
        for _ in range(60):
            pose = _poses([world], positions, rng)
            if rng.random() < 0.1:  # now and then right at the goal
                pose[0, :2] = table.goal[:2]
            _, distance, reached = features.observe_one(readings, pose[0], 0.0, 0.0, 6.28)
            expected, expected_reached = numpy_goal.evaluate(pose)
            assert distance == float(expected[0]) and reached == bool(expected_reached[0])
