"""More of what an RL researcher tries on mazesim's gymnasium envs before trusting them (#38):
gymnasium's observation, reward and time wrappers, the native vector env's seeds lists, partial
resets, autoreset modes and rendering, keywords overriding the registered ones, envs built in
spawned processes, and every registered id's observations inside the declared space."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")
from gymnasium.vector import AutoresetMode  # noqa: E402

import mazesim  # noqa: E402,F401
from mazesim.envs.tasks import task_ids  # noqa: E402
from mazesim.errors import MazesimError  # noqa: E402

IDS = task_ids()
SHORT = {"max_episode_steps": 6}


def _same(first: Any, second: Any) -> None:
    """Equal arrays, or equal dicts of arrays key by key."""
    if isinstance(first, dict):
        assert set(first) == set(second)
        for key in first:
            np.testing.assert_array_equal(np.asarray(first[key]), np.asarray(second[key]), key)
    else:
        np.testing.assert_array_equal(np.asarray(first), np.asarray(second))


def _rollout(env: Any, steps: int, seed: int = 3) -> tuple[list[Any], list[float]]:
    """Observations and rewards of ``steps`` steps of one fixed action after a seeded reset."""
    observations = [env.reset(seed=seed)[0]]
    rewards = []
    action = np.full(env.action_space.shape, 0.5, dtype=env.action_space.dtype)
    for _ in range(steps):
        observation, reward, terminated, truncated, _ = env.step(action)
        observations.append(observation)
        rewards.append(float(reward))
        if terminated or truncated:
            observations.append(env.reset()[0])
    return observations, rewards


def test_time_aware_observation_counts_the_steps_of_a_box_task() -> None:
    env = gymnasium.wrappers.TimeAwareObservation(
        gymnasium.make("mazesim/MazeFixed-v1", **SHORT), flatten=True, normalize_time=False
    )
    observation = env.reset(seed=0)[0]
    assert env.observation_space.contains(observation) and observation[-1] == 0
    for step in range(1, 6):
        observation = env.step(env.action_space.sample())[0]
        assert env.observation_space.contains(observation) and observation[-1] == step


def test_time_aware_observation_adds_a_time_key_to_a_goal_task() -> None:
    env = gymnasium.wrappers.TimeAwareObservation(
        gymnasium.make("mazesim/EPuckGoal-v0", **SHORT), flatten=False
    )
    observation = env.reset(seed=0)[0]
    assert {"observation", "achieved_goal", "desired_goal", "time"} <= set(observation)
    assert env.observation_space.contains(env.step(env.action_space.sample())[0])


def test_transform_reward_scales_every_reward_of_the_same_episode() -> None:
    plain = _rollout(gymnasium.make("mazesim/MazeFixed-v1", **SHORT), 14)
    scaled = _rollout(
        gymnasium.wrappers.TransformReward(
            gymnasium.make("mazesim/MazeFixed-v1", **SHORT), lambda r: 2.0 * r
        ),
        14,
    )
    for one, two in zip(plain[0], scaled[0]):
        _same(one, two)
    assert scaled[1] == pytest.approx([2.0 * r for r in plain[1]])
    assert any(r != 0.0 for r in plain[1])


def test_transform_observation_with_its_own_space_stays_in_it() -> None:
    inner = gymnasium.make("mazesim/UnseenMaze-v2", **SHORT)
    space = gymnasium.spaces.Box(-1.0, 1.0, inner.observation_space.shape, np.float32)
    env = gymnasium.wrappers.TransformObservation(
        inner, lambda o: np.clip(o, -1.0, 1.0).astype(np.float32), space
    )
    env.reset(seed=2)
    env.action_space.seed(2)
    for _ in range(30):
        observation, _, terminated, truncated, _ = env.step(env.action_space.sample())
        assert space.contains(observation)
        if terminated or truncated:
            env.reset()


def test_episode_statistics_of_a_time_limited_env_report_the_limit() -> None:
    env = gymnasium.wrappers.RecordEpisodeStatistics(
        gymnasium.make("mazesim/MazeFixed-v1", **SHORT)
    )
    env.reset(seed=0)
    total = 0.0
    for _ in range(6):
        _, reward, terminated, truncated, info = env.step(np.zeros(2, np.float32))
        total += float(reward)
    assert truncated and not terminated
    assert info["episode"]["l"] == 6 and info["episode"]["r"] == pytest.approx(total)


def test_vector_episode_statistics_sum_each_envs_rewards() -> None:
    envs = gymnasium.wrappers.vector.RecordEpisodeStatistics(
        gymnasium.make_vec("mazesim/MazeRandomGoal-v1", num_envs=3, **SHORT)
    )
    envs.reset(seed=5)
    envs.action_space.seed(5)
    sums = np.zeros(3)
    reported = 0
    for _ in range(13):
        _, rewards, terminated, truncated, info = envs.step(envs.action_space.sample())
        sums += rewards
        if "episode" in info:
            done = info["_episode"]
            np.testing.assert_allclose(info["episode"]["r"][done], sums[done], rtol=1e-5)
            assert (info["episode"]["l"][done] == 6).all()
            reported += int(done.sum())
            sums[done] = 0.0
    assert reported == 6


def test_vector_transform_reward_on_the_native_vector_env() -> None:
    options = {"num_envs": 2, **SHORT}
    plain = gymnasium.make_vec("mazesim/MazeFixed-v1", **options)
    halved = gymnasium.wrappers.vector.TransformReward(
        gymnasium.make_vec("mazesim/MazeFixed-v1", **options), lambda r: r / 2
    )
    plain.reset(seed=1)
    halved.reset(seed=1)
    actions = np.full((2, 2), 0.7, np.float32)
    for _ in range(8):
        np.testing.assert_allclose(halved.step(actions)[1], plain.step(actions)[1] / 2)


def test_frozen_observation_normalisation_stops_updating_its_statistics() -> None:
    envs = gymnasium.wrappers.vector.NormalizeObservation(
        gymnasium.make_vec("mazesim/UnseenMaze-v2", num_envs=2, **SHORT)
    )
    envs.reset(seed=0)
    for _ in range(5):
        envs.step(envs.action_space.sample())
    envs.update_running_mean = False
    mean = envs.obs_rms.mean.copy()
    for _ in range(5):
        assert np.isfinite(envs.step(envs.action_space.sample())[0]).all()
    np.testing.assert_array_equal(envs.obs_rms.mean, mean)


def test_dict_info_to_list_gives_one_info_per_env() -> None:
    envs = gymnasium.wrappers.vector.DictInfoToList(
        gymnasium.make_vec("mazesim/MazeFixed-v1", num_envs=3, **SHORT)
    )
    infos = envs.reset(seed=0)[1]
    assert isinstance(infos, list) and len(infos) == 3
    infos = envs.step(envs.action_space.sample())[4]
    assert len(infos) == 3 and all(set(one) == set(infos[0]) for one in infos)


@pytest.mark.parametrize("env_id", ["mazesim/MazeRandomGoal-v1", "mazesim/UnseenMazeGoal-v0"])
def test_a_list_of_seeds_gives_the_sync_vector_envs_resets(env_id: str) -> None:
    native = gymnasium.make_vec(env_id, num_envs=3, **SHORT)
    sync = gymnasium.make_vec(env_id, num_envs=3, vectorization_mode="sync", **SHORT)
    seeds = [9, 2, 40]
    _same(native.reset(seed=seeds)[0], sync.reset(seed=seeds)[0])


def test_an_int_seed_is_the_list_of_consecutive_seeds() -> None:
    envs = gymnasium.make_vec("mazesim/UnseenMaze-v2", num_envs=3, **SHORT)
    _same(envs.reset(seed=7)[0], envs.reset(seed=[7, 8, 9])[0])


def test_a_none_in_the_seeds_list_leaves_that_env_drawing_on() -> None:
    envs = gymnasium.make_vec("mazesim/UnseenMaze-v2", num_envs=2, **SHORT)
    first = envs.reset(seed=[3, 4])[0]
    again = envs.reset(seed=[3, None])[0]
    np.testing.assert_array_equal(first[0], again[0])
    assert np.isfinite(again[1]).all()


@pytest.mark.parametrize("seed", [[1, 2], [1, 2, 3, 4], [1, -2, 3], "7"])
def test_seeds_that_do_not_fit_are_refused_clearly(seed: Any) -> None:
    envs = gymnasium.make_vec("mazesim/MazeFixed-v1", num_envs=3, **SHORT)
    with pytest.raises(MazesimError, match="expected.*seed|seed.*expected.*found"):
        envs.reset(seed=seed)


def test_a_masked_reset_with_next_step_autoreset_leaves_the_others_alone() -> None:
    envs = gymnasium.make_vec("mazesim/UnseenMaze-v2", num_envs=3, max_episode_steps=50)
    start = envs.reset(seed=0)[0]
    moved = envs.step(np.full((3, 2), 3.0, np.float32))[0]
    mask = np.array([True, False, True])
    after = envs.reset(options={"reset_mask": mask})[0]
    np.testing.assert_array_equal(after[1], moved[1])
    assert not np.array_equal(after[0], moved[0]) or not np.array_equal(start[0], moved[0])


@pytest.mark.parametrize("mask", [np.array([True, False]), [True, False, True], np.ones(3)])
def test_a_reset_mask_that_does_not_fit_is_refused_clearly(mask: Any) -> None:
    envs = gymnasium.make_vec("mazesim/MazeFixed-v1", num_envs=3, **SHORT)
    envs.reset(seed=0)
    with pytest.raises(MazesimError, match="reset_mask"):
        envs.reset(options={"reset_mask": mask})


def test_next_step_autoreset_starts_the_next_episode_with_a_step_of_no_reward() -> None:
    native = gymnasium.make_vec("mazesim/UnseenMaze-v2", num_envs=2, **SHORT)
    sync = gymnasium.make_vec("mazesim/UnseenMaze-v2", 2, vectorization_mode="sync", **SHORT)
    _same(native.reset(seed=0)[0], sync.reset(seed=0)[0])
    actions = np.full((2, 2), 0.4, np.float32)
    for _ in range(6):
        native.step(actions)
        truncated = sync.step(actions)[3]
    assert truncated.all()
    observations, rewards, terminated, truncated, _ = native.step(actions)
    assert (rewards == 0).all() and not (terminated | truncated).any()
    _same(observations, sync.step(actions)[0])
    assert native.observation_space.contains(observations)


def test_same_step_autoreset_hands_the_final_observation_in_the_infos() -> None:
    """The final observation SAME_STEP puts in the infos is the one NEXT_STEP returns."""
    same = gymnasium.make_vec(
        "mazesim/MazeFixed-v1", num_envs=2, autoreset_mode=AutoresetMode.SAME_STEP, **SHORT
    )
    following = gymnasium.make_vec("mazesim/MazeFixed-v1", num_envs=2, **SHORT)
    same.reset(seed=0)
    following.reset(seed=0)
    actions = np.full((2, 2), 0.6, np.float32)
    for _ in range(6):
        observations, _, _, truncated, info = same.step(actions)
        last = following.step(actions)[0]
    assert truncated.all() and info["_final_obs"].all()
    _same(np.stack(info["final_obs"]), last)
    assert same.observation_space.contains(observations)
    assert not np.array_equal(observations, last)


def test_a_vector_envs_frames_are_one_per_env() -> None:
    envs = gymnasium.make_vec("mazesim/MazeFixed-v1", num_envs=3, render_mode="rgb_array")
    envs.reset(seed=0)
    frames = envs.render()
    assert len(frames) == 3
    assert all(f.dtype == np.uint8 and f.ndim == 3 and f.shape == frames[0].shape for f in frames)


def test_keywords_at_make_override_the_registered_ones() -> None:
    spec = gymnasium.spec("mazesim/MazeFixed-v1")
    env = gymnasium.make("mazesim/MazeFixed-v1", max_episode_steps=3, action_mode="discrete")
    assert env.spec.max_episode_steps == 3 and env.spec.kwargs["action_mode"] == "discrete"
    assert spec.kwargs.get("action_mode") != "discrete"
    assert isinstance(env.action_space, gymnasium.spaces.Discrete)
    env.reset(seed=0)
    assert not env.step(0)[3] and not env.step(0)[3] and env.step(0)[3]


def _spawned_first_observation(env_id: str) -> Any:
    env = gymnasium.make(env_id)
    return env.reset(seed=11)[0]


def test_envs_built_in_spawned_processes_match_the_ones_built_here() -> None:
    import multiprocessing

    with multiprocessing.get_context("spawn").Pool(1) as pool:
        there = pool.map(
            _spawned_first_observation, ["mazesim/UnseenMaze-v2", "mazesim/EPuckGoal-v0"]
        )
    _same(there[0], _spawned_first_observation("mazesim/UnseenMaze-v2"))
    _same(there[1], _spawned_first_observation("mazesim/EPuckGoal-v0"))


@pytest.mark.parametrize("env_id", IDS)
def test_every_ids_vector_observations_keep_the_declared_dtype_and_bounds(env_id: str) -> None:
    envs = gymnasium.make_vec(env_id, num_envs=2, max_episode_steps=25)
    space = envs.observation_space
    observations = envs.reset(seed=8)[0]
    envs.action_space.seed(8)
    for _ in range(120):
        assert space.contains(observations), env_id
        observations, rewards, terminated, truncated, _ = envs.step(envs.action_space.sample())
        assert rewards.dtype == np.float64 and np.isfinite(rewards).all()
        assert terminated.dtype == np.bool_ and truncated.dtype == np.bool_
    assert space.contains(observations)
