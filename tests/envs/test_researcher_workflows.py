"""What an RL researcher does with a gymnasium env first, on mazesim's tasks: gymnasium's checkers
on other option combinations, its wrappers, its vectorization modes, seeding, rendering, closing,
spaces over long rollouts with autoreset, info keys, specs and copies."""

from __future__ import annotations

import copy
import pickle
import warnings
from pathlib import Path
from typing import Any

import pytest

gymnasium = pytest.importorskip("gymnasium")
import numpy as np  # noqa: E402
from gymnasium.utils.env_checker import check_env  # noqa: E402
from gymnasium.vector import AutoresetMode  # noqa: E402

import mazesim  # noqa: E402,F401
from mazesim.envs.tasks import task_ids  # noqa: E402

IDS = task_ids()


def _assert_same(first: Any, second: Any) -> None:
    """Equal observations, rewards or flags, dicts of arrays compared key by key."""
    if isinstance(first, dict):
        assert set(first) == set(second)
        for key in first:
            np.testing.assert_array_equal(np.asarray(first[key]), np.asarray(second[key]), key)
    else:
        np.testing.assert_array_equal(first, second)


@pytest.mark.parametrize("env_id", IDS)
def test_gymnasiums_checker_passes_with_discrete_actions(env_id: str) -> None:
    env = gymnasium.make(env_id, action_mode="discrete").unwrapped
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env, skip_render_check=True)


@pytest.mark.parametrize("robot", ["seed", "alphabot2"])
@pytest.mark.parametrize("env_id", ["mazesim/MazeFixed-v1", "mazesim/UnseenMaze-v2"])
def test_gymnasiums_checker_passes_with_other_robots(env_id: str, robot: str) -> None:
    env = gymnasium.make(env_id, robot=robot).unwrapped
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env, skip_render_check=True)


def test_the_passive_checker_warns_of_nothing_while_rendering_every_task() -> None:
    for env_id in IDS:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            env = gymnasium.make(env_id, render_mode="rgb_array", disable_env_checker=False)
            env.reset(seed=1)
            env.step(env.action_space.sample())
            frame = env.render()
            assert frame.dtype == np.uint8 and frame.ndim == 3 and frame.shape[2] == 3
            env.close()


@pytest.mark.parametrize("env_id", ["mazesim/MazeRandomGoal-v1", "mazesim/EPuckGoal-v0"])
def test_async_vector_env_equals_the_native_one(env_id: str) -> None:
    native = gymnasium.make_vec(env_id, num_envs=3, max_episode_steps=100)
    processes = gymnasium.make_vec(
        env_id, num_envs=3, vectorization_mode="async", max_episode_steps=100
    )
    _assert_same(processes.reset(seed=5)[0], native.reset(seed=5)[0])
    rng = np.random.default_rng(0)
    for _ in range(150):  # past the time limit: NEXT_STEP autoreset in both
        actions = rng.uniform(-1, 1, (3, 2)).astype(np.float32)
        for first, second in zip(processes.step(actions)[:4], native.step(actions)[:4]):
            _assert_same(first, second)
    processes.close()
    native.close()


def test_async_mode_takes_same_step_autoreset_in_vector_kwargs() -> None:
    same_step = {"autoreset_mode": AutoresetMode.SAME_STEP}
    processes = gymnasium.make_vec(
        "mazesim/MazeFixed-v1",
        num_envs=2,
        vectorization_mode="async",
        vector_kwargs=same_step,
        max_episode_steps=5,
    )
    # The native vector env takes its own keywords directly (docs/rl.md).
    native = gymnasium.make_vec(
        "mazesim/MazeFixed-v1", num_envs=2, max_episode_steps=5, **same_step
    )
    assert processes.metadata["autoreset_mode"] == native.metadata["autoreset_mode"]
    processes.reset(seed=0)
    native.reset(seed=0)
    actions = np.full((2, 2), 0.5, dtype=np.float32)
    for step in range(1, 13):
        first, second = processes.step(actions), native.step(actions)
        _assert_same(first[0], second[0])
        _assert_same(first[3], second[3])
        assert bool(second[3].all()) == (step % 5 == 0)
    processes.close()
    native.close()


