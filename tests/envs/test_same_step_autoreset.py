"""gymnasium's SAME_STEP autoreset in the native vector env: bit for bit SyncVectorEnv's."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")

from gymnasium.vector import AutoresetMode  # noqa: E402

from env_worlds import CORRIDOR  # noqa: E402
from mazesim.envs import ENV_ID, EPuckMazeVectorEnv  # noqa: E402
from mazesim.errors import UnknownNameError  # noqa: E402


def assert_same_info(mine: dict[str, Any], theirs: dict[str, Any], where: str) -> None:
    """Info dicts of arrays (and SAME_STEP's nested ``final_info`` and object ``final_obs``)."""
    assert mine.keys() == theirs.keys(), f"{where}: keys {sorted(mine)} != {sorted(theirs)}"
    for key, value in mine.items():
        expected = theirs[key]
        if isinstance(value, dict):
            assert_same_info(value, expected, f"{where}: {key}")
        elif value.dtype == object:
            assert expected.dtype == object, f"{where}: {key} dtype"
            for row, (a, b) in enumerate(zip(value, expected)):
                assert (a is None and b is None) or np.array_equal(a, b), f"{where}: {key}[{row}]"
        else:
            assert value.dtype == expected.dtype, f"{where}: {key} dtype"
            assert np.array_equal(value, expected), f"{where}: {key} differ"


@pytest.mark.parametrize("world", ["corridor", "random"])
def test_same_step_autoreset_equals_sync_vector_env(world: str, tmp_path: Any) -> None:
    if world == "corridor":
        path = tmp_path / "corridor.toml"
        path.write_text(CORRIDOR)
        world = str(path)
    num_envs = 5
    options = {"world": world, "max_episode_steps": 300}
    native = gymnasium.make_vec(
        ENV_ID,
        num_envs,
        vectorization_mode="vector_entry_point",
        autoreset_mode="SameStep",
        **options,
    )
    sync = gymnasium.make_vec(
        ENV_ID,
        num_envs,
        vectorization_mode="sync",
        vector_kwargs={"autoreset_mode": AutoresetMode.SAME_STEP},
        **options,
    )
    assert native.metadata["autoreset_mode"] == AutoresetMode.SAME_STEP
    observations, info = native.reset(seed=3)
    expected, expected_info = sync.reset(seed=3)
    assert np.array_equal(observations, expected)
    assert_same_info(info, expected_info, "reset")
    rng = np.random.default_rng(1)
    ended = reached = 0
    for step in range(700):
        actions = (0.7 + 0.3 * rng.uniform(-1, 1, (num_envs, 2))).astype(np.float32)
        result, reference = native.step(actions), sync.step(actions)
        names = ("obs", "reward", "terminated", "truncated")
        for name, mine, theirs in zip(names, result, reference):
            assert mine.dtype == theirs.dtype and np.array_equal(mine, theirs), f"{step}: {name}"
        assert_same_info(result[4], reference[4], f"step {step}")
        ended += int((result[2] | result[3]).sum())
        reached += int(result[2].sum())
    assert ended >= num_envs  # every env restarted at least once
    if world != "random":
        assert reached > 0


def test_an_unknown_autoreset_mode_is_refused() -> None:
    with pytest.raises(UnknownNameError, match="autoreset_mode.*Disabled.*found 'Never'"):
        EPuckMazeVectorEnv(num_envs=2, autoreset_mode="Never")
    with pytest.raises(UnknownNameError) as refused:
        EPuckMazeVectorEnv(num_envs=2, autoreset_mode="Never")
    assert "did you mean" not in str(refused.value)


@pytest.mark.parametrize(
    ("spelt", "meant"),
    [("next_step", "NextStep"), ("SAME_STEP", "SameStep"), ("disabled", "Disabled")],
)
def test_a_mode_spelt_otherwise_is_told_gymnasiums_spelling(spelt: str, meant: str) -> None:
    with pytest.raises(UnknownNameError, match=f"found '{spelt}'; did you mean '{meant}'\\?$"):
        EPuckMazeVectorEnv(num_envs=2, autoreset_mode=spelt)
