"""The flat baseline, the package's one flat Q-learner: one Q-table over primitive actions,
trained on the target world directly (``mazesim train --flat``, the sweep's ``baseline``).

Without a hierarchy a tabular learner needs to know where it is in the maze, so its state is the
distance state of :mod:`mazesim.learn.discretise` together with the last checkpoint event seen in
the episode (none, or arrival / departure at each checkpoint): ``distance_state + 4096 * k``
with ``k = 0`` before any event and ``k = 1 + 2 * place + (departure)`` after one, so
``(1 + 2 * checkpoints) * 4096`` states. It learns with the same machinery as the sub-tasks
(decisions held until the state changes, the batch update of :mod:`mazesim.learn.qlearning`,
epsilon falling from 0.3 to 0 over the first 80% of the budget) on episodes of the target world
from its jittered start, for the same number of env-steps as the hierarchical run it is compared
with.

Rewards per control step (:class:`FlatConfig`'s defaults): ``10 * (metres driven forward)``,
``-0.02``, ``-2`` in contact with a wall, and ``+10`` on reaching the goal, which ends the
episode. Episodes that run out of time are cut short (not failed), as the sub-tasks' are.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from mazesim._core import World
from mazesim._seeding import stream
from mazesim._settings import MAX_COUNT, bounded, check_settings
from mazesim._sizes import index_array, whole_array
from mazesim.actions import ACTION_CODES
from mazesim.episodes import MAX_STEPS, EpisodeBatch
from mazesim.learn import qlearning
from mazesim.learn.discretise import (
    NUM_LEVELS,
    NUM_SENSORS,
    NUM_STATES,
    distances_and_levels,
    encode_state,
)
from mazesim.learn.policy import StepRecord
from mazesim.maze import checkpoint_ids

__all__ = [
    "FlatConfig",
    "FlatNavigator",
    "flat_table_rows",
    "train_flat",
]


@dataclass(frozen=True)
class FlatConfig:
    """The flat learner's settings; these defaults are the only ones (``mazesim train --flat``
    and the sweep's ``baseline`` trainer start from them).

    Attributes:
        gamma: Discount factor per control step.
        decision_steps: Longest a decision holds its action (it ends earlier when the state
            changes).
        epsilon_start: Exploration rate at the start, falling linearly to 0.
        greedy_share: Share of the budget at the end that is greedy.
        learning_rate: First learning rate of a state-action pair (falling with its updates as
            :class:`mazesim.learn.qlearning.LearningRate` says).
        progress_reward: Reward per metre driven forward.
        step_reward: Reward of each control step.
        contact_reward: Reward of each control step in contact with a wall.
        goal_reward: Reward on reaching the goal.
        max_steps: Control steps after which a training episode is cut short.
    """

    gamma: float = bounded(0.99, least=0.0, most=1.0)
    decision_steps: int = bounded(10, least=1, most=MAX_COUNT)
    epsilon_start: float = bounded(0.3, least=0.0, most=1.0)
    greedy_share: float = bounded(0.2, least=0.0, most=1.0)
    # The learning rate's own rule: 0 < floor <= initial <= 0.5.
    learning_rate: float = bounded(qlearning.LearningRate().initial, above=0.0, most=0.5)
    progress_reward: float = bounded(10.0)
    step_reward: float = bounded(-0.02)
    contact_reward: float = bounded(-2.0)
    goal_reward: float = bounded(10.0)
    max_steps: int = bounded(MAX_STEPS, least=1, most=MAX_COUNT)

    def __post_init__(self) -> None:
        check_settings(self)

    def rate(self) -> qlearning.LearningRate:
        """The learning-rate schedule: the default one, started at :attr:`learning_rate`."""
        default = qlearning.LearningRate()
        return qlearning.LearningRate(
            initial=self.learning_rate,
            floor=min(default.floor, self.learning_rate),
            power=default.power,
        )


def flat_table_rows(checkpoint_count: int) -> int:
    """Rows of the flat table of a world with that many checkpoints."""
    return (1 + 2 * checkpoint_count) * NUM_STATES


class FlatNavigator:
    """The flat baseline driving N robots (greedy, or epsilon-greedy while training).

    Args:
        q: The table, ``(flat_table_rows(len(checkpoint_ids)), 12)``.
        checkpoint_ids: The world's checkpoint ids.
        num_envs: Number of robots.
    """

    def __init__(self, q: npt.NDArray[np.float64], checkpoint_ids: list[int], num_envs: int):
        self.q = q
        self.checkpoint_ids = sorted(checkpoint_ids)
        largest = max(self.checkpoint_ids, default=0)
        self._place = np.full(largest + 1, -1, dtype=np.int64)
        for place, checkpoint in enumerate(self.checkpoint_ids):
            self._place[checkpoint] = place
        self.num_envs = num_envs
        self.context = np.zeros(num_envs, dtype=np.int64)
        self.record = StepRecord(num_envs)

    def reset(self, envs: npt.ArrayLike, poses: npt.ArrayLike) -> None:
        """Forgets the last checkpoint event of robots ``envs``."""
        self.context[index_array(envs, "envs", self.num_envs)] = 0

    def states(self, observations: npt.ArrayLike, events: npt.ArrayLike) -> npt.NDArray[np.int64]:
        """Notes the events and returns each robot's state."""
        rows = np.asarray(observations)
        distances, levels = distances_and_levels(rows[:, :NUM_SENSORS])
        states = self.states_from_levels(levels, events)
        self.record.distances_cm = distances
        return states

    def states_from_levels(
        self, levels: npt.ArrayLike, events: npt.ArrayLike
    ) -> npt.NDArray[np.int64]:
        """Notes the events and returns each robot's state from its (N, 6) levels."""
        event = whole_array(events, "events")
        checkpoint = np.abs(event)
        known = (event != 0) & (checkpoint < self._place.size)
        place = np.where(known, self._place[np.where(known, checkpoint, 0)], -1)
        seen = place >= 0
        self.context[seen] = 1 + 2 * place[seen] + (event[seen] < 0)
        record = self.record
        record.levels = index_array(levels, "levels", NUM_LEVELS)
        record.state = np.asarray(encode_state(record.levels))
        record.event = event
        return record.state + NUM_STATES * self.context

    def act(
        self, observations: npt.ArrayLike, poses: npt.ArrayLike, events: npt.ArrayLike
    ) -> npt.NDArray[np.int64]:
        """Greedy actions."""
        action = qlearning.greedy(self.q, self.states(observations, events))
        self.record.action = action
        return action


