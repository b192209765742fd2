"""``BatchSimulator.run(..., hold_spins=True)``: the tabular controller keeps turning on the spot
the way the env's last step turned, as ``mazesim.learn.policy.hold_spins`` does in Python."""

from __future__ import annotations

import numpy as np
import pytest

import mazesim
from mazesim.actions import ACTION_CODES
from mazesim.batch import RobotBatch

RIGHT, LEFT = ACTION_CODES.index("aa"), ACTION_CODES.index("bb")


def only(action: int) -> np.ndarray:
    """A table whose best action is ``action`` in every state."""
    table = np.zeros((4096, 12))
    table[:, action] = 1.0
    return table


def actions(batch: RobotBatch, table: np.ndarray, steps: int, hold: bool) -> list[int]:
    trace = {"actions": np.zeros((steps, batch.num_envs), np.int32)}
    batch.simulator.run(
        steps,
        mazesim.TabularSettings(table, hold_spins=hold),
        batch.observations,
        batch.poses,
        batch.colliding,
        batch.crossings,
        settings=mazesim.RunSettings(trace=trace),
    )
    return [int(a) for a in trace["actions"][:, 0]]


@pytest.mark.parametrize(("first", "then"), [(RIGHT, LEFT), (LEFT, RIGHT)])
def test_a_turn_on_the_spot_is_kept_only_when_asked(first: int, then: int) -> None:
    held, free = (RobotBatch([mazesim.load_world("seed-maze")], [0], threads=1) for _ in "ab")
    for batch in (held, free):
        batch.reset()
        assert actions(batch, only(first), 1, hold=True) == [first]
    assert actions(held, only(then), 3, hold=True) == [first] * 3
    assert actions(free, only(then), 3, hold=False) == [then] * 3


def test_after_a_reset_or_another_action_nothing_is_held() -> None:
    batch = RobotBatch([mazesim.load_world("seed-maze")], [0], threads=1)
    batch.reset()
    assert actions(batch, only(LEFT), 1, hold=True) == [LEFT]
    batch.reset()
    forward = ACTION_CODES.index("00")
    assert actions(batch, only(forward), 1, hold=True) == [forward]
    assert actions(batch, only(RIGHT), 2, hold=True) == [RIGHT, RIGHT]
