"""Issue 35: misuse of the gymnasium envs raises the package's errors, the same in the single and
the vector env (each also gymnasium's own error class where gymnasium defines one)."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

from gymnasium.error import ClosedEnvironmentError, ResetNeeded  # noqa: E402

from mazesim.envs import EnvClosedError, EPuckMazeEnv, EPuckMazeVectorEnv  # noqa: E402
from mazesim.envs.errors import MAX_SEED, ResetNeededError  # noqa: E402
from mazesim.errors import InvalidArgumentError, MazesimError  # noqa: E402

KINDS = ["single", "vector"]


def make(kind: str) -> Any:
    return EPuckMazeEnv() if kind == "single" else EPuckMazeVectorEnv(num_envs=2)


def action(kind: str) -> Any:
    return np.zeros(2 if kind == "single" else (2, 2), dtype=np.float32)


@pytest.mark.parametrize("kind", KINDS)
def test_every_call_after_close_raises_the_closed_error(kind: str) -> None:
    env = make(kind)
    env.reset(seed=0)
    env.close()
    for call in (lambda: env.reset(seed=0), lambda: env.step(action(kind))):
        with pytest.raises(EnvClosedError) as caught:
            call()
        assert isinstance(caught.value, MazesimError)
        assert isinstance(caught.value, ClosedEnvironmentError)


@pytest.mark.parametrize("kind", KINDS)
def test_step_before_reset_raises_the_reset_needed_error(kind: str) -> None:
    with pytest.raises(ResetNeededError) as caught:
        make(kind).step(action(kind))
    assert isinstance(caught.value, MazesimError) and isinstance(caught.value, ResetNeeded)


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize(
    "options", [123, "reset_mask", [("reset_mask", None)], 1.5], ids=["int", "str", "list", "float"]
)
def test_options_that_are_not_a_dict_are_invalid_arguments(kind: str, options: Any) -> None:
    env = make(kind)
    refused = "expected options to be None or a dict|options refused: expected dict"
    with pytest.raises(InvalidArgumentError, match=refused):
        env.reset(seed=0, options=options)
    env.reset(seed=0, options={})


def test_a_misspelt_reset_option_is_refused_by_name() -> None:
    """``reset_mak`` for the vector env's ``reset_mask`` was ignored without a word."""
    env = make("vector")
    with pytest.raises(InvalidArgumentError, match="found 'reset_mak'; did you mean 'reset_mask'"):
        env.reset(seed=0, options={"reset_mak": np.ones(2, bool)})
    env.reset(seed=0, options={"reset_mask": np.ones(2, bool)})


@pytest.mark.parametrize("kind", KINDS)
def test_an_option_no_env_reads_is_left_alone(kind: str) -> None:
    """Wrappers pass options of their own; PettingZoo's API test resets with ``{"options": 1}``."""
    first, _ = make(kind).reset(seed=0)
    again, _ = make(kind).reset(seed=0, options={"options": 1})
    np.testing.assert_array_equal(first, again)


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("seed", [-1, MAX_SEED + 1, 1.5, "7", True, np.float64(3.0)], ids=str)
def test_the_same_seeds_are_refused_by_both(kind: str, seed: Any) -> None:
    with pytest.raises(InvalidArgumentError, match="seed"):
        make(kind).reset(seed=seed)


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("seed", [0, 7, np.int64(5), np.uint64(MAX_SEED), MAX_SEED], ids=str)
def test_the_same_seeds_are_accepted_by_both(kind: str, seed: Any) -> None:
    observation, _ = make(kind).reset(seed=seed)
    assert np.all(np.isfinite(observation))


def test_a_vector_env_seeds_env_i_with_seed_plus_i_wrapping_past_the_largest() -> None:
    vector = EPuckMazeVectorEnv(num_envs=2)
    observations, _ = vector.reset(seed=MAX_SEED)
    for i, seed in enumerate([MAX_SEED, 0]):
        single, _ = EPuckMazeEnv().reset(seed=seed)
        np.testing.assert_array_equal(observations[i], single)


def _open_grid(side: int) -> str:
    rows = ["+" + "--+" * side]
    for row in range(side):
        cells = ["S " if row == side - 1 and col == 0 else "  " for col in range(side)]
        rows.append("|" + " ".join(cells) + "|")
        rows.append("+" + ("  +" * side if row < side - 1 else "--+" * side))
    grid = "\n".join(rows)
    return (
        'format = "mazesim-world"\nversion = 1\nname = "open"\nbasic_time_step_ms = 32\n'
        "[grid]\ncell_size = 0.25\nwall_thickness = 0.01\norigin = [0.0, 0.0]\n"
        f'map = """\n{grid}\n"""\n'
    )


@pytest.mark.parametrize("kind", KINDS)
def test_a_world_past_the_env_cell_limit_is_refused_at_once(kind: str) -> None:
    from mazesim import World
    from mazesim.envs.options import MAX_ENV_CELLS

    side = int(MAX_ENV_CELLS**0.5) + 1
    world = World.from_toml(_open_grid(side), "open.toml")
    env_class = EPuckMazeEnv if kind == "single" else EPuckMazeVectorEnv
    with pytest.raises(InvalidArgumentError, match=f"at most {MAX_ENV_CELLS} maze cells"):
        env_class(world=world) if kind == "single" else env_class(num_envs=2, world=world)
    with pytest.raises(InvalidArgumentError, match="maze_size"):
        env_class(world="random", maze_size=(side, side))


@pytest.mark.parametrize(
    "layout",
    [np.asfortranarray, lambda a: np.ascontiguousarray(a.T).T, lambda a: np.repeat(a, 2, 0)[::2]],
)
def test_the_vector_env_steps_actions_of_any_memory_layout_alike(layout: Any) -> None:
    """Actions in Fortran order (or a transpose of a (2, N) policy output) kept their order
    through the env's conversion and the batch refused them as "not C-contiguous"; a strided
    slice was copied and worked. Every layout of the same values steps the same."""
    wanted = np.array([[0.5, -0.25], [1.0, 0.75], [-1.0, 0.0]], np.float32)
    results = []
    for given in (wanted, layout(wanted)):
        env = EPuckMazeVectorEnv(num_envs=3)
        env.reset(seed=7)
        observations, *_ = env.step(given)
        results.append(observations)
    assert np.array_equal(results[0], results[1])
