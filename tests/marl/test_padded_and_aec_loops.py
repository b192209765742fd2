"""Multi-agent loops an RL researcher writes around the ParallelEnv and the AEC env (#38): a
fixed-size batch padded by hand for the robots that ended, the AEC loop that steps ended agents
with None, and the AEC form's summed rewards equal to the parallel env's."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

pytest.importorskip("pettingzoo", reason="needs mazesim[marl] (make marl-deps)")

from mazesim.marl import aggregation_v0, maze_goals_v0  # noqa: E402

MODULES: dict[str, Any] = {"maze_goals_v0": maze_goals_v0, "aggregation_v0": aggregation_v0}


@pytest.mark.parametrize("name", MODULES)
def test_a_batch_padded_by_hand_keeps_each_live_robots_row(name: str) -> None:
    env = MODULES[name].parallel_env(num_robots=3, max_cycles=60)
    agents = env.possible_agents
    space = env.observation_space(agents[0])
    assert all(env.observation_space(a) == space for a in agents)
    assert all(env.action_space(a) == env.action_space(agents[0]) for a in agents)
    observations, _ = env.reset(seed=5)
    rng = np.random.default_rng(5)
    while env.agents:
        padded = np.zeros((len(agents), *space.shape), dtype=space.dtype)
        for i, agent in enumerate(agents):
            if agent in observations:
                padded[i] = observations[agent]
                assert space.contains(padded[i])
        assert padded.dtype == space.dtype
        actions = {a: rng.uniform(-1, 1, 2).astype(np.float32) for a in env.agents}
        observations, *_ = env.step(actions)


@pytest.mark.parametrize("name", MODULES)
def test_the_aec_loop_steps_ended_agents_with_none_to_the_end(name: str) -> None:
    env = MODULES[name].env(num_robots=3, max_cycles=40)
    env.reset(seed=2)
    ended: set[str] = set()
    steps = 0
    for agent in env.agent_iter(max_iter=1000):
        observation, _, termination, truncation, _ = env.last()
        if termination or truncation:
            ended.add(agent)
            env.step(None)
        else:
            assert env.observation_space(agent).contains(observation)
            env.step(env.action_space(agent).sample())
        steps += 1
    assert ended == set(env.possible_agents) and not env.agents
    assert steps < 1000


def test_the_aec_forms_summed_rewards_equal_the_parallel_envs() -> None:
    action = np.array([0.9, 0.6], np.float32)
    parallel = maze_goals_v0.parallel_env(num_robots=2, max_cycles=25)
    parallel.reset(seed=8)
    totals = dict.fromkeys(parallel.possible_agents, 0.0)
    while parallel.agents:
        rewards = parallel.step(dict.fromkeys(parallel.agents, action))[1]
        for agent, reward in rewards.items():
            totals[agent] += reward
    aec = maze_goals_v0.env(num_robots=2, max_cycles=25)
    aec.reset(seed=8)
    summed = dict.fromkeys(aec.possible_agents, 0.0)
    for agent in aec.agent_iter():
        _, reward, termination, truncation, _ = aec.last()
        summed[agent] += reward
        aec.step(None if termination or truncation else action)
    assert summed == pytest.approx(totals)
    assert any(total != 0.0 for total in totals.values())
