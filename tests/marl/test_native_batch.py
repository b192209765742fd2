"""The native batch equals N PettingZoo envs stepped one by one, bit for bit, whatever its thread
count; the same seed gives the same run."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

pytest.importorskip("pettingzoo", reason="needs mazesim[marl] (make marl-deps)")

import mazesim  # noqa: E402
from mazesim.errors import InvalidArgumentError  # noqa: E402
from mazesim.marl import aggregation_v0, maze_goals_v0  # noqa: E402
from mazesim.marl.batch import MultiRobotBatch  # noqa: E402

TASKS: dict[str, tuple[Any, dict[str, Any]]] = {
    "maze_goals_v0": (maze_goals_v0, {"num_robots": 3, "maze_size": (3, 3), "max_cycles": 25}),
    "aggregation_v0": (aggregation_v0, {"num_robots": 4, "max_cycles": 25}),
    # One robot alone, the task's single-agent case (#33): the batch of one-robot worlds.
    "maze_goals_v0, one robot": (maze_goals_v0, {"num_robots": 1, "max_cycles": 25}),
}
STEPS = 60  # over two episodes of every env: the autoreset is covered


def random_actions(seed: int, n: int, r: int) -> np.ndarray:
    """STEPS steps of (n, r, 2) actions, forward-leaning so that robots meet walls and others."""
    rng = np.random.default_rng(seed)
    return rng.uniform(-0.5, 1.0, size=(STEPS, n, r, 2)).astype(np.float32)


def batch_run(batch: MultiRobotBatch, seed: int, actions: np.ndarray) -> list[tuple]:
    outputs = [(batch.reset(seed)[0].copy(),)]
    for step in actions:
        observations, rewards, terminations, truncations, _ = batch.step(step)
        outputs.append((observations.copy(), rewards, terminations, truncations))
    return outputs


@pytest.mark.parametrize("name", TASKS)
def test_batch_equals_parallel_envs_stepped_one_by_one(name: str) -> None:
    module, options = TASKS[name]
    n, seed = 3, 40
    batch = module.batch_env(n, threads=2, **options)
    r = batch.num_robots
    actions = random_actions(1, n, r)
    outputs = batch_run(batch, seed, actions)
    resets = 0
    for i in range(n):
        env = module.parallel_env(**options)
        observations, _ = env.reset(seed=seed + i)
        for k, agent in enumerate(env.possible_agents):
            assert np.array_equal(observations[agent], outputs[0][0][i, k])
        for t, step in enumerate(actions):
            if not env.agents:  # the batch restarted this env at the end of the last step
                observations, _ = env.reset()
                resets += 1
                for k, agent in enumerate(env.possible_agents):
                    assert np.array_equal(observations[agent], outputs[t][0][i, k])
            acting = {a: step[i, k] for k, a in enumerate(env.possible_agents) if a in env.agents}
            observations, rewards, terminations, truncations, _ = env.step(acting)
            batch_obs, batch_rewards, batch_terms, batch_truncs = outputs[t + 1]
            for k, agent in enumerate(env.possible_agents):
                if agent not in observations:
                    continue
                assert rewards[agent] == batch_rewards[i, k]
                assert terminations[agent] == batch_terms[i, k]
                assert truncations[agent] == batch_truncs[i, k]
                if env.agents:  # else the batch's row is already the next episode's
                    assert np.array_equal(observations[agent], batch_obs[i, k])
    assert resets >= n  # every env ran into its second episode


@pytest.mark.parametrize("name", TASKS)
def test_same_seed_same_run_whatever_the_thread_count(name: str) -> None:
    module, options = TASKS[name]
    probe = module.batch_env(4, threads=1, **options)
    actions = random_actions(2, 4, probe.num_robots)
    one = batch_run(probe, 9, actions)
    two = batch_run(module.batch_env(4, threads=2, **options), 9, actions)
    other = batch_run(module.batch_env(4, threads=1, **options), 10, actions)
    for a, b in zip(one, two):
        for x, y in zip(a, b):
            assert np.array_equal(x, y)
    assert not np.array_equal(one[-1][0], other[-1][0])


def test_set_world_puts_an_env_of_several_robots_into_a_new_world() -> None:
    task = maze_goals_v0.task(num_robots=2, maze_size=(3, 3))
    fresh = task.draw(np.random.default_rng(5))
    batch = MultiRobotBatch(task, 2, threads=1)
    batch.reset(0)
    assert batch.simulator is not None
    batch.simulator.set_world(1, fresh.world, fresh.seed)
    readings = np.zeros((2, 2, batch.simulator.observation_width), np.float32)
    poses = np.zeros((2, 2, 3), np.float32)
    colliding, crossings = np.zeros((2, 2), bool), np.zeros((2, 2), np.int32)
    batch.simulator.observe(readings, poses, colliding, crossings)
    starts = np.array([robot["start"] for robot in fresh.world.robots], np.float32)
    assert np.allclose(poses[1], starts, atol=1e-6)
    assert not np.allclose(poses[0], poses[1])


def test_set_world_refuses_a_world_of_another_number_of_robots() -> None:
    two = maze_goals_v0.task(num_robots=2, maze_size=(3, 3))
    three = maze_goals_v0.task(num_robots=3, maze_size=(3, 3))
    batch = MultiRobotBatch(two, 2, threads=1)
    batch.reset(0)
    assert batch.simulator is not None
    with pytest.raises(InvalidArgumentError, match="expected a world placing 2 robots"):
        batch.simulator.set_world(0, three.draw(np.random.default_rng(1)).world, 3)
    single = mazesim.BatchSimulator(mazesim.World.builtin("arena"), num_envs=2)
    with pytest.raises(InvalidArgumentError, match="expected a world placing 1 robots"):
        single.set_world(1, two.draw(np.random.default_rng(1)).world, 3)
    with pytest.raises(InvalidArgumentError, match="expected num_envs from 1 to"):
        MultiRobotBatch(two, 0)
