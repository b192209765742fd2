"""The navigator's stretches in the core give, episode for episode, what one step at a time gives
for navigators whose door sub-tasks count the distance (``door_distance``) and whose Corridors
and Corners holds its heading where blind (``hold_heading``): the randomised navigator shipped
(:mod:`mazesim.learn.core_episodes`); its evaluation is in ``test_core_episodes.py``."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import mazesim
from mazesim.episodes import EpisodeBatch, run_episodes
from mazesim.learn.core_episodes import run_navigator_episodes, stretches_apply
from mazesim.learn.higher import HigherLevel
from mazesim.learn.policy import HierarchicalPolicy
from mazesim.learn.subtasks import BLIND_STATE
from mazesim.learn.tables import load_policy
from mazesim.maze import checkpoint_ids


@pytest.mark.parametrize(
    ("navigator", "hold_heading", "stretch_steps", "seed", "threads"),
    [
        ("randomised", True, 256, 5, 2),
        ("randomised", True, 19, 5, 1),
        ("randomised", False, 41, 8, 2),
        (None, True, 256, 8, 1),
    ],
)
def test_stretches_equal_single_steps_with_distance_and_held_heading(
    navigator: str | None,
    hold_heading: bool,
    stretch_steps: int,
    seed: int,
    threads: int,
) -> None:
    """Random higher-level values (so every sub-task runs), a short step limit (so some episodes
    fail), fewer robots than episodes; two seeds, one and two threads, three stretch lengths."""
    shipped = load_policy(navigator)
    assert shipped.lower_q is not None
    worlds = [mazesim.generate_maze(5, 5, seed=300 + i) for i in range(2)]
    ids = [checkpoint_ids(world) for world in worlds]
    level = HigherLevel(ids, q=np.random.default_rng(seed).normal(size=HigherLevel(ids).q.shape))
    world_of_env = np.repeat(np.arange(2), 3)
    results = []
    blind = [0]
    for multi in (True, False):
        nav = EpisodeBatch(worlds, world_of_env, seed=seed, max_steps=2500, threads=threads)
        policy = HierarchicalPolicy(shipped.lower_q, level, world_of_env, hold_heading=hold_heading)
        assert stretches_apply(nav, policy)
        if multi:
            got = run_navigator_episodes(nav, policy, 4, stretch_steps=stretch_steps)
        else:

            def counted(*args: Any, act: Any = policy.act, p: Any = policy) -> Any:
                actions = act(*args)
                step = p.record
                blind[0] += int(np.count_nonzero((step.state == BLIND_STATE) & (step.subtask == 0)))
                return actions

            policy.act = counted  # type: ignore[method-assign]
            got = run_episodes(nav, policy, 4, None, None, policy.record.decisions)
        results.append(got)
    fast, slow = results
    assert [r.episode for r in fast] == list(range(8))
    assert fast == slow
    assert any(r.arrived for r in fast), "expected some episodes to arrive"
    assert {option for r in fast for _, option in r.decisions} >= {1, 2, 3}
    assert blind[0] > 0, "expected Corridors and Corners in the blind state"