def train_flat(
    world: World,
    env_steps: int,
    num_envs: int = 256,
    seed: int = 0,
    threads: int = 0,
    progress: Callable[[int, int, float], None] | None = None,
    config: FlatConfig | None = None,
) -> tuple[npt.NDArray[np.float64], list[bool]]:
    """Trains the flat baseline on ``world`` for ``env_steps`` env-steps.

    Its episodes run through the episode layer on the ``flat/episode`` stream; exploration draws
    from ``flat/explore`` (:mod:`mazesim._seeding`). ``config`` defaults to :class:`FlatConfig`.

    Returns:
        The table and, per finished episode, whether it reached the goal.
    """
    ids = checkpoint_ids(world)
    rows = flat_table_rows(len(ids))
    q = np.zeros((rows, len(ACTION_CODES)))
    visits = np.zeros(q.shape, dtype=np.int64)
    config = config if config is not None else FlatConfig()
    rate = config.rate()
    nav = EpisodeBatch(
        [world],
        np.zeros(num_envs, dtype=np.int64),
        seed=seed,
        stream="flat/episode",
        max_steps=config.max_steps,
        threads=threads,
    )
    navigator = FlatNavigator(q, ids, num_envs)
    rng = stream(seed, "flat/explore")
    everyone = np.arange(num_envs)
    next_episode = num_envs
    nav.start(everyone, everyone)
    navigator.reset(everyone, nav.poses)
    events = np.zeros(num_envs, dtype=np.int64)
    state = navigator.states(nav.observations, events)
    action = np.zeros(num_envs, dtype=np.int64)
    earned = np.zeros(num_envs)
    discount = np.ones(num_envs)
    held = np.zeros(num_envs, dtype=np.int64)
    deciding = np.ones(num_envs, dtype=bool)
    outcomes: list[bool] = []
    total_steps = max(1, math.ceil(env_steps / num_envs))
    exploring = max(1.0, total_steps * (1.0 - config.greedy_share))
    for step in range(total_steps):
        epsilon = max(0.0, config.epsilon_start * (1.0 - step / exploring))
        explore = rng.random(num_envs) < epsilon
        random_action = rng.integers(0, len(ACTION_CODES), num_envs)
        chosen = np.where(explore, random_action, qlearning.greedy(q, state))
        action = np.where(deciding, chosen, action)
        earned[deciding] = 0.0
        discount[deciding] = 1.0
        held[deciding] = 0
        before = nav.poses.astype(np.float64)
        arrived, out_of_time = nav.step(action)
        after = nav.poses.astype(np.float64)
        forward = (after[:, 0] - before[:, 0]) * np.cos(before[:, 2]) + (
            after[:, 1] - before[:, 1]
        ) * np.sin(before[:, 2])
        reward = (
            config.progress_reward * forward
            + config.step_reward
            + config.contact_reward * nav.colliding
            + config.goal_reward * arrived
        )
        next_state = navigator.states(nav.observations, nav.events)
        earned += discount * reward
        discount *= config.gamma
        held += 1
        ended = arrived | out_of_time
        deciding = ended | (next_state != state) | (held >= config.decision_steps)
        learners = np.flatnonzero(deciding)
        qlearning.batch_update(
            q,
            visits,
            state[learners],
            action[learners],
            earned[learners],
            next_state[learners],
            np.where(arrived, 0.0, discount)[learners],
            rate,
        )
        state = next_state
        finished = np.flatnonzero(ended)
        if finished.size:
            outcomes.extend(bool(a) for a in arrived[finished])
            numbers = np.arange(next_episode, next_episode + finished.size)
            next_episode += finished.size
            nav.start(finished, numbers)
            navigator.reset(finished, nav.poses)
            state[finished] = navigator.states(nav.observations, np.zeros(num_envs, np.int64))[
                finished
            ]
            if progress is not None:
                recent = outcomes[-200:]
                progress(step + 1, total_steps, sum(recent) / len(recent))
    return q, outcomes
