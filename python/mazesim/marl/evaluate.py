"""One evaluator for every policy of a multi-robot task: the same held-out episodes, the same
measures, whether the policy is learned, random or a hand rule."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mazesim.marl.batch import MultiRobotBatch
from mazesim.marl.rules import Policy

__all__ = ["Evaluation", "evaluate"]


@dataclass(frozen=True)
class Evaluation:
    """Measures of one episode in each of a batch's environments.

    Attributes:
        episodes: Episodes (environments) evaluated.
        mean_return: Mean return of a robot.
        success: Share of robots that reached their goal (``maze_goals``; NaN otherwise).
        collided: Share of robots whose episode a contact ended (``maze_goals``; NaN
            otherwise).
        dispersion: Mean dispersion at the last step (``aggregation``; NaN otherwise).
    """

    episodes: int
    mean_return: float
    success: float
    collided: float
    dispersion: float


def evaluate(batch: MultiRobotBatch, policy: Policy, seed: int) -> Evaluation:
    """Runs one episode in every environment of ``batch`` (reset with ``seed``), each robot acting
    by ``policy`` on its observation, until every robot's episode has ended."""
    saved = batch.autoreset
    batch.autoreset = False
    try:
        observations, _ = batch.reset(seed)
        returns = np.zeros((batch.num_envs, batch.num_robots))
        success = np.zeros_like(returns, dtype=bool)
        collided = np.zeros_like(success)
        spread = np.full(batch.num_envs, np.nan)
        while batch.live.any():
            live = batch.live.copy()
            observations, rewards, terminations, _, infos = batch.step(policy(observations))
            returns += rewards
            if "is_success" in infos:
                success |= infos["is_success"]
                collided |= terminations & live & ~infos["is_success"]
            if "dispersion" in infos:
                spread = np.where(live.any(axis=1), infos["dispersion"][:, 0], spread)
    finally:
        batch.autoreset = saved
    goals = "is_success" in infos
    return Evaluation(
        episodes=batch.num_envs,
        mean_return=float(returns.mean()),
        success=float(success.mean()) if goals else float("nan"),
        collided=float(collided.mean()) if goals else float("nan"),
        dispersion=float(spread.mean()),
    )
