"""Tabular Q-learning with epsilon-greedy exploration, one transition or a whole batch at once.

A Q-table is a float64 array of shape ``(states, actions)``. One Q-learning update of the
transition ``(s, a, r, s')`` is

    Q[s, a] <- Q[s, a] + alpha * (r + bootstrap * max_b Q[s', b] - Q[s, a])

where ``bootstrap`` is ``gamma`` for an ordinary step, ``gamma ** tau`` for a decision that lasted
``tau`` steps (an SMDP transition) and 0 when ``s'`` ends the episode. The learning rate of a
pair's n-th update is ``max(floor, initial * (n + 1) ** -power)`` (:class:`LearningRate`): a table
keeps the count of updates of each pair beside it.

:func:`batch_update` applies the transitions of N environments stepped together, in the core
(``mazesim._core.q_batch_update``). Its result is this loop of scalar updates, in environment
order::

    before = q.copy()
    for i in range(N):
        target = rewards[i] + bootstrap[i] * before[next_states[i]].max()
        alpha = max(rate.floor, rate.initial * (visits[states[i], actions[i]] + 1) ** -rate.power)
        q[states[i], actions[i]] += alpha * (target - q[states[i], actions[i]])
        visits[states[i], actions[i]] += 1

the N transitions happen at the same time, so their targets read the table as it was before
the batch, and when k environments hit the same state-action pair their updates are applied one
after the other, each at its own rate. Summing the k increments instead (``np.add.at`` of
``alpha * td_error``) would move ``Q`` by k times a step when thousands of environments share a
state, and diverge. The core computes the rate with the C library's ``pow``, which numpy's
vectorised power can differ from in the last bit, so the loop above matches it to rounding.

Greedy choices break ties towards the lowest action index, so an untried state (all zeros) drives
forward (action 0, ``00``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from mazesim._checks import MOST_ARRAY_VALUES
from mazesim._core import q_batch_update
from mazesim._sizes import index_array, number_array, whole_array
from mazesim.errors import InvalidArgumentError

__all__ = [
    "LearningRate",
    "batch_update",
    "best_allowed",
    "epsilon_greedy",
    "greedy",
]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]


@dataclass(frozen=True)
class LearningRate:
    """The learning rate of a pair's n-th update (n = 0, 1, ...):
    ``max(floor, initial * (n + 1) ** -power)``; rare pairs learn fast, common ones average."""

    initial: float = 0.5
    floor: float = 0.02
    power: float = 0.5

    def __post_init__(self) -> None:
        if not (0.0 < self.floor <= self.initial <= 0.5 and self.power >= 0.0):
            raise InvalidArgumentError(
                "expected 0 < floor <= initial <= 0.5 and power >= 0, found "
                f"initial={self.initial}, floor={self.floor}, power={self.power}"
            )


def best_allowed(values: FloatArray, allowed: npt.NDArray[np.bool_] | None = None) -> IntArray:
    """The index of the largest of each row of ``values`` (ties go to the lowest), among the
    ``allowed`` columns only when given (a boolean mask broadcast against ``values``)."""
    if allowed is not None:
        values = np.where(allowed, values, -np.inf)
    return np.argmax(values, axis=-1).astype(np.int64)


def greedy(
    q: FloatArray, states: npt.ArrayLike, allowed: npt.NDArray[np.bool_] | None = None
) -> IntArray:
    """The greedy action of each state (ties go to the lowest action index), among the
    ``allowed`` actions only when given (a boolean mask over the columns, or one mask per state
    broadcast against the rows).

    Raises:
        InvalidArgumentError: The rows asked for would hold more than ``MOST_ARRAY_VALUES`` values.
    """
    indices = index_array(states, "states", np.shape(q)[0])
    if indices.size * max(1, math.prod(np.shape(q)[1:])) > MOST_ARRAY_VALUES:
        raise InvalidArgumentError(
            f"greedy: expected states to ask for at most {MOST_ARRAY_VALUES} Q-values, found "
            f"{indices.size} states of {math.prod(np.shape(q)[1:])} values each"
        )
    return best_allowed(q[indices], allowed)


def epsilon_greedy(
    q: FloatArray, states: npt.ArrayLike, epsilon: float, rng: np.random.Generator
) -> IntArray:
    """Epsilon-greedy actions: a uniformly random action with probability ``epsilon``.

    The generator draws the same numbers whatever ``epsilon`` is (N uniforms, then N actions),
    so runs with different exploration rates stay in step.

    Args:
        q: The Q-table, ``(states, actions)``.
        states: (N,) state numbers.
        epsilon: The exploration rate in [0, 1].
        rng: The generator to draw from.

    Returns:
        (N,) action indices.
    """
    indices = index_array(states, "states", q.shape[0])
    explore = rng.random(indices.shape) < epsilon
    random_actions = rng.integers(0, q.shape[-1], size=indices.shape)
    return np.where(explore, random_actions, greedy(q, indices)).astype(np.int64)


def batch_update(
    q: FloatArray,
    visits: npt.NDArray[np.int64],
    states: npt.ArrayLike,
    actions: npt.ArrayLike,
    rewards: npt.ArrayLike,
    next_states: npt.ArrayLike,
    bootstrap: npt.ArrayLike,
    rate: LearningRate,
    allowed: npt.NDArray[np.bool_] | None = None,
) -> None:
    """Applies N Q-learning updates in place, as the module describes.

    Args:
        q: The Q-table, ``(states, actions)``, float64, C-contiguous; updated in place.
        visits: The table's update counts, same shape, int64; updated in place.
        states: (N,) states the actions were taken in.
        actions: (N,) actions taken.
        rewards: (N,) rewards received.
        next_states: (N,) states reached (ignored where ``bootstrap`` is 0).
        bootstrap: (N,) or scalar factor of ``max Q[s']``: ``gamma``, ``gamma ** tau``, or 0 at
            the end of an episode.
        rate: The learning-rate schedule.
        allowed: The actions the table's learner may take (a boolean mask over its columns; all
            by default): the value of a next state is the best of these.

    Raises:
        InvalidArgumentError: The arrays differ in length, a state or action is not a whole
            number inside the table, a reward is not finite or a bootstrap factor not in [0, 1].
    """
    if not (q.flags.c_contiguous and visits.flags.c_contiguous and visits.shape == q.shape):
        raise InvalidArgumentError("expected C-contiguous Q and visit tables of one shape")
    num_states, num_actions = q.shape
    state_array = index_array(states, "states", num_states).ravel()
    action_array = index_array(actions, "actions", num_actions).ravel()
    count = state_array.size
    # Whole numbers (1.5 is not a state); those an episode's end does not read (bootstrap 0)
    # may be any, the others the core checks are inside the table.
    following = whole_array(next_states, "next_states").ravel()
    if action_array.size != count or np.size(rewards) != count or following.size != count:
        raise InvalidArgumentError(
            f"expected as many actions, rewards and next_states as states ({count}), "
            f"found {action_array.size}, {np.size(rewards)} and {following.size}"
        )
    if count == 0:
        return
    reward_array = np.ascontiguousarray(number_array(rewards, "rewards").ravel())
    factors = np.ascontiguousarray(
        np.broadcast_to(
            number_array(bootstrap, "bootstrap", checked_after=True).ravel(),
            (count,),
        ),
        dtype=np.float64,
    )
    if not np.all((factors >= 0.0) & (factors <= 1.0)):  # NaN fails too
        found = factors[~((factors >= 0.0) & (factors <= 1.0))][0]
        raise InvalidArgumentError(
            f"expected bootstrap factors in [0, 1] (gamma, gamma ** tau or 0), found {found}"
        )
    mask = (
        np.ones(num_actions, dtype=bool)
        if allowed is None
        else np.ascontiguousarray(allowed, dtype=bool)
    )
    transitions = {
        "states": np.ascontiguousarray(state_array),
        "actions": np.ascontiguousarray(action_array),
        "rewards": reward_array,
        "next_states": following,
        "bootstrap": factors,
    }
    q_batch_update(q, visits, transitions, mask, (rate.initial, rate.floor, rate.power))
