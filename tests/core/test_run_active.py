"""``BatchSimulator.run(..., active=mask)``: the envs outside the mask stand still for the call.

A caller stepping some envs one step at a time and others many steps at once (the navigator's
corridor stretches, :mod:`mazesim.learn.core_episodes`) relies on it: a held env neither moves nor
draws from its streams, and an active env goes exactly as it would with every env active.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import numpy.typing as npt
import pytest

import mazesim
from mazesim.batch import RobotBatch


def batch_of(n: int) -> RobotBatch:
    worlds = [mazesim.generate_maze(5, 5, seed=70 + i) for i in range(n)]
    batch = RobotBatch(worlds, np.arange(n), threads=1)
    batch.observe()
    return batch


def run(
    batch: RobotBatch, steps: int, active: npt.NDArray[np.bool_] | None = None
) -> dict[str, Any]:
    return batch.simulator.run(
        steps,
        "random",
        batch.observations,
        batch.poses,
        batch.colliding,
        batch.crossings,
        settings=mazesim.RunSettings(seeds=5, active=active),
    )


def test_held_envs_stand_still_and_active_ones_go_as_without_a_mask() -> None:
    held, free = batch_of(6), batch_of(6)
    start = held.poses.copy()
    active = np.array([True, False, True, True, False, True])
    counters = run(held, 30, active)
    run(free, 30)
    assert counters["steps"].tolist() == [30, 0, 30, 30, 0, 30]
    np.testing.assert_array_equal(held.poses[~active], start[~active])
    for mine, theirs in zip(
        (held.observations, held.poses, held.colliding, held.crossings),
        (free.observations, free.poses, free.colliding, free.crossings),
    ):
        np.testing.assert_array_equal(mine[active], theirs[active])
    # A held env's stream was not drawn from: run later, it goes as env 1 of a fresh batch does.
    again = batch_of(6)
    only_one = np.zeros(6, dtype=bool)
    only_one[1] = True
    run(held, 30, only_one)
    run(again, 30, only_one)
    np.testing.assert_array_equal(held.poses[1], again.poses[1])
    assert not np.array_equal(held.poses[1], start[1])


def test_an_active_mask_of_the_wrong_length_is_refused() -> None:
    with pytest.raises(mazesim.InvalidArgumentError, match="active"):
        run(batch_of(3), 5, np.ones(2, dtype=bool))
