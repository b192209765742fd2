"""Stable-Baselines3 workflows an RL researcher runs past the first training (#38): a saved model
evaluating as the one saved, VecNormalize statistics saved and loaded, HER with DQN on discrete
actions over several envs of a goal task, the VecEnv's attribute methods and seeding, and
training that leaves no log folder."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")
pytest.importorskip(
    "stable_baselines3", reason="needs the optional extra mazesim[sb3] (make sb3-deps)"
)

from stable_baselines3 import DQN, PPO, HerReplayBuffer  # noqa: E402
from stable_baselines3.common.evaluation import evaluate_policy  # noqa: E402
from stable_baselines3.common.vec_env import VecNormalize  # noqa: E402

import mazesim  # noqa: E402,F401
from mazesim.errors import InvalidArgumentError  # noqa: E402
from mazesim.integrations.sb3 import make_vec_env  # noqa: E402

ENV_ID = "mazesim/MazeFixed-v1"
SHORT = {"max_episode_steps": 20}


def _trained_ppo(steps: int) -> PPO:
    """A small PPO trained ``steps`` steps on two envs of the fixed maze."""
    model = PPO(
        "MlpPolicy",
        make_vec_env(ENV_ID, 2, seed=0, **SHORT),
        n_steps=steps // 2,
        batch_size=32,
        seed=0,
        device="cpu",
    )
    return model.learn(steps)


def test_a_saved_and_loaded_model_evaluates_as_the_one_saved(tmp_path: Path) -> None:
    model = _trained_ppo(64)
    model.save(tmp_path / "ppo")
    loaded = PPO.load(tmp_path / "ppo", device="cpu")
    results = [
        evaluate_policy(
            m, make_vec_env(ENV_ID, 2, seed=3, **SHORT), n_eval_episodes=4, deterministic=True
        )
        for m in (model, loaded)
    ]
    assert results[0] == results[1]
    observations = make_vec_env(ENV_ID, 2, seed=9, **SHORT).reset()
    np.testing.assert_array_equal(
        model.predict(observations, deterministic=True)[0],
        loaded.predict(observations, deterministic=True)[0],
    )


def test_vec_normalize_statistics_saved_and_loaded_normalise_alike(tmp_path: Path) -> None:
    envs = VecNormalize(make_vec_env(ENV_ID, 3, seed=0, **SHORT))
    envs.reset()
    for _ in range(30):
        envs.step(np.stack([envs.action_space.sample() for _ in range(3)]))
    envs.save(str(tmp_path / "stats.pkl"))
    loaded = VecNormalize.load(
        str(tmp_path / "stats.pkl"), make_vec_env(ENV_ID, 3, seed=0, **SHORT)
    )
    raw = make_vec_env(ENV_ID, 3, seed=4, **SHORT).reset()
    np.testing.assert_allclose(loaded.normalize_obs(raw), envs.normalize_obs(raw))
    assert np.isfinite(loaded.normalize_obs(raw)).all()


def test_her_with_dqn_learns_a_goal_task_with_discrete_actions_over_two_envs() -> None:
    envs = make_vec_env(
        "mazesim/UnseenMazeGoal-v0", 2, seed=0, max_episode_steps=30, action_mode="discrete"
    )
    model = DQN(
        "MultiInputPolicy",
        envs,
        replay_buffer_class=HerReplayBuffer,
        replay_buffer_kwargs={"n_sampled_goal": 2, "goal_selection_strategy": "final"},
        learning_starts=80,
        batch_size=16,
        policy_kwargs={"net_arch": [16, 16]},
        seed=0,
        device="cpu",
    )
    model.learn(120)
    assert model.replay_buffer.size() * 2 == 120
    rewards = model.replay_buffer.sample(64).rewards.numpy().ravel()
    assert set(np.unique(rewards)) <= {-1.0, 0.0}
    actions = model.predict(envs.reset(), deterministic=True)[0]
    assert all(envs.action_space.contains(int(a)) for a in actions)


def test_the_vec_envs_attributes_reach_each_env_and_setting_one_is_refused() -> None:
    envs = make_vec_env(ENV_ID, 3, seed=0, **SHORT)
    assert len(envs.get_attr("spec")) == 3
    assert all(spec.id == ENV_ID for spec in envs.get_attr("spec"))
    assert [spec.max_episode_steps for spec in envs.get_attr("spec", indices=[1])] == [20]
    with pytest.raises(InvalidArgumentError, match="set_attr.*found 'max_episode_steps'"):
        envs.set_attr("max_episode_steps", 5, indices=[1])


def test_seeding_the_vec_env_repeats_its_resets() -> None:
    envs = make_vec_env("mazesim/UnseenMaze-v2", 3, **SHORT)
    envs.seed(21)
    first = envs.reset()
    envs.seed(21)
    np.testing.assert_array_equal(envs.reset(), first)
    envs.seed(22)
    assert not np.array_equal(envs.reset(), first)


def test_training_leaves_no_log_folder_in_the_temporary_directory() -> None:
    def folders() -> set[str]:
        return {n for n in os.listdir(tempfile.gettempdir()) if n.startswith("SB3-")}

    before = folders()
    _trained_ppo(32)
    assert folders() == before
