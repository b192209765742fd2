"""Tabular Q-learning with epsilon-greedy exploration, one transition or a whole batch at once.

A Q-table is a float64 array of shape ``(states, actions)``. One Q-learning update of the
transition ``(s, a, r, s')`` is

    Q[s, a] <- Q[s, a] + alpha * (r + bootstrap * max_b Q[s', b] - Q[s, a])

where ``bootstrap`` is ``gamma`` for an ordinary step, ``gamma ** tau`` for a sub-task that lasted
``tau`` steps (the higher level's SMDP update) and 0 when ``s'`` ends the episode.

:func:`batch_update` applies the transitions of N environments stepped together. Its result
equals this loop of scalar updates, in environment order::

    before = q.copy()
    for i in range(N):
        target = rewards[i] + bootstrap[i] * before[next_states[i]].max()
        q[states[i], actions[i]] += alpha * (target - q[states[i], actions[i]])

up to floating-point rounding (relative differences of order 1e-15): the N transitions happen at
the same time, so their targets read the table as it was before the batch, and when k
environments hit the same state-action pair their updates are applied one after the other, as
``Q <- (1 - alpha)^k Q + sum_j alpha (1 - alpha)^(k-1-j) target_j``. Summing the k increments
instead (``np.add.at`` of ``alpha * td_error``) would move ``Q`` by k times a step when thousands
of environments share a state, and diverge.

Greedy choices break ties towards the lowest action index, so an untried state (all zeros) drives
forward (action 0, ``00``).
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from mazesim.errors import InvalidArgumentError

__all__ = [
    "batch_update",
    "epsilon_greedy",
    "greedy",
    "scalar_update",
    "td_targets",
]

FloatArray = npt.NDArray[np.float64]
IntArray = npt.NDArray[np.int64]


def greedy(q: FloatArray, states: npt.ArrayLike) -> IntArray:
    """The greedy action of each state (ties go to the lowest action index)."""
    return np.argmax(q[np.asarray(states, dtype=np.int64)], axis=-1).astype(np.int64)


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
    indices = np.asarray(states, dtype=np.int64)
    explore = rng.random(indices.shape) < epsilon
    random_actions = rng.integers(0, q.shape[-1], size=indices.shape)
    return np.where(explore, random_actions, greedy(q, indices)).astype(np.int64)


def scalar_update(
    q: FloatArray,
    state: int,
    action: int,
    reward: float,
    next_state: int,
    bootstrap: float,
    alpha: float,
) -> None:
    """One Q-learning update in place (see the module's formula)."""
    target = reward + bootstrap * float(np.max(q[next_state])) if bootstrap else reward
    q[state, action] += alpha * (target - q[state, action])


def td_targets(
    q: FloatArray,
    rewards: npt.ArrayLike,
    next_states: npt.ArrayLike,
    bootstrap: npt.ArrayLike,
) -> FloatArray:
    """The targets ``r + bootstrap * max_b Q[s', b]`` of N transitions (0 * max where bootstrap is
    0, so a terminal next state is never read)."""
    rewards_array = np.asarray(rewards, dtype=np.float64)
    factors = np.broadcast_to(np.asarray(bootstrap, dtype=np.float64), rewards_array.shape)
    following = np.asarray(next_states, dtype=np.int64)
    best = np.zeros_like(rewards_array)
    live = factors != 0.0
    best[live] = q[following[live]].max(axis=-1)
    return rewards_array + factors * best


def batch_update(
    q: FloatArray,
    states: npt.ArrayLike,
    actions: npt.ArrayLike,
    rewards: npt.ArrayLike,
    next_states: npt.ArrayLike,
    bootstrap: npt.ArrayLike,
    alpha: float,
) -> None:
    """Applies N Q-learning updates in place, as the module describes.

    Args:
        q: The Q-table, ``(states, actions)``, float64, updated in place.
        states: (N,) states the actions were taken in.
        actions: (N,) actions taken.
        rewards: (N,) rewards received.
        next_states: (N,) states reached (ignored where ``bootstrap`` is 0).
        bootstrap: (N,) or scalar factor of ``max Q[s']``: ``gamma``, ``gamma ** tau``, or 0 at
            the end of an episode.
        alpha: The learning rate in [0, 1].

    Raises:
        InvalidArgumentError: The arrays differ in length, or an index is out of the table.
    """
    state_array = np.asarray(states, dtype=np.int64).ravel()
    action_array = np.asarray(actions, dtype=np.int64).ravel()
    count = state_array.size
    if action_array.size != count or np.size(rewards) != count:
        raise InvalidArgumentError(
            f"expected as many actions and rewards as states ({count}), "
            f"found {action_array.size} and {np.size(rewards)}"
        )
    if count == 0:
        return
    num_states, num_actions = q.shape
    if state_array.min() < 0 or state_array.max() >= num_states:
        raise InvalidArgumentError(f"expected states in [0, {num_states}), found out of range")
    if action_array.min() < 0 or action_array.max() >= num_actions:
        raise InvalidArgumentError(f"expected actions in [0, {num_actions}), found out of range")
    targets = td_targets(q, np.ravel(rewards), np.ravel(next_states), np.ravel(bootstrap))
    keys = state_array * num_actions + action_array
    order = np.argsort(keys, kind="stable")
    sorted_keys = keys[order]
    starts_group = np.ones(count, dtype=bool)
    starts_group[1:] = sorted_keys[1:] != sorted_keys[:-1]
    group = np.cumsum(starts_group) - 1
    group_start = np.flatnonzero(starts_group)
    group_size = np.diff(np.append(group_start, count))
    position = np.arange(count) - group_start[group]
    keep = 1.0 - alpha
    weights = alpha * keep ** (group_size[group] - 1 - position)
    moved = np.bincount(group, weights=weights * targets[order], minlength=group_start.size)
    flat = q.reshape(-1)
    unique_keys = sorted_keys[group_start]
    flat[unique_keys] = keep**group_size * flat[unique_keys] + moved