def test_record_video_writes_an_episode(tmp_path: Path) -> None:
    env = gymnasium.make("mazesim/MazeFixed-v1", render_mode="rgb_array", max_episode_steps=10)
    env = gymnasium.wrappers.RecordVideo(
        env, str(tmp_path / "videos"), episode_trigger=lambda _: True, disable_logger=True
    )
    env.reset(seed=0)
    truncated = False
    while not truncated:
        truncated = env.step(np.array([0.5, 0.5], dtype=np.float32))[3]
    env.close()
    videos = list((tmp_path / "videos").glob("*.mp4"))
    assert len(videos) == 1 and videos[0].stat().st_size > 0


def test_frame_stacking_keeps_observations_in_the_stacked_space() -> None:
    env = gymnasium.make("mazesim/UnseenMaze-v2")
    env = gymnasium.wrappers.FrameStackObservation(env, 4)
    observation, _ = env.reset(seed=0)
    assert observation.shape[0] == 4 and env.observation_space.contains(observation)
    env.action_space.seed(0)
    for _ in range(10):
        observation = env.step(env.action_space.sample())[0]
        assert env.observation_space.contains(observation)


def test_normalising_observations_and_rewards_keeps_them_finite() -> None:
    env = gymnasium.make("mazesim/MazeRandomGoal-v1")
    env = gymnasium.wrappers.NormalizeReward(gymnasium.wrappers.NormalizeObservation(env))
    env.reset(seed=0)
    env.action_space.seed(0)
    for _ in range(50):
        observation, reward = env.step(env.action_space.sample())[:2]
        assert np.all(np.isfinite(observation)) and np.isfinite(reward)


def test_a_time_limit_given_at_make_truncates_without_terminating() -> None:
    env = gymnasium.make("mazesim/MazeFixed-v1", max_episode_steps=7)
    assert env.spec.max_episode_steps == 7
    env.reset(seed=0)
    ends = [env.step(np.zeros(2, dtype=np.float32))[2:4] for _ in range(7)]
    assert ends[-1] == (False, True)
    assert not any(terminated or truncated for terminated, truncated in ends[:-1])
    envs = gymnasium.make_vec("mazesim/MazeFixed-v1", num_envs=2, max_episode_steps=4)
    envs.reset(seed=0)
    flags = [envs.step(np.zeros((2, 2), dtype=np.float32))[2:4] for _ in range(4)]
    assert flags[-1][1].all() and not flags[-1][0].any()
    assert not any(truncated.any() for _, truncated in flags[:-1])


@pytest.mark.parametrize("env_id", ["mazesim/EPuckGoal-v0", "mazesim/UnseenMazeGoal-v0"])
def test_flattening_a_goal_tasks_dict_keeps_it_in_the_flat_space(env_id: str) -> None:
    env = gymnasium.wrappers.FlattenObservation(gymnasium.make(env_id))
    observation, _ = env.reset(seed=0)
    assert observation.ndim == 1 and env.observation_space.contains(observation)
    env.action_space.seed(0)
    for _ in range(20):
        assert env.observation_space.contains(env.step(env.action_space.sample())[0])


def test_rescaled_and_clipped_actions_drive_the_wheels_as_the_plain_ones() -> None:
    plain = gymnasium.make("mazesim/MazeFixed-v1")
    low, high = np.zeros(2, dtype=np.float32), np.ones(2, dtype=np.float32)
    rescaled = gymnasium.wrappers.RescaleAction(gymnasium.make("mazesim/MazeFixed-v1"), low, high)
    clipped = gymnasium.wrappers.ClipAction(
        gymnasium.make("mazesim/MazeFixed-v1", clip_actions=False)
    )
    for env in (plain, rescaled, clipped):
        env.reset(seed=0)
    for _ in range(10):
        expected = plain.step(np.array([1.0, 0.0], dtype=np.float32))[0]
        _assert_same(rescaled.step(np.array([1.0, 0.5], dtype=np.float32))[0], expected)
        _assert_same(clipped.step(np.array([3.0, 0.0], dtype=np.float32))[0], expected)


