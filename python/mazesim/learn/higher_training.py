"""The higher level's training: episodes on the target worlds, the lower level fixed, the
sub-tasks chosen epsilon-greedily at checkpoint events.

The episodes run through the episode layer (:func:`mazesim.episodes.run_episodes`) on the
``higher/episode`` stream; exploration draws from ``higher/explore`` (:mod:`mazesim._seeding`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from mazesim._core import World
from mazesim._seeding import stream
from mazesim._settings import MAX_COUNT, MAX_SEED, bounded, check_settings
from mazesim.batch import RobotChoice
from mazesim.episodes import MAX_STEPS, EpisodeBatch, EpisodeResult, StartJitter, run_episodes
from mazesim.learn.higher import (
    CONTACT_REWARD,
    GOAL_REWARD,
    STEP_REWARD,
    HigherLearner,
    HigherLevel,
)
from mazesim.learn.policy import HierarchicalPolicy
from mazesim.maze import checkpoint_ids

__all__ = [
    "HigherTraining",
    "train_higher",
]


@dataclass(frozen=True)
class HigherTraining:
    """How the higher level trains on its worlds; the defaults are ``mazesim train``'s (the
    adaptation to unseen worlds of :func:`mazesim.learn.evaluate.navigator_for` is
    :data:`mazesim.learn.evaluate.ADAPTATION`)."""

    episodes_per_world: int = bounded(400, least=1, most=MAX_COUNT)
    envs_per_world: int = bounded(32, least=1, most=MAX_COUNT)
    epsilon_start: float = bounded(0.2, least=0.0, most=1.0)
    greedy_share: float = bounded(0.3, least=0.0, most=1.0)
    max_steps: int = bounded(MAX_STEPS, least=1, most=MAX_COUNT)
    seed: int = bounded(0, least=0, most=MAX_SEED)

    def __post_init__(self) -> None:
        check_settings(self)

    def epsilon(self, episodes_started: npt.NDArray[np.int64]) -> npt.NDArray[np.float64]:
        """Exploration rate of each world after it started that many episodes."""
        exploring = max(1.0, self.episodes_per_world * (1.0 - self.greedy_share))
        return np.maximum(0.0, self.epsilon_start * (1.0 - episodes_started / exploring))


def train_higher(
    lower_q: npt.NDArray[np.float64],
    worlds: Sequence[World],
    settings: HigherTraining,
    jitter: StartJitter | None = None,
    threads: int = 0,
    progress: Callable[[int, int, float], None] | None = None,
    robot: RobotChoice = "seed",
    hold_heading: bool = False,
) -> tuple[HigherLevel, list[EpisodeResult]]:
    """Trains the higher level of each world with the lower level fixed.

    Args:
        lower_q: The lower-level tables.
        worlds: The target worlds (each gets its own higher-level table).
        settings: Episodes, robots per world, exploration.
        jitter: Start jitter of the episodes (the default :class:`StartJitter`).
        threads: Worker threads of the batch.
        progress: Called as ``progress(episodes_done, episodes_total, recent_success)``.
        robot: The robots (:data:`mazesim.batch.RobotChoice`), handed to the batch as given.
        hold_heading: The lower level holds its heading where blind
            (the core's ``navigator::heading_hold``), as the navigator was trained.

    Returns:
        The higher level and the training episodes' results.
    """
    world_of_env = np.repeat(np.arange(len(worlds)), settings.envs_per_world)
    nav = EpisodeBatch(
        worlds,
        world_of_env,
        seed=settings.seed,
        stream="higher/episode",
        jitter=jitter,
        max_steps=settings.max_steps,
        threads=threads,
        robot=robot,
    )
    level = HigherLevel([checkpoint_ids(world) for world in worlds])
    learner = HigherLearner(level, nav.num_envs)
    rng = stream(settings.seed, "higher/explore")
    started = np.zeros(len(worlds), dtype=np.int64)
    last_choice: dict[str, npt.NDArray[np.int64]] = {
        "robots": np.zeros(0, dtype=np.int64),
        "options": np.zeros(0, dtype=np.int64),
    }

    def choose(
        robots: npt.NDArray[np.int64], states: npt.NDArray[np.int64]
    ) -> npt.NDArray[np.int64]:
        epsilon = settings.epsilon(started[nav.world_of_env[robots]])
        explore = rng.random(robots.size) < epsilon
        random_options = rng.integers(0, level.q.shape[-1], robots.size)
        options = np.where(explore, random_options, level.choose(states))
        learner.decide(robots, states, options)
        last_choice["robots"], last_choice["options"] = robots, options
        return options

    policy = HierarchicalPolicy(
        lower_q, level, world_of_env, chooser=choose, hold_heading=hold_heading
    )
    total = len(worlds) * settings.episodes_per_world
    finished: list[bool] = []

    def watch(
        batch: EpisodeBatch,
        actions: npt.NDArray[np.int64],
        arrived: npt.NDArray[np.bool_],
        out_of_time: npt.NDArray[np.bool_],
    ) -> None:
        learner.reward(STEP_REWARD + CONTACT_REWARD * batch.colliding + GOAL_REWARD * arrived)

    def on_end(robots: npt.NDArray[np.int64], arrived: npt.NDArray[np.bool_]) -> None:
        learner.finish(robots)
        learner.forget(robots)
        np.add.at(started, nav.world_of_env[robots], 1)
        finished.extend(bool(a) for a in arrived)
        if progress is not None:
            recent = finished[-200:]
            progress(len(finished), total, sum(recent) / len(recent))

    def decisions_of() -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]:
        robots, options = last_choice["robots"], last_choice["options"]
        last_choice["robots"] = np.zeros(0, dtype=np.int64)
        last_choice["options"] = np.zeros(0, dtype=np.int64)
        return robots, options

    results = run_episodes(nav, policy, settings.episodes_per_world, watch, on_end, decisions_of)
    return level, results
