"""What a MARL researcher checks beside PettingZoo's own tests: every observation and the global
state stay in their spaces over long random rollouts with resets, the spaces are one object per
agent, and PettingZoo's conversions between the parallel and AEC forms pass its API test."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

pytest.importorskip("pettingzoo", reason="needs mazesim[marl] (make marl-deps)")

from pettingzoo.test import parallel_api_test  # noqa: E402
from pettingzoo.utils.conversions import aec_to_parallel, parallel_to_aec  # noqa: E402

from mazesim.marl import aggregation_v0, maze_goals_v0  # noqa: E402

MODULES: dict[str, Any] = {"maze_goals_v0": maze_goals_v0, "aggregation_v0": aggregation_v0}


@pytest.mark.parametrize("name", MODULES)
def test_observations_and_state_stay_in_their_spaces_over_a_long_rollout(name: str) -> None:
    env = MODULES[name].parallel_env(max_cycles=40)
    env.reset(seed=0)
    for agent in env.possible_agents:
        assert env.observation_space(agent) is env.observation_space(agent)
        assert env.action_space(agent) is env.action_space(agent)
    rng = np.random.default_rng(0)
    episodes = 0
    for _ in range(200):
        if not env.agents:
            env.reset()
            episodes += 1
        actions = {agent: rng.uniform(-1, 1, 2).astype(np.float32) for agent in env.agents}
        observations, rewards, _, _, _ = env.step(actions)
        for agent, observation in observations.items():
            assert env.observation_space(agent).contains(observation), agent
            assert np.isfinite(rewards[agent])
        assert env.state_space.contains(env.state())
    assert episodes >= 4


@pytest.mark.parametrize("name", MODULES)
def test_pettingzoos_conversions_pass_its_parallel_api_test(name: str) -> None:
    module = MODULES[name]
    parallel_api_test(aec_to_parallel(module.env(max_cycles=30)), num_cycles=70)
    parallel_api_test(aec_to_parallel(parallel_to_aec(module.parallel_env(max_cycles=30))))
