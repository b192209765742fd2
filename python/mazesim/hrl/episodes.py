"""Running navigation episodes with a navigator, learning or not, and what each episode did.

:func:`run_episodes` drives a :class:`mazesim.hrl.navigation.NavigationBatch` with any
:class:`Navigator` (the hierarchical policy, the flat baseline) until every world has run its
number of episodes, and returns one :class:`EpisodeResult` per episode. A ``watch`` callback sees
every step (training hooks rewards to it; evaluation records traces with it).
:func:`train_higher` is the higher level's training: episodes on the target worlds, the lower
level fixed, the sub-tasks chosen epsilon-greedily at checkpoint events.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np
import numpy.typing as npt

from mazesim._core import World
from mazesim.hrl.higher import (
    CONTACT_REWARD,
    GOAL_REWARD,
    STEP_REWARD,
    HigherLearner,
    HigherLevel,
)
from mazesim.hrl.mazes import checkpoint_ids
from mazesim.hrl.navigation import NavigationBatch, StartJitter
from mazesim.hrl.policy import HierarchicalPolicy

__all__ = [
    "EpisodeResult",
    "HigherTraining",
    "Navigator",
    "run_episodes",
    "train_higher",
]


class Navigator(Protocol):
    """What :func:`run_episodes` drives: N robots' controllers."""

    def reset(self, envs: npt.ArrayLike, poses: npt.ArrayLike) -> None: ...

    def act(
        self, observations: npt.ArrayLike, poses: npt.ArrayLike, events: npt.ArrayLike
    ) -> npt.NDArray[np.int64]: ...


@dataclass
class EpisodeResult:
    """One episode: where, which, and how it went."""

    world: int
    episode: int
    arrived: bool
    steps: int
    bumps: int
    contact_steps: int
    decisions: list[tuple[int, int]] = field(default_factory=list)


#: Called after every step with the batch, the actions, ``arrived`` and ``out_of_time``.
Watcher = Callable[
    [NavigationBatch, npt.NDArray[np.int64], npt.NDArray[np.bool_], npt.NDArray[np.bool_]], None
]


def run_episodes(
    nav: NavigationBatch,
    navigator: Navigator,
    episodes_per_world: int,
    watch: Watcher | None = None,
    on_end: Callable[[npt.NDArray[np.int64], npt.NDArray[np.bool_]], None] | None = None,
    decisions_of: Callable[[], tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]] | None = None,
) -> list[EpisodeResult]:
    """Runs ``episodes_per_world`` episodes in each world of ``nav``.

    Episode ``k`` of world ``w`` is numbered ``w * episodes_per_world + k``; its start jitter and
    noise seed follow from that number (see :class:`NavigationBatch`). Robots of a world take its
    episodes in turn; a robot whose world has none left waits (its steps are not counted).

    Args:
        nav: The robots and their worlds.
        navigator: The controller of all robots.
        episodes_per_world: Episodes to run in each world.
        watch: Called after every step (see :data:`Watcher`).
        on_end: Called with the robots whose episode ended and whether each arrived, before new
            episodes start on them.
        decisions_of: Returns ``(robots, sub-tasks)`` chosen at the last step, to log them with
            the checkpoint event that caused them.

    Returns:
        The results, in order of episode number.
    """
    count = nav.num_envs
    worlds = len(nav.worlds)
    next_episode = np.arange(worlds) * episodes_per_world
    last_episode = next_episode + episodes_per_world
    active = np.zeros(count, dtype=bool)
    results: dict[int, EpisodeResult] = {}
    decisions: dict[int, list[tuple[int, int]]] = {}

    def start(robots: npt.NDArray[np.int64]) -> None:
        starting = []
        numbers = []
        for env in robots:
            world = nav.world_of_env[env]
            if next_episode[world] < last_episode[world]:
                starting.append(env)
                numbers.append(next_episode[world])
                next_episode[world] += 1
        active[robots] = False
        if starting:
            chosen = np.array(starting, dtype=np.int64)
            nav.start(chosen, numbers)
            navigator.reset(chosen, nav.poses)
            active[chosen] = True
            for env in chosen:
                decisions[int(env)] = []

    start(np.arange(count))
    events = np.zeros(count, dtype=np.int64)
    while np.any(active):
        actions = navigator.act(nav.observations, nav.poses, events)
        if decisions_of is not None:
            robots, chosen = decisions_of()
            for env, option in zip(robots, chosen):
                if active[env]:
                    decisions[int(env)].append((int(events[env]), int(option)))
        arrived, out_of_time = nav.step(actions)
        arrived &= active
        out_of_time &= active
        events = nav.events.copy()
        if watch is not None:
            watch(nav, actions, arrived, out_of_time)
        ended = np.flatnonzero(arrived | out_of_time)
        if ended.size:
            if on_end is not None:
                on_end(ended, arrived[ended])
            bumps = nav.bumps()
            for env in ended:
                number = int(nav.episode[env])
                results[number] = EpisodeResult(
                    world=int(nav.world_of_env[env]),
                    episode=number,
                    arrived=bool(arrived[env]),
                    steps=int(nav.episode_steps[env]),
                    bumps=int(bumps[env]),
                    contact_steps=int(nav.contact_steps[env]),
                    decisions=decisions.pop(int(env)),
                )
            start(ended)
            events[ended] = 0
    return [results[number] for number in sorted(results)]


@dataclass(frozen=True)
class HigherTraining:
    """How the higher level trains on its worlds."""

    episodes_per_world: int = 200
    envs_per_world: int = 8
    epsilon_start: float = 0.2
    greedy_share: float = 0.3
    max_steps: int = 4000
    seed: int = 0

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
) -> tuple[HigherLevel, list[EpisodeResult]]:
    """Trains the higher level of each world with the lower level fixed.

    Args:
        lower_q: The lower-level tables.
        worlds: The target worlds (each gets its own higher-level table).
        settings: Episodes, robots per world, exploration.
        jitter: Start jitter of the episodes (the default :class:`StartJitter`).
        threads: Worker threads of the batch.
        progress: Called as ``progress(episodes_done, episodes_total, recent_success)``.

    Returns:
        The higher level and the training episodes' results.
    """
    world_of_env = np.repeat(np.arange(len(worlds)), settings.envs_per_world)
    nav = NavigationBatch(
        worlds,
        world_of_env,
        seed=settings.seed,
        jitter=jitter,
        max_steps=settings.max_steps,
        threads=threads,
    )
    level = HigherLevel([checkpoint_ids(world) for world in worlds])
    learner = HigherLearner(level, nav.num_envs)
    rng = np.random.default_rng([settings.seed, 2])
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

    policy = HierarchicalPolicy(lower_q, level, world_of_env, chooser=choose)
    total = len(worlds) * settings.episodes_per_world
    finished: list[bool] = []

    def watch(
        batch: NavigationBatch,
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
