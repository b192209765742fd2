"""Settings of training runs small enough for the tests (a few seconds each)."""

from __future__ import annotations

from mazesim.learn.train import TrainSettings

__all__ = ["TINY"]

#: Three lower-level rounds of 64 robots, four higher-level episodes.
TINY = TrainSettings(
    envs=64,
    steps=64 * 500 * 3,
    seed=11,
    maze_pool=8,
    higher_episodes=4,
    higher_envs=2,
    higher_max_steps=300,
    checkpoint_seconds=1e9,
)
