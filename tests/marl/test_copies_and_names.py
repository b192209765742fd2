"""What MARL users do with an env besides stepping it: pickle or deep-copy it mid-episode (to
ship it to a worker, to branch a rollout) and ask for an agent's space by name (#33)."""

from __future__ import annotations

import copy
import pickle
from typing import Any

import numpy as np
import pytest

pytest.importorskip("pettingzoo", reason="needs mazesim[marl] (make marl-deps)")

from mazesim.errors import UnknownNameError  # noqa: E402
from mazesim.marl import aggregation_v0, maze_goals_v0  # noqa: E402

COPIES = (lambda env: pickle.loads(pickle.dumps(env)), copy.deepcopy)


def _actions(env: Any, k: int) -> dict[str, Any]:
    return {
        agent: np.array([np.sin(k + i), np.cos(2 * k + i)], np.float32)
        for i, agent in enumerate(env.agents)
    }


@pytest.mark.parametrize("make_copy", COPIES, ids=["pickle", "deepcopy"])
@pytest.mark.parametrize("module", [maze_goals_v0, aggregation_v0], ids=["goals", "aggregation"])
def test_a_copy_of_a_parallel_env_steps_on_bit_for_bit(module: Any, make_copy: Any) -> None:
    """Copied after 5 steps of a rendered episode, the copy gives the original's next 20 steps'
    observations, rewards, flags and pictures, bit for bit, and its live agents."""
    env = module.parallel_env(num_robots=3, render_mode="rgb_array")
    env.reset(seed=11)
    for k in range(5):
        env.step(_actions(env, k))
    env.render()
    twin = make_copy(env)
    for k in range(5, 25):
        if not env.agents:
            break
        actions = _actions(env, k)
        mine, theirs = env.step(actions), twin.step(actions)
        for a, b in zip(mine, theirs):
            assert a.keys() == b.keys()
            for agent in a:
                assert np.array_equal(a[agent], b[agent]), (k, agent)
        assert env.agents == twin.agents
        assert np.array_equal(env.render(), twin.render())
        assert np.array_equal(env.state(), twin.state())


def test_a_pickled_aec_env_goes_on_from_the_same_agent() -> None:
    env = maze_goals_v0.env(num_robots=2)
    env.reset(seed=3)
    for k in range(3):
        env.step(np.array([0.5, 0.1 * k], np.float32))
    twin = pickle.loads(pickle.dumps(env))
    for k in range(6):
        assert twin.agent_selection == env.agent_selection
        for agent in env.possible_agents:
            assert np.array_equal(env.observe(agent), twin.observe(agent))
        action = np.array([0.3, -0.2 * k], np.float32)
        env.step(action)
        twin.step(action)
    assert env.rewards == twin.rewards


def test_a_pickled_native_batch_steps_on_as_the_original() -> None:
    """Every environment's engine state travels (one snapshot each), and its episode stream:
    the copy's next steps, autoresets included, are the original's."""
    batch = aggregation_v0.batch_env(4, threads=1, num_robots=2, max_cycles=6)
    batch.reset(seed=5)
    rng = np.random.default_rng(0)
    batch.step(rng.uniform(-1, 1, (4, 2, 2)).astype(np.float32))
    twin = pickle.loads(pickle.dumps(batch))
    for _ in range(10):
        actions = rng.uniform(-1, 1, (4, 2, 2)).astype(np.float32)
        mine, theirs = batch.step(actions), twin.step(actions)
        for a, b in zip(mine[:4], theirs[:4]):
            assert np.array_equal(a, b)
        assert np.array_equal(mine[4]["reset"], theirs[4]["reset"])


def test_a_copy_of_an_env_never_reset_is_one_too() -> None:
    twin = pickle.loads(pickle.dumps(maze_goals_v0.parallel_env(num_robots=2)))
    observations, _ = twin.reset(seed=1)
    reference, _ = maze_goals_v0.parallel_env(num_robots=2).reset(seed=1)
    assert all(np.array_equal(observations[a], reference[a]) for a in reference)


@pytest.mark.parametrize("make", [maze_goals_v0.parallel_env, maze_goals_v0.env])
@pytest.mark.parametrize("ask", ["observation_space", "action_space"])
def test_an_unknown_agent_names_the_agents_and_the_one_meant(make: Any, ask: str) -> None:
    env = make(num_robots=2)
    space = getattr(env, ask)
    assert space("epuck_1") is space("epuck_1")
    with pytest.raises(UnknownNameError) as raised:
        space("epuk_1")
    assert str(raised.value) == (
        "expected one of the agents ['epuck_0', 'epuck_1'], found 'epuk_1'; did you mean 'epuck_1'?"
    )
    assert isinstance(raised.value, LookupError)
