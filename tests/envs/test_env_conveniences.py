"""What an RL user expects of the maze environments: ``is_success``, episode statistics, clipped
actions, ``gymnasium.make`` without a prior import, one list of options, a usable ``env.spec``."""

from __future__ import annotations

import subprocess
import sys
from typing import Any

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

from gymnasium.wrappers.vector import (  # noqa: E402
    RecordEpisodeStatistics as RecordVectorEpisodeStatistics,
)

from env_worlds import CORRIDOR  # noqa: E402
from mazesim.envs import ENV_ID, EPuckMazeEnv, EPuckMazeVectorEnv  # noqa: E402
from mazesim.envs.options import option_names  # noqa: E402
from mazesim.errors import InvalidActionError, InvalidArgumentError  # noqa: E402

FORWARD = np.array([0.8, 0.8], dtype=np.float32)


@pytest.fixture(scope="module")
def corridor(tmp_path_factory: pytest.TempPathFactory) -> str:
    path = tmp_path_factory.mktemp("worlds") / "corridor.toml"
    path.write_text(CORRIDOR)
    return str(path)


def test_is_success_is_true_on_the_step_that_reaches_the_goal(corridor: str) -> None:
    env = gymnasium.make(ENV_ID, world=corridor, noise=False)
    _, info = env.reset(seed=0)
    assert info["is_success"] is False
    successes, terminated, truncated = [], False, False
    while not (terminated or truncated):
        _, _, terminated, truncated, info = env.step(FORWARD)
        successes.append(info["is_success"])
    assert terminated and successes[-1] is True and not any(successes[:-1])


def test_vector_env_reports_is_success_where_episodes_end_at_the_goal(corridor: str) -> None:
    envs = EPuckMazeVectorEnv(num_envs=3, world=corridor, noise=False)
    envs.reset(seed=0)
    actions = np.tile(FORWARD, (3, 1))
    actions[1] = 0.0  # env 1 stays at the start
    for _ in range(400):
        _, _, terminated, _, info = envs.step(actions)
        assert np.array_equal(info["is_success"], terminated) and info["_is_success"].all()
        if terminated.any():
            break
    assert terminated.tolist() == [True, False, True]


def test_episode_statistics_of_the_native_vector_env_equal_single_envs(corridor: str) -> None:
    """gymnasium's RecordEpisodeStatistics gives episode returns and lengths: over the native
    vector env they are those over SyncVectorEnv of single envs."""
    num_envs = 3
    options = {"world": corridor, "max_episode_steps": 150}
    native, sync = (
        RecordVectorEpisodeStatistics(
            gymnasium.make_vec(ENV_ID, num_envs, vectorization_mode=mode, **options)
        )
        for mode in ("vector_entry_point", "sync")
    )
    native.reset(seed=5)
    sync.reset(seed=5)
    rng = np.random.default_rng(0)
    episodes = 0
    for _ in range(600):
        actions = (0.6 + 0.4 * rng.uniform(-1, 1, (num_envs, 2))).astype(np.float32)
        *_, info = native.step(actions)
        *_, expected = sync.step(actions)
        assert ("episode" in info) == ("episode" in expected)
        if "episode" in info:
            assert np.array_equal(info["_episode"], expected["_episode"])
            for key in ("r", "l"):
                assert np.array_equal(info["episode"][key], expected["episode"][key])
            episodes += int(info["_episode"].sum())
    assert episodes >= 6


@pytest.mark.parametrize("vector", [False, True], ids=["single", "vector"])
def test_actions_outside_the_box_are_clipped_by_default(vector: bool) -> None:
    def make(**options: Any) -> Any:
        if vector:
            return EPuckMazeVectorEnv(num_envs=2, **options)
        return gymnasium.make(ENV_ID, **options)

    wild, exact = make(), make()
    wild.reset(seed=1)
    exact.reset(seed=1)
    beyond = np.array([1.0001, -7.5])
    inside = np.array([1.0, -1.0], dtype=np.float32)
    if vector:
        beyond, inside = np.tile(beyond, (2, 1)), np.tile(inside, (2, 1))
    for _ in range(30):
        clipped, expected = wild.step(beyond), exact.step(inside)
        assert np.array_equal(clipped[0], expected[0]) and np.array_equal(clipped[1], expected[1])
    strict = make(clip_actions=False)
    strict.reset(seed=1)
    with pytest.raises(InvalidActionError, match=r"in \[-1, 1\], found 1.0001"):
        strict.step(beyond)
    nan = np.full_like(beyond, np.nan)
    with pytest.raises(InvalidActionError, match="finite"):
        wild.step(nan)  # clipping never hides a NaN


def test_unknown_option_names_the_options_there_are() -> None:
    with pytest.raises(InvalidArgumentError, match="found unknown 'wrold'") as raised:
        gymnasium.make(ENV_ID, wrold="random")
    assert "world" in str(raised.value) and "clip_actions" in str(raised.value)
    with pytest.raises(InvalidArgumentError, match="unknown 'clip'"):
        EPuckMazeVectorEnv(num_envs=2, clip=True)
    assert option_names()[:4] == ["world", "robot", "action_mode", "clip_actions"]


def test_the_env_docstring_names_every_option() -> None:
    documented = EPuckMazeEnv.__doc__ or ""
    assert [name for name in option_names() if f"``{name}``" not in documented] == []


def test_single_and_vector_env_take_the_same_options() -> None:
    options = {"world": "random", "action_mode": "discrete", "include_pose": True}
    single, vector = EPuckMazeEnv(**options), EPuckMazeVectorEnv(num_envs=2, **options)
    for name in option_names():
        mine, theirs = getattr(single.options, name, None), getattr(vector.options, name, None)
        assert mine == theirs or mine.name == theirs.name, name  # a robot profile by its name
    assert single.action_space == vector.single_action_space
    assert single.observation_space == vector.single_observation_space


def test_single_env_spec_of_the_vector_env_makes_one_of_its_environments() -> None:
    vector = gymnasium.make_vec(
        "mazesim/UnseenMaze-v2", 3, max_episode_steps=40, threads=1, maze_size=(3, 4)
    )
    spec = vector.unwrapped.single_env_spec
    reference = gymnasium.make("mazesim/UnseenMaze-v2", max_episode_steps=40, maze_size=(3, 4))
    assert spec == reference.spec
    single = gymnasium.make(spec)
    observations, _ = vector.reset(seed=5)
    assert np.array_equal(single.reset(seed=5)[0], observations[0])
    assert EPuckMazeVectorEnv(num_envs=2).single_env_spec is None  # not made by make_vec


def test_make_without_importing_mazesim_first() -> None:
    """gymnasium (1.x) has no plugin entry points; its ``module:env`` form imports mazesim."""
    script = (
        "import sys, gymnasium\n"
        "assert 'mazesim' not in sys.modules\n"
        "env = gymnasium.make('mazesim:mazesim/EPuckMaze-v0', world='random')\n"
        "observation, info = env.reset(seed=0)\n"
        "assert observation.shape == (11,) and env.spec.max_episode_steps == 3000\n"
        "envs = gymnasium.make_vec('mazesim:mazesim/EPuckMaze-v0', num_envs=2)\n"
        "assert type(envs.unwrapped).__name__ == 'EPuckMazeVectorEnv'\n"
        "print('ok')\n"
    )
    finished = subprocess.run(
        [sys.executable, "-W", "error", "-c", script], capture_output=True, text=True, timeout=120
    )
    assert finished.returncode == 0, finished.stderr
    assert finished.stdout.strip() == "ok"
