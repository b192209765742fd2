"""``world=`` a callable: a distribution of worlds of one's own, drawn at each reset from the
env's RNG, seeded and deterministic, the same in the native vector env as over single envs."""

from __future__ import annotations

from pathlib import Path

import gymnasium
import numpy as np
import pytest

import mazesim
from mazesim.envs.baselines import FrontierExplorer, evaluate
from mazesim.envs.curriculum import MazeSizeCurriculum
from mazesim.errors import InvalidArgumentError

TASK = "mazesim/UnseenMazeExplore-v0"


def sizes_and_seeds(rng: np.random.Generator) -> mazesim.World:
    """Mazes of 3 x 3 to 5 x 5 cells, each a fresh seed: a training distribution of one's own."""
    side = int(rng.integers(3, 6))
    return mazesim.generate_maze(side, side, seed=int(rng.integers(2**32)))


def episode_worlds(seed: int, episodes: int) -> list[str]:
    env = gymnasium.make(TASK, world=sizes_and_seeds)
    worlds = []
    for episode in range(episodes):
        env.reset(seed=seed if episode == 0 else None)
        worlds.append(env.unwrapped.world.to_toml())
    env.close()
    return worlds


def test_the_same_seed_draws_the_same_worlds_and_another_seed_others() -> None:
    first = episode_worlds(7, 6)
    assert episode_worlds(7, 6) == first
    assert len(set(first)) > 1  # a new world at each reset
    assert episode_worlds(8, 6) != first


def test_the_sampler_draws_from_the_env_rng_at_each_reset() -> None:
    calls: list[np.random.Generator] = []

    def sampler(rng: np.random.Generator) -> mazesim.World:
        calls.append(rng)
        return sizes_and_seeds(rng)

    env = gymnasium.make(TASK, world=sampler)
    assert len(calls) == 1  # once when made, for the spaces, with an RNG of its own
    env.reset(seed=3)
    assert len(calls) == 2 and calls[1] is env.unwrapped.np_random
    # The episode's world is the first draw of the RNG that reset(seed=3) seeded.
    rng, _ = gymnasium.utils.seeding.np_random(3)
    assert env.unwrapped.world.to_toml() == sizes_and_seeds(rng).to_toml()
    env.close()


def test_the_native_vector_env_equals_single_envs_bit_for_bit() -> None:
    options = {"world": sizes_and_seeds, "max_episode_steps": 50}
    native = gymnasium.make_vec(TASK, num_envs=3, **options)
    sync = gymnasium.make_vec(TASK, num_envs=3, vectorization_mode="sync", **options)
    observations, _ = native.reset(seed=11)
    expected, _ = sync.reset(seed=11)
    np.testing.assert_array_equal(observations, expected)
    first = [world.to_toml() for world in native.unwrapped._worlds]  # type: ignore[attr-defined]
    actions = np.random.default_rng(0).uniform(-1, 1, (400, 3, 2)).astype(np.float32)
    truncated = 0
    for action in actions:
        got = native.step(action)
        want = sync.step(action)
        for a, b in zip(got[:4], want[:4]):
            np.testing.assert_array_equal(a, b)
        truncated += int(np.sum(got[3]))
    worlds = [world.to_toml() for world in native.unwrapped._worlds]  # type: ignore[attr-defined]
    assert worlds == [env.unwrapped.world.to_toml() for env in sync.envs]
    assert truncated >= 3 * 7 and worlds != first  # the autoresets drew new worlds
    native.close()
    sync.close()


def test_a_sampler_may_return_names_and_paths(tmp_path: Path) -> None:
    path = tmp_path / "mine.toml"
    path.write_text(mazesim.generate_maze(3, 3, seed=5).to_toml(), encoding="utf-8")
    env = gymnasium.make("mazesim/EPuckMaze-v0", world=lambda rng: str(path))
    env.reset(seed=0)
    assert env.unwrapped.world.to_toml() == mazesim.load_world(str(path)).to_toml()
    env.close()


def test_a_sampler_returning_something_else_is_told_what_to_return() -> None:
    def broken(rng: np.random.Generator) -> object:
        return [mazesim.generate_maze(3, 3, seed=1)]

    with pytest.raises(InvalidArgumentError) as refused:
        gymnasium.make(TASK, world=broken)
    said = str(refused.value)
    assert "expected the world sampler" in said and "'test_a_sampler_returning" in said
    assert "return a World, a built-in world name or a path" in said
    assert "found [" in said and "generate_maze(5, 5, seed=int(rng.integers(2**32)))" in said


def test_a_sampled_world_without_cells_is_refused_when_starts_are_drawn() -> None:
    with pytest.raises(InvalidArgumentError, match="arena"):
        gymnasium.make(TASK, world=lambda rng: "arena")


def test_the_curriculum_refuses_an_env_of_a_sampler_saying_what_to_do() -> None:
    env = gymnasium.make(TASK, world=sizes_and_seeds)
    with pytest.raises(InvalidArgumentError, match=r"generate_maze\(\*curriculum.size"):
        MazeSizeCurriculum().apply(env)
    env.close()


class Forward:
    """A policy of one's own for ``evaluate``: drive straight ahead."""

    def __init__(self, observation_names: list[str], maze_size: tuple[int, int]) -> None:
        self.size = maze_size

    def act(self, observation: np.ndarray) -> np.ndarray:
        return np.array([0.8, 0.8], dtype=np.float32)


def test_evaluate_runs_a_policy_of_ones_own_on_held_out_mazes_of_a_sampler() -> None:
    drawn: list[int] = []

    def held_out(rng: np.random.Generator) -> mazesim.World:
        drawn.append(int(rng.integers(10**6, 2 * 10**6)))
        return mazesim.generate_maze(3, 3, seed=drawn[-1])

    first = evaluate(TASK, FrontierExplorer, episodes=4, maze_size=(3, 3), world=held_out)
    # The probe, one maze per held-out episode, and those of the ended envs' next episodes.
    assert len(drawn) >= 1 + 4
    assert all(seed >= 10**6 for seed in drawn)
    again = evaluate(TASK, FrontierExplorer, episodes=4, maze_size=(3, 3), world=held_out)
    assert again == first and first.success > 0
    straight = evaluate(TASK, Forward, episodes=4, maze_size=(3, 3), world=held_out)
    assert straight.episodes == 4 and straight.mean_length > 0


def test_evaluate_refuses_no_episodes_naming_its_own_argument() -> None:
    with pytest.raises(InvalidArgumentError, match="expected episodes to be a whole number of at"):
        evaluate(TASK, None, episodes=0)
