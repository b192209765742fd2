"""Stable-Baselines3's checker on the discrete action mode of every task, and short learning runs
of the algorithms the action and observation spaces call for (DQN on the discrete actions, PPO's
MultiInputPolicy on a goal task's Dict): each learns and predicts valid actions."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")
pytest.importorskip(
    "stable_baselines3", reason="needs the optional extra mazesim[sb3] (make sb3-deps)"
)

from stable_baselines3 import DQN, PPO  # noqa: E402
from stable_baselines3.common.env_checker import check_env  # noqa: E402

import mazesim  # noqa: E402,F401
from mazesim.envs.tasks import GOAL_TASKS, task_ids  # noqa: E402

GOAL_IDS = {task.env_id for task in GOAL_TASKS}


@pytest.mark.parametrize("env_id", task_ids())
def test_sb3s_checker_passes_with_discrete_actions(env_id: str) -> None:
    env = gymnasium.make(env_id, action_mode="discrete", max_episode_steps=50)
    # SB3's goal-env check calls compute_reward on the env it is given: a goal task unwrapped.
    checked = env.unwrapped if env_id in GOAL_IDS else env
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(checked, warn=True)


def test_dqn_learns_on_the_discrete_actions_and_predicts_one_of_them() -> None:
    env = gymnasium.make("mazesim/MazeFixed-v1", action_mode="discrete", max_episode_steps=50)
    model = DQN(
        "MlpPolicy",
        env,
        learning_starts=40,
        buffer_size=500,
        policy_kwargs={"net_arch": [16]},
        seed=0,
        device="cpu",
    )
    before = [p.detach().clone() for p in model.q_net.parameters()]
    model.learn(100)
    after = list(model.q_net.parameters())
    assert any(not bool((a == b).all()) for a, b in zip(after, before))
    action, _ = model.predict(env.reset(seed=0)[0], deterministic=True)
    assert env.action_space.contains(int(action))


def test_ppo_multi_input_policy_learns_on_a_goal_tasks_dict() -> None:
    env = gymnasium.make("mazesim/EPuckGoalDense-v0", max_episode_steps=50)
    model = PPO(
        "MultiInputPolicy",
        env,
        n_steps=64,
        batch_size=32,
        n_epochs=1,
        policy_kwargs={"net_arch": [16]},
        seed=0,
        device="cpu",
    )
    model.learn(128)
    observation, _ = env.reset(seed=0)
    action, _ = model.predict(observation, deterministic=True)
    assert action.shape == (2,) and np.all(np.isfinite(action))
    env.step(action)  # the policy's action, clipped as the env documents
