"""Bytes per env of a batch: envs of equal worlds share one copy of the world (worlds are
deduplicated by content, not by object), and an env's own state is small."""

from __future__ import annotations

import numpy as np

import mazesim
from mazesim import BatchSimulator


def test_equal_worlds_are_shared_by_content() -> None:
    distinct = BatchSimulator([mazesim.generate_maze(5, 5, seed=s) for s in range(64)])
    equal = BatchSimulator([mazesim.generate_maze(5, 5, seed=7) for _ in range(64)])
    assert equal.bytes_per_env() * 4 < distinct.bytes_per_env()
    assert equal.bytes_per_env() <= 4_000
    assert distinct.bytes_per_env() <= 16_000


def test_a_shared_world_steps_as_separate_copies_would() -> None:
    """Envs 0 and 1 run in the same (shared) world with the same seed: identical rows."""
    worlds = [mazesim.generate_maze(5, 5, seed=3) for _ in range(2)]
    batch = BatchSimulator(worlds, seeds=[11, 11])
    n, width = batch.num_envs, batch.observation_width
    observations = np.zeros((n, width), np.float32)
    poses = np.zeros((n, 3), np.float32)
    colliding = np.zeros(n, np.bool_)
    crossings = np.zeros(n, np.int32)
    actions = np.tile(np.array([[6.0, 5.0]], np.float32), (n, 1))
    touched = False
    for _ in range(300):
        batch.step(actions, observations, poses, colliding, crossings)
        assert observations[0].tobytes() == observations[1].tobytes()
        assert poses[0].tobytes() == poses[1].tobytes()
        touched = touched or bool(colliding.any())
    assert touched
