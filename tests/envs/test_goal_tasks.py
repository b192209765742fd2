"""The goal-conditioned tasks: Gymnasium-Robotics' GoalEnv form, checked by gymnasium and SB3,
``compute_reward`` equal to the step reward (one pair and batches), SB3's HER accepting it, and
the native vector env equal to SyncVectorEnv."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

from gymnasium.utils.env_checker import check_env  # noqa: E402

from mazesim.envs.goal import MazeGoalEnv  # noqa: E402
from mazesim.envs.tasks import GOAL_TASKS  # noqa: E402
from mazesim.errors import InvalidArgumentError, UnknownNameError  # noqa: E402

IDS = [task.env_id for task in GOAL_TASKS]


@pytest.mark.parametrize("env_id", IDS)
def test_gymnasiums_checker_passes(env_id: str) -> None:
    env = gymnasium.make(env_id)
    check_env(env.unwrapped, skip_render_check=True)
    observation, _ = env.reset(seed=0)
    assert set(observation) == {"observation", "achieved_goal", "desired_goal"}
    assert env.observation_space.contains(observation)


@pytest.mark.parametrize("env_id", IDS)
def test_compute_reward_is_the_step_reward_single_and_batched(env_id: str) -> None:
    env = gymnasium.make(env_id, max_episode_steps=60)
    goal_env = env.unwrapped
    assert isinstance(goal_env, MazeGoalEnv)
    observation, _ = env.reset(seed=3)
    env.action_space.seed(3)
    achieved, desired, rewards, infos = [], [], [], []
    for _ in range(60):
        observation, reward, terminated, truncated, info = env.step(env.action_space.sample())
        one = goal_env.compute_reward(
            observation["achieved_goal"], observation["desired_goal"], info
        )
        assert one == reward and isinstance(reward, float)
        achieved.append(observation["achieved_goal"])
        desired.append(observation["desired_goal"])
        rewards.append(reward)
        infos.append(info)
        if terminated or truncated:
            break
    batch = goal_env.compute_reward(np.array(achieved), np.array(desired), np.array(infos))
    assert np.array_equal(batch, np.array(rewards))
    # HER's batches: (episodes, steps, 2), relabelled with other steps' achieved goals.
    grid = goal_env.compute_reward(
        np.array(achieved)[None].repeat(2, 0), np.array(achieved[::-1])[None].repeat(2, 0), None
    )
    assert grid.shape == (2, len(achieved))
    if "Dense" not in env_id:
        assert set(np.unique(grid)) <= {-1.0, 0.0} and grid[0, len(achieved) // 2] == 0.0


def test_compute_reward_is_the_step_reward_in_a_vector_env() -> None:
    envs = gymnasium.make_vec("mazesim/EPuckGoalDense-v0", 3, vectorization_mode="sync")
    goal_env = envs.envs[0].unwrapped
    observations, _ = envs.reset(seed=1)
    for _ in range(20):
        observations, rewards, _, _, infos = envs.step(envs.action_space.sample())
        again = goal_env.compute_reward(
            observations["achieved_goal"], observations["desired_goal"], infos
        )
        assert np.array_equal(again, rewards)


def test_the_sparse_reward_is_zero_only_at_the_goal() -> None:
    env = MazeGoalEnv(reward_type="sparse", world="seed-maze", start_goal="random")
    observation, _ = env.reset(seed=2)
    goal = observation["desired_goal"]
    assert env.compute_reward(goal, goal, {}) == 0.0
    assert env.compute_reward(goal + np.float32(1.0), goal, {}) == -1.0
    with pytest.raises(UnknownNameError, match="expected reward_type to be one of sparse, dense"):
        MazeGoalEnv(reward_type="shaped")


def test_sb3s_checker_and_her_accept_every_goal_task() -> None:
    pytest.importorskip(
        "stable_baselines3", reason="needs the optional extra mazesim[sb3] (make sb3-deps)"
    )
    from stable_baselines3 import SAC, HerReplayBuffer
    from stable_baselines3.common.env_checker import check_env as sb3_check_env

    for env_id in IDS:
        sb3_check_env(gymnasium.make(env_id).unwrapped, warn=True)
    env = gymnasium.make("mazesim/EPuckGoal-v0", max_episode_steps=50)
    model = SAC(
        "MultiInputPolicy",
        env,
        replay_buffer_class=HerReplayBuffer,
        replay_buffer_kwargs={"n_sampled_goal": 4, "goal_selection_strategy": "future"},
        learning_starts=150,
        batch_size=32,
        policy_kwargs={"net_arch": [32, 32]},
        seed=0,
        device="cpu",
    )
    model.learn(total_timesteps=200)
    buffer = model.replay_buffer
    assert isinstance(buffer, HerReplayBuffer) and buffer.size() == 200
    sample = buffer.sample(64)
    recomputed = env.unwrapped.compute_reward(
        sample.next_observations["achieved_goal"].numpy(),
        sample.observations["desired_goal"].numpy(),
        None,
    )
    assert np.allclose(sample.rewards.numpy().ravel(), recomputed)


@pytest.mark.parametrize(
    ("achieved", "desired", "found"),
    [
        (np.zeros(7), np.zeros(2), r"shape \(7,\)"),
        (np.zeros((4, 2)), np.zeros((4, 3)), r"shape \(4, 3\)"),
        (5.0, np.zeros(2), r"shape \(\)"),
        (np.array([np.nan, 0.0]), np.zeros(2), "NaN or infinity"),
        (np.zeros((3, 2)), np.array([[0.0, np.inf]]), "NaN or infinity"),
    ],
)
def test_compute_reward_refuses_goals_that_are_not_finite_pairs(
    achieved: object, desired: object, found: str
) -> None:
    goal_env = gymnasium.make("mazesim/EPuckGoalDense-v0").unwrapped
    with pytest.raises(InvalidArgumentError, match=found):
        goal_env.compute_reward(achieved, desired, {})


def _same(mine: Any, theirs: Any) -> bool:
    """Whether two batched values (arrays, or dicts of them, as goal observations) are equal,
    dtypes included."""
    if isinstance(theirs, dict):
        return mine.keys() == theirs.keys() and all(_same(mine[k], theirs[k]) for k in theirs)
    mine, theirs = np.asarray(mine), np.asarray(theirs)
    if theirs.dtype == object:
        return len(mine) == len(theirs) and all(_same(a, b) for a, b in zip(mine, theirs))
    return mine.dtype == theirs.dtype and np.array_equal(mine, theirs)


@pytest.mark.parametrize("env_id", IDS)
@pytest.mark.parametrize("autoreset_mode", ["NextStep", "SameStep"])
def test_the_native_vector_env_equals_sync(env_id: str, autoreset_mode: str) -> None:
    num_envs = 3
    native = gymnasium.make_vec(
        env_id,
        num_envs,
        vectorization_mode="vector_entry_point",
        max_episode_steps=40,
        autoreset_mode=autoreset_mode,
    )
    sync = gymnasium.make_vec(
        env_id,
        num_envs,
        vectorization_mode="sync",
        max_episode_steps=40,
        vector_kwargs={"autoreset_mode": gymnasium.vector.AutoresetMode(autoreset_mode)},
    )
    assert type(native.unwrapped).__name__ == "MazeGoalVectorEnv"
    assert native.single_observation_space == sync.single_observation_space
    assert _same(native.reset(seed=5)[0], sync.reset(seed=5)[0])
    native.action_space.seed(5)
    ended = 0
    for step in range(130):  # the 40-step limit ends every episode at least three times
        actions = native.action_space.sample()
        mine, theirs = native.step(actions), sync.step(actions)
        for a, b in zip(mine[:4], theirs[:4]):
            assert _same(a, b), step
        assert mine[4].keys() == theirs[4].keys(), step
        assert all(_same(mine[4][k], theirs[4][k]) for k in theirs[4]), step
        ended += int((mine[2] | mine[3]).sum())
    assert ended >= num_envs * 3
    # A seeded reset starts the same episodes again; an unseeded one goes on with the stream.
    again = native.reset(seed=5)[0]
    assert _same(again, sync.reset(seed=5)[0])
    assert _same(native.reset()[0], sync.reset()[0])


def test_the_native_vector_env_refuses_what_the_goal_env_refuses() -> None:
    with pytest.raises(UnknownNameError, match="reward_type"):
        gymnasium.make_vec(
            "mazesim/EPuckGoal-v0", 2, vectorization_mode="vector_entry_point", reward_type="x"
        )
    with pytest.raises(InvalidArgumentError, match="a world with a goal"):
        gymnasium.make_vec(
            "mazesim/EPuckGoal-v0",
            2,
            vectorization_mode="vector_entry_point",
            world="arena",
            start_goal="world",
        )
