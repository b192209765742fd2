"""Envs pickle and deep-copy, and a copy goes on exactly as the original; a World passed as
``world`` keeps ``env.spec`` usable, so subprocess vector envs work."""

from __future__ import annotations

import copy
import pickle
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

from gymnasium.utils.env_checker import data_equivalence  # noqa: E402

import mazesim  # noqa: E402
from mazesim.envs import ENV_ID, EPuckMazeVectorEnv  # noqa: E402

COPIES: dict[str, Callable[[Any], Any]] = {
    "pickle": lambda env: pickle.loads(pickle.dumps(env)),
    "deepcopy": copy.deepcopy,
}


def _continue(env: Any, actions: list[Any]) -> list[Any]:
    return [env.step(action) for action in actions]


@pytest.mark.parametrize("how", sorted(COPIES))
@pytest.mark.parametrize("world", ["seed-maze", "random"])
def test_a_copied_env_goes_on_as_the_original(how: str, world: str) -> None:
    env = gymnasium.make(ENV_ID, world=world, max_episode_steps=150)
    env.reset(seed=2)
    env.action_space.seed(2)
    for _ in range(40):  # into the episode: contacts, noise stream and time under way
        env.step(env.action_space.sample())
    twin = COPIES[how](env)
    actions = [env.action_space.sample() for _ in range(200)]  # crosses the time limit
    original = _continue(env, actions[:120])
    copied = _continue(twin, actions[:120])
    assert data_equivalence(original, copied, exact=True)
    assert original[-1][0].shape == (11,)
    # After the episode ends, both draw the same next episode from their RNGs.
    assert data_equivalence(env.reset(), twin.reset(), exact=True)
    assert data_equivalence(_continue(env, actions[120:]), _continue(twin, actions[120:]))


@pytest.mark.parametrize("how", sorted(COPIES))
def test_a_copied_vector_env_goes_on_as_the_original(how: str) -> None:
    envs = EPuckMazeVectorEnv(num_envs=4, world="random", max_episode_steps=60, threads=2)
    envs.reset(seed=8)
    envs.action_space.seed(8)
    for _ in range(50):
        envs.step(envs.action_space.sample())
    twin = COPIES[how](envs)
    for step in range(120):  # every env restarts on the way
        actions = envs.action_space.sample()
        mine, theirs = envs.step(actions), twin.step(actions)
        for a, b in zip(mine[:4], theirs[:4]):
            assert np.array_equal(a, b), step
        assert all(np.array_equal(mine[4][k], theirs[4][k]) for k in mine[4]), step
    envs.close()
    assert twin.step(envs.action_space.sample())[0].shape == (4, 11)  # independent of the original


def test_a_world_object_keeps_the_spec_and_runs_in_subprocesses() -> None:
    world = mazesim.generate_maze(4, 4, seed=3)
    env = gymnasium.make(ENV_ID, world=world)
    assert env.spec is not None and env.unwrapped.options.world == world
    options = {"world": world, "max_episode_steps": 30}
    parallel = gymnasium.make_vec(ENV_ID, 2, vectorization_mode="async", **options)
    serial = gymnasium.make_vec(ENV_ID, 2, vectorization_mode="sync", **options)
    assert np.array_equal(parallel.reset(seed=1)[0], serial.reset(seed=1)[0])
    parallel.action_space.seed(0)
    for _ in range(40):
        actions = parallel.action_space.sample()
        assert np.array_equal(parallel.step(actions)[0], serial.step(actions)[0])
    parallel.close()
    serial.close()
