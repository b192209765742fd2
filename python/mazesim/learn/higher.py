"""The higher level: SMDP Q-learning over (checkpoint, direction), choosing the sub-task.

The higher level acts only at a checkpoint event, when the robot has crossed a barcode: its
state is the checkpoint and the direction of the crossing (arrival: along the checkpoint's yaw,
towards the door it faces; departure: the other way), its options are the four sub-tasks. The
chosen sub-task runs until it ends (:mod:`mazesim.learn.subtasks`), then Corridors and Corners
drives until the next event; the whole stretch is one SMDP transition, learned as

    Q[h, o] <- Q[h, o] + alpha * (R + max_o' Q[h', o'] - Q[h, o])

with ``R`` the rewards summed over the stretch (undiscounted: the task is episodic and every step
costs) and ``h'`` the next event's state; reaching the goal ends the episode (no ``Q[h']``), and so
does running out of time.

Rewards: :data:`STEP_REWARD` each control step, :data:`CONTACT_REWARD` each step in contact with
a wall, :data:`GOAL_REWARD` on reaching the goal. All values start at 0, above what any stretch
earns without the goal, so every option of a state is tried before any is trusted.

One :class:`HigherLevel` may hold the tables of several worlds (one per world, side by side), so
the higher levels of many mazes learn in one batch.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from mazesim._sizes import index_array, number_array, whole_array
from mazesim.errors import InvalidArgumentError
from mazesim.learn import qlearning
from mazesim.learn.subtasks import NUM_SUBTASKS

#: The largest checkpoint id a navigator's tables hold (a world's ids run from 1).
MAX_CHECKPOINT_ID = 65535

__all__ = [
    "CONTACT_REWARD",
    "GOAL_REWARD",
    "HIGHER_RATE",
    "STEP_REWARD",
    "HigherLearner",
    "HigherLevel",
    "MAX_CHECKPOINT_ID",
    "event_state_names",
]

#: Reward of each control step.
STEP_REWARD = -0.01
#: Reward of each control step in contact with a wall.
CONTACT_REWARD = -5.0
#: Reward on reaching the goal.
GOAL_REWARD = 100.0
#: Learning rate of the higher level (few, decisive updates).
HIGHER_RATE = qlearning.LearningRate(initial=0.5, floor=0.1, power=0.5)


def event_state_names(checkpoint_ids: Sequence[int]) -> list[str]:
    """Names of the higher-level states of one world, in table order (``"+3"``, ``"-3"``...)."""
    names = []
    for checkpoint in checkpoint_ids:
        names += [f"+{checkpoint}", f"-{checkpoint}"]
    return names


class HigherLevel:
    """The higher-level tables of one or more worlds.

    State ``2 * k`` of a world is arriving at its k-th checkpoint (in id order), ``2 * k + 1``
    departing from it.

    Args:
        checkpoint_ids: The checkpoint ids of each world.
        q: The values, ``(worlds, states, 4)``; zeros by default.
        visits: The update counts, same shape; zeros by default.

    Raises:
        InvalidArgumentError: The tables have the wrong shape, a checkpoint id is not a whole
            number from 1 to :data:`MAX_CHECKPOINT_ID`, or a visit count is not a whole number
            of 0 or more.
    """

    def __init__(
        self,
        checkpoint_ids: Sequence[Sequence[int]],
        q: npt.ArrayLike | None = None,
        visits: npt.ArrayLike | None = None,
    ) -> None:
        self.checkpoint_ids = [
            sorted(whole_array(ids, "checkpoint_ids", 1, MAX_CHECKPOINT_ID).ravel().tolist())
            for ids in checkpoint_ids
        ]
        if not self.checkpoint_ids:
            raise InvalidArgumentError("expected the checkpoints of at least one world")
        self.num_states = max(1, 2 * max(len(ids) for ids in self.checkpoint_ids))
        shape = (len(self.checkpoint_ids), self.num_states, NUM_SUBTASKS)
        self.q = np.zeros(shape) if q is None else np.array(number_array(q, "q"))
        self.visits = (
            np.zeros(shape, dtype=np.int64)
            if visits is None
            else np.array(whole_array(visits, "visits", low=0))
        )
        if self.q.shape != shape or self.visits.shape != shape:
            raise InvalidArgumentError(
                f"expected higher-level tables of shape {shape}, found {self.q.shape} "
                f"and {self.visits.shape}"
            )
        largest = max((max(ids) for ids in self.checkpoint_ids if ids), default=0)
        self._index = np.full((len(self.checkpoint_ids), largest + 1), -1, dtype=np.int64)
        for world, ids in enumerate(self.checkpoint_ids):
            for place, checkpoint in enumerate(ids):
                self._index[world, checkpoint] = place

    def states(self, worlds: npt.ArrayLike, events: npt.ArrayLike) -> npt.NDArray[np.int64]:
        """Flat state numbers (``world * num_states + state``) of events; -1 for an unknown id."""
        world = index_array(worlds, "worlds", len(self.checkpoint_ids))
        event = whole_array(events, "events")
        checkpoint = np.abs(event)
        known = (event != 0) & (checkpoint < self._index.shape[1])
        place = np.where(known, self._index[world, np.where(known, checkpoint, 0)], -1)
        state = 2 * place + (event < 0)
        return np.where(place >= 0, world * self.num_states + state, -1)

    def flat_q(self) -> npt.NDArray[np.float64]:
        """The values as one ``(worlds * states, 4)`` table (a view)."""
        return self.q.reshape(-1, NUM_SUBTASKS)

    def choose(
        self,
        states: npt.ArrayLike,
        epsilon: float = 0.0,
        rng: np.random.Generator | None = None,
    ) -> npt.NDArray[np.int64]:
        """Sub-tasks for flat states (greedy, or epsilon-greedy with ``rng``)."""
        table = self.flat_q()
        if rng is None or epsilon <= 0.0:
            return qlearning.greedy(table, states)
        return qlearning.epsilon_greedy(table, states, epsilon, rng)


class HigherLearner:
    """SMDP bookkeeping of N robots: the open decision of each and what it has earned so far.

    Args:
        level: The tables to learn.
        num_envs: Number of robots.
    """

    def __init__(self, level: HigherLevel, num_envs: int) -> None:
        self.level = level
        self.state = np.full(num_envs, -1, dtype=np.int64)
        self.option = np.zeros(num_envs, dtype=np.int64)
        self.earned = np.zeros(num_envs, dtype=np.float64)

    def reward(self, rewards: npt.ArrayLike) -> None:
        """Adds one step's rewards to the open decisions.

        Raises:
            InvalidArgumentError: A reward is not finite (it would reach the table at the
                decision's end), or there is not one per robot.
        """
        values = number_array(rewards, "rewards", checked_after=True)
        if not np.all(np.isfinite(values)):
            found = values[~np.isfinite(values)].flat[0]
            raise InvalidArgumentError(f"expected finite rewards, found {found}")
        self.earned += values

    def decide(self, envs: npt.ArrayLike, states: npt.ArrayLike, options: npt.ArrayLike) -> None:
        """Closes the open decisions of ``envs`` (bootstrapping on ``states``) and opens new ones.

        Robots whose event is unknown (state -1) close nothing and keep their decision open.
        """
        robots = index_array(envs, "envs", self.state.size)
        new_states = whole_array(states, "states", -1, self.level.q.size // NUM_SUBTASKS - 1)
        known = new_states >= 0
        robots, new_states = robots[known], new_states[known]
        chosen = index_array(options, "options", NUM_SUBTASKS)[known]
        open_ = self.state[robots] >= 0
        self._update(robots[open_], new_states[open_], bootstrap=1.0)
        self.state[robots] = new_states
        self.option[robots] = chosen
        self.earned[robots] = 0.0

    def finish(self, envs: npt.ArrayLike) -> None:
        """Ends the episodes of ``envs``: their open decisions learn what they earned, no more."""
        robots = index_array(envs, "envs", self.state.size)
        robots = robots[self.state[robots] >= 0]
        self._update(robots, np.zeros(robots.size, dtype=np.int64), bootstrap=0.0)
        self.state[robots] = -1
        self.earned[robots] = 0.0

    def forget(self, envs: npt.ArrayLike) -> None:
        """Drops the open decisions of ``envs`` without learning (a fresh episode)."""
        robots = index_array(envs, "envs", self.state.size)
        self.state[robots] = -1
        self.earned[robots] = 0.0

    def _update(
        self, robots: npt.NDArray[np.int64], next_states: npt.NDArray[np.int64], bootstrap: float
    ) -> None:
        if robots.size == 0:
            return
        qlearning.batch_update(
            self.level.flat_q(),
            self.level.visits.reshape(-1, NUM_SUBTASKS),
            self.state[robots],
            self.option[robots],
            self.earned[robots],
            next_states,
            np.full(robots.size, bootstrap),
            HIGHER_RATE,
        )
