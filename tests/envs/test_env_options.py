"""The options of ``gymnasium.make`` and ``make_vec`` as a sweep or a config file hands them over:
numpy scalars, wrong types, and combinations that cannot run, refused when the env is made."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

import mazesim  # noqa: E402
from mazesim.envs import EPuckMazeEnv, EPuckMazeVectorEnv  # noqa: E402
from mazesim.errors import InvalidArgumentError  # noqa: E402

TASK = "mazesim/UnseenMaze-v2"

#: Options as numpy gives them (a sweep's ``rng.integers`` or ``np.linspace``, a config's array)
#: and as Python numbers: the env made with either is the same env.
NUMPY_OPTIONS: list[tuple[str, Any, Any]] = [
    ("maze_size", (np.int64(4), np.int32(6)), (4, 6)),
    ("maze_size", np.array([4, 6]), (4, 6)),
    ("render_size", np.int64(64), 64),
    ("render_size", np.array([64, 48]), (64, 48)),
    ("control_step_ms", np.float32(64.0), 64.0),
    ("goal_reward", np.float32(5.0), 5.0),
    ("collision_penalty", np.float64(0.25), 0.25),
    ("progress_reward", np.int64(20), 20),
]


def rollout(env: Any, steps: int = 40) -> list[Any]:
    """Observations and rewards of a seeded rollout with a fixed action sequence."""
    observation, _ = env.reset(seed=3)
    actions = np.random.default_rng(0).uniform(-1, 1, (steps, 2)).astype(np.float32)
    out = [observation]
    for action in actions:
        observation, reward, _, _, _ = env.step(action)
        out += [observation, reward]
    return out


@pytest.mark.parametrize(
    ("name", "numpy_value", "python_value"),
    NUMPY_OPTIONS,
    ids=[f"{name}-{type(value).__name__}" for name, value, _ in NUMPY_OPTIONS],
)
def test_numpy_values_make_the_same_env_as_python_numbers(
    name: str, numpy_value: Any, python_value: Any
) -> None:
    from_numpy = gymnasium.make(TASK, **{name: numpy_value})
    from_python = gymnasium.make(TASK, **{name: python_value})
    mine, theirs = rollout(from_numpy), rollout(from_python)
    assert all(np.array_equal(a, b) for a, b in zip(mine, theirs))
    # Rewards stay Python floats (gymnasium's SupportsFloat), whatever the weights' types.
    assert all(type(value) is float for value in mine[2::2])
    vector = gymnasium.make_vec(TASK, 2, **{name: numpy_value})
    observations, _ = vector.reset(seed=0)
    _, rewards, _, _, _ = vector.step(vector.action_space.sample())
    assert observations.dtype == np.float32 and rewards.dtype == np.float64


@pytest.mark.parametrize(
    "render_size", [3.5, None, "big", (64,), (64, 64.0), True, np.array(64), np.ones((2, 2), int)]
)
def test_a_render_size_of_the_wrong_type_is_refused_by_name(render_size: Any) -> None:
    for make in (EPuckMazeEnv, EPuckMazeVectorEnv):
        with pytest.raises(InvalidArgumentError, match="render_size"):
            make(render_size=render_size)


@pytest.mark.parametrize("world", ["arena", "line-follow"])
def test_random_starts_in_a_world_without_a_cell_maze_are_refused_when_made(world: str) -> None:
    # gymnasium.make should fail, not the first reset() inside a training loop.
    with pytest.raises(InvalidArgumentError, match='cell maze for start_goal="random"'):
        gymnasium.make(TASK, world=world)
    with pytest.raises(InvalidArgumentError, match='cell maze for start_goal="random"'):
        gymnasium.make_vec(TASK, 2, world=world)
    env = gymnasium.make(TASK, world=world, start_goal="world")  # its own start and goal: fine
    assert env.observation_space.contains(env.reset(seed=0)[0])


@pytest.mark.parametrize("mode", [None, "sync", "vector_entry_point"])
def test_a_mistyped_option_says_which_option_was_meant(mode: str | None) -> None:
    with pytest.raises(InvalidArgumentError) as caught:
        if mode is None:
            gymnasium.make(TASK, wrold="arena", max_episde_steps=10)
        else:
            gymnasium.make_vec(TASK, num_envs=2, vectorization_mode=mode, wrold="arena")
    message = str(caught.value)
    assert "expected options among world, robot," in message
    assert message.endswith(
        "; did you mean 'max_episode_steps' for 'max_episde_steps', 'world' for 'wrold'?"
        if mode is None
        else "; did you mean 'world' for 'wrold'?"
    )
    with pytest.raises(InvalidArgumentError, match="did you mean 'render_mode' for 'render_mod'"):
        gymnasium.make(TASK, render_mod="rgb_array")
    with pytest.raises(InvalidArgumentError) as caught:
        gymnasium.make(TASK, colour="red")
    assert "did you mean" not in str(caught.value)


def test_a_list_of_worlds_is_told_how_to_run_a_maze_distribution_of_ones_own() -> None:
    worlds = [mazesim.generate_maze(4, 4, seed=seed, loops=0.3) for seed in range(2)]
    with pytest.raises(InvalidArgumentError) as refused:
        gymnasium.make(TASK, world=worlds)
    said = (
        "give a callable that draws each episode's world from the env's RNG: "
        "world=lambda rng: worlds[rng.integers(len(worlds))]"
    )
    assert str(refused.value).endswith(said)
    # What it says runs: each episode in one of the worlds, drawn from the env's RNG.
    env = gymnasium.make(TASK, world=lambda rng: worlds[rng.integers(len(worlds))])
    seen = set()
    for seed in range(8):
        env.reset(seed=seed)
        seen.add(env.unwrapped.world.to_toml())
    assert seen == {world.to_toml() for world in worlds}
    env.close()
