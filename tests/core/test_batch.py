"""The batch engine from Python: equality with lone simulators, buffers, errors."""

from __future__ import annotations

import numpy as np
import pytest

import mazesim
from batch_buffers import buffers
from mazesim import BatchSimulator, InvalidActionError, InvalidArgumentError, Simulator

STEPS = 150


def actions_for(n: int, step: int) -> np.ndarray:
    t = step * 0.05 + np.arange(n, dtype=np.float32)
    return np.stack([4 + 2.5 * np.sin(t), 4 + 2.5 * np.cos(1.7 * t)], axis=1).astype(np.float32)


def batch_run(n: int, threads: int, watch: int) -> np.ndarray:
    worlds = [mazesim.generate_maze(5, 5, seed=i, loops=0.1) for i in range(n)]
    batch = BatchSimulator(worlds, seeds=100, threads=threads)
    obs, poses, colliding, crossings = buffers(batch)
    batch.reset(obs, poses, colliding, crossings)
    rows = []
    for step in range(STEPS):
        batch.step(actions_for(n, step), obs, poses, colliding, crossings)
        rows.append(np.concatenate([obs[watch], poses[watch]]))
    return np.array(rows)


def lone_run(env: int) -> np.ndarray:
    sim = Simulator(mazesim.generate_maze(5, 5, seed=env, loops=0.1), seed=100 + env)
    rows = []
    for step in range(STEPS):
        left, right = actions_for(env + 1, step)[env]
        sim.step(float(left), float(right))
        rows.append(
            np.concatenate([sim.distance_sensors(), sim.ground_sensors(), np.float32(sim.pose)])
        )
    return np.array(rows, dtype=np.float32)


@pytest.mark.parametrize(("n", "threads"), [(1, 1), (7, 1), (7, 2), (64, 2)])
def test_env_0_equals_a_lone_simulator(n: int, threads: int) -> None:
    assert np.array_equal(batch_run(n, threads, 0), lone_run(0))


def test_env_6_is_the_same_in_batches_of_7_and_64() -> None:
    lone = lone_run(6)
    assert np.array_equal(batch_run(7, 1, 6), lone)
    assert np.array_equal(batch_run(64, 2, 6), lone)


@pytest.fixture
def small_batch() -> BatchSimulator:
    return BatchSimulator(mazesim.load_world("arena"), num_envs=3, seeds=[5, 6, 7], noise=False)


def test_bad_actions_raise_the_packages_errors(small_batch: BatchSimulator) -> None:
    obs, poses, colliding, crossings = buffers(small_batch)
    with pytest.raises(InvalidArgumentError, match=r"float32 and shape \(3, 2\).*float64"):
        small_batch.step(np.zeros((3, 2)), obs, poses, colliding, crossings)
    with pytest.raises(InvalidArgumentError, match=r"shape \(3, 2\)"):
        small_batch.step(np.zeros((2, 2), np.float32), obs, poses, colliding, crossings)
    nan = np.ones((3, 2), np.float32)
    nan[2, 1] = np.nan
    with pytest.raises(InvalidActionError, match="environment 2"):
        small_batch.step(nan, obs, poses, colliding, crossings)
    assert np.all(small_batch.steps() == 0)
    with pytest.raises(InvalidArgumentError, match="observations"):
        small_batch.step(np.ones((3, 2), np.float32), obs[:, :5], poses, colliding, crossings)
    with pytest.raises(InvalidArgumentError, match="colliding"):
        small_batch.step(np.ones((3, 2), np.float32), obs, poses, crossings, crossings)


def test_masked_reset_and_its_errors(small_batch: BatchSimulator) -> None:
    obs, poses, colliding, crossings = buffers(small_batch)
    small_batch.reset(obs, poses, colliding, crossings)
    for _ in range(5):
        small_batch.step(np.full((3, 2), 4.0, np.float32), obs, poses, colliding, crossings)
    small_batch.reset(obs, poses, colliding, crossings, mask=np.array([False, True, False]))
    assert list(small_batch.steps()) == [5, 0, 5]
    with pytest.raises(InvalidArgumentError, match="mask"):
        small_batch.reset(obs, poses, colliding, crossings, mask=np.array([True, False]))
    with pytest.raises(InvalidArgumentError, match="mask"):
        small_batch.reset(obs, poses, colliding, crossings, mask=np.ones(3, np.int64))
    with pytest.raises(InvalidArgumentError, match="seeds"):
        small_batch.reset(obs, poses, colliding, crossings, seeds=np.ones(3, np.int64))
    with pytest.raises(InvalidArgumentError, match="index"):
        small_batch.set_world(3, mazesim.load_world("arena"), 0)


def test_construction_errors() -> None:
    world = mazesim.load_world("arena")
    with pytest.raises(InvalidArgumentError, match="num_envs"):
        BatchSimulator(world)
    with pytest.raises(InvalidArgumentError, match="seeds"):
        BatchSimulator(world, num_envs=2, seeds=[1])
    with pytest.raises(mazesim.UnknownNameError):
        BatchSimulator(world, num_envs=2, robot="nope")


def test_generator_is_seeded_and_mazes_are_solvable() -> None:
    a = mazesim.generate_maze(6, 4, seed=9, loops=0.2)
    assert a == mazesim.generate_maze(6, 4, seed=9, loops=0.2)
    assert a != mazesim.generate_maze(6, 4, seed=10, loops=0.2)
    maze = a.cell_maze()
    assert maze is not None and maze["rows"] == 4 and maze["cols"] == 6
    assert a.goal is not None
    with pytest.raises(InvalidArgumentError):
        mazesim.generate_maze(1, 5)


def test_start_poses_encoders_and_ground_readings() -> None:
    batch = BatchSimulator(mazesim.load_world("arena"), num_envs=2, noise=False)
    batch.set_starts(np.array([[0.1, 0.1, 0.5], [0.2, -0.1, 1.0]]))
    obs, poses, colliding, crossings = buffers(batch)
    batch.reset(obs, poses, colliding, crossings)
    assert np.allclose(poses, [[0.1, 0.1, 0.5], [0.2, -0.1, 1.0]])
    batch.step(np.array([[1, 2], [3, 4]], np.float32), obs, poses, colliding, crossings)
    lone = Simulator(mazesim.load_world("arena"), noise=False)
    lone.set_start(0.2, -0.1, 1.0)
    lone.reset()
    lone.step(3.0, 4.0)
    assert np.array_equal(batch.encoders()[1], lone.encoders)
    assert np.array_equal(poses[1], np.float32(lone.pose))
    with pytest.raises(InvalidArgumentError, match="finite"):
        batch.set_starts(np.array([[0.0, 0.0, np.nan], [0.0, 0.0, 0.0]]))
    profile = mazesim.RobotProfile.builtin("e-puck")
    assert profile.ground_reading(1, 1.0) == pytest.approx(855.625)
    assert profile.ground_reading(1, 0.2) == pytest.approx(300.0)
    with pytest.raises(InvalidArgumentError):
        profile.ground_reading(3, 0.5)
