"""Fixtures shared by the transfer study's tests."""

from __future__ import annotations

import pytest

from mazesim import load_world
from mazesim.learn.evaluate import navigator_for
from mazesim.learn.tables import load_policy
from mazesim.transfer.cells import CellRun


@pytest.fixture(scope="module")
def run() -> CellRun:
    """The shipped navigator's cells in seed-maze: 2 episodes a cell, the simulator's events."""
    policy = load_policy(None)
    world = load_world(policy.world_name)
    higher, _ = navigator_for(policy, [world])
    assert policy.lower_q is not None
    return CellRun(world, policy.lower_q, higher, episodes=2, events="truth")