def test_a_seeded_reset_repeats_and_unseeded_resets_draw_on() -> None:
    env = gymnasium.make("mazesim/UnseenMaze-v2")
    _assert_same(env.reset(seed=3)[0], env.reset(seed=3)[0])
    names = {env.unwrapped.world.name}
    for _ in range(4):
        env.reset()
        names.add(env.unwrapped.world.name)
    assert len(names) > 1
    env.reset(seed=None, options=None)
    env.reset(options={})
    env.step(env.action_space.sample())


def test_render_before_reset_and_without_a_render_mode() -> None:
    with pytest.raises(gymnasium.error.ResetNeeded):
        gymnasium.make("mazesim/MazeFixed-v1", render_mode="rgb_array").render()
    env = gymnasium.make("mazesim/MazeFixed-v1")
    env.reset(seed=0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # gymnasium warns that no render mode was given
        assert env.render() is None


@pytest.mark.parametrize("mode", ["vector_entry_point", "sync", "async"])
def test_closing_twice_is_harmless_in_every_vectorization_mode(mode: str) -> None:
    envs = gymnasium.make_vec("mazesim/EPuckGoal-v0", num_envs=2, vectorization_mode=mode)
    envs.reset(seed=0)
    envs.close()
    envs.close()
    assert envs.closed


@pytest.mark.parametrize(
    "env_id",
    [
        "mazesim/MazeRandomGoal-v1",
        "mazesim/UnseenMaze-v2",
        "mazesim/UnseenMazeGuided-v0",
        "mazesim/UnseenMazeGoal-v0",
    ],
)
def test_every_observation_of_a_long_noisy_rollout_is_in_the_space(env_id: str) -> None:
    envs = gymnasium.make_vec(env_id, num_envs=8, max_episode_steps=60, noise=True)
    observations, _ = envs.reset(seed=11)
    assert envs.observation_space.contains(observations)
    envs.action_space.seed(1)
    ended = 0
    for _ in range(300):  # five episodes each: observations after autoreset included
        observations, rewards, terminated, truncated, _ = envs.step(envs.action_space.sample())
        assert envs.observation_space.contains(observations)
        assert rewards.dtype == np.float64 and np.all(np.isfinite(rewards))
        ended += int((terminated | truncated).sum())
    assert ended >= 8 * 4
    envs.close()


def test_info_keys_are_the_same_at_every_step_and_every_reset() -> None:
    env = gymnasium.make("mazesim/UnseenMaze-v2", max_episode_steps=30)
    _, first = env.reset(seed=0)
    env.action_space.seed(0)
    step_keys: set[str] | None = None
    resets = 0
    for _ in range(100):
        _, _, terminated, truncated, info = env.step(env.action_space.sample())
        keys = set(info)
        step_keys = step_keys or keys
        assert keys == step_keys
        if terminated or truncated:
            assert set(env.reset()[1]) == set(first)
            resets += 1
    assert resets >= 3


def test_the_native_vector_envs_infos_have_the_sync_ones_keys_and_values() -> None:
    native = gymnasium.make_vec("mazesim/MazeFixed-v1", num_envs=3)
    sync = gymnasium.make_vec("mazesim/MazeFixed-v1", num_envs=3, vectorization_mode="sync")
    _assert_same(native.reset(seed=0)[1], sync.reset(seed=0)[1])
    actions = np.zeros((3, 2), dtype=np.float32)
    _assert_same(native.step(actions)[4], sync.step(actions)[4])


@pytest.mark.parametrize("env_id", IDS)
def test_a_spec_through_json_makes_the_same_env(env_id: str) -> None:
    spec = gymnasium.spec(env_id)
    env = gymnasium.make(spec)
    assert env.spec.id == env_id and env.spec.max_episode_steps == spec.max_episode_steps
    again = gymnasium.make(gymnasium.envs.registration.EnvSpec.from_json(env.spec.to_json()))
    _assert_same(env.reset(seed=2)[0], again.reset(seed=2)[0])
    _assert_same(env.unwrapped.observation_names, again.unwrapped.observation_names)


def test_a_pickled_env_with_episode_statistics_goes_on_as_the_original() -> None:
    env = gymnasium.wrappers.RecordEpisodeStatistics(gymnasium.make("mazesim/UnseenMaze-v2"))
    env.reset(seed=4)
    action = np.array([0.3, 0.5], dtype=np.float32)
    for _ in range(10):
        env.step(action)
    copied = pickle.loads(pickle.dumps(env))
    for _ in range(30):
        first, second = env.step(action), copied.step(action)
        _assert_same(first[0], second[0])
        assert first[1] == second[1]


def test_a_deep_copied_sync_vector_env_goes_on_as_the_original() -> None:
    envs = gymnasium.make_vec("mazesim/MazeRandomGoal-v1", num_envs=2, vectorization_mode="sync")
    envs.reset(seed=0)
    copied = copy.deepcopy(envs)
    actions = np.full((2, 2), 0.4, dtype=np.float32)
    for _ in range(20):
        _assert_same(envs.step(actions)[0], copied.step(actions)[0])


def test_a_cleanrl_style_loop_over_wrapped_single_envs_reports_episodes() -> None:
    def make() -> Any:
        env = gymnasium.make("mazesim/MazeFixed-v1", max_episode_steps=20)
        return gymnasium.wrappers.RecordEpisodeStatistics(gymnasium.wrappers.ClipAction(env))

    envs = gymnasium.vector.SyncVectorEnv([make, make])
    envs = gymnasium.wrappers.vector.NormalizeReward(envs)
    envs.reset(seed=1)
    envs.action_space.seed(1)
    lengths = []
    for _ in range(45):
        info = envs.step(envs.action_space.sample())[4]
        if "episode" in info:
            lengths.extend(info["episode"]["l"][info["_episode"]].tolist())
    assert lengths == [20, 20, 20, 20]


def test_gymnasiums_vector_wrappers_stack_on_the_native_vector_env() -> None:
    envs = gymnasium.make_vec("mazesim/UnseenMaze-v2", num_envs=4, max_episode_steps=10)
    envs = gymnasium.wrappers.vector.ClipAction(envs)
    envs = gymnasium.wrappers.vector.NormalizeObservation(envs)
    envs = gymnasium.wrappers.vector.RecordEpisodeStatistics(envs)
    envs.reset(seed=0)
    episodes = 0
    for _ in range(21):
        observations, _, _, _, info = envs.step(np.full((4, 2), 2.0, dtype=np.float32))
        assert np.all(np.isfinite(observations))
        episodes += int(info.get("_episode", np.zeros(4, dtype=bool)).sum())
    assert episodes == 8
    envs.close()


@pytest.mark.parametrize("env_id", ["mazesim/MazeRandomGoal-v1", "mazesim/UnseenMazeGuided-v0"])
def test_the_native_vector_env_equals_sync_with_discrete_actions(env_id: str) -> None:
    options = {"action_mode": "discrete", "max_episode_steps": 40}
    native = gymnasium.make_vec(env_id, num_envs=3, **options)
    sync = gymnasium.make_vec(env_id, num_envs=3, vectorization_mode="sync", **options)
    _assert_same(native.reset(seed=9)[0], sync.reset(seed=9)[0])
    rng = np.random.default_rng(2)
    for _ in range(100):
        actions = rng.integers(0, 12, 3)
        for first, second in zip(native.step(actions)[:4], sync.step(actions)[:4]):
            _assert_same(first, second)


@pytest.mark.parametrize("env_id", IDS)
def test_the_native_vector_envs_spaces_and_metadata_are_the_sync_ones(env_id: str) -> None:
    native = gymnasium.make_vec(env_id, num_envs=2)
    sync = gymnasium.make_vec(env_id, num_envs=2, vectorization_mode="sync")
    assert native.single_observation_space == sync.single_observation_space
    assert native.single_action_space == sync.single_action_space
    assert native.observation_space == sync.observation_space
    assert native.action_space == sync.action_space
    assert native.metadata["autoreset_mode"] == sync.metadata["autoreset_mode"]
    native.close()
    sync.close()
