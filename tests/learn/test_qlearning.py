"""Tabular Q-learning: a batch of updates in the core against a loop of scalar updates."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mazesim.errors import InvalidArgumentError
from mazesim.learn.qlearning import (
    LearningRate,
    batch_update,
    epsilon_greedy,
    greedy,
)


def learning_rates(visits: object, rate: LearningRate) -> object:
    """The learning rate of the update that follows ``visits`` earlier updates of a pair."""
    counts = np.asarray(visits, dtype=np.float64)
    return np.maximum(rate.floor, rate.initial * (counts + 1.0) ** -rate.power)


def test_one_batch_update_equals_the_formula() -> None:
    q = np.array([[1.0, 2.0], [3.0, 4.0]])
    visits = np.zeros((2, 2), dtype=np.int64)
    rate = LearningRate(initial=0.5, floor=0.02, power=0.5)
    batch_update(q, visits, [0], [1], [0.5], [1], [0.9], rate)
    assert q[0, 1] == pytest.approx(2.0 + 0.5 * (0.5 + 0.9 * 4.0 - 2.0))
    assert visits.tolist() == [[0, 1], [0, 0]]
    # The second visit of the pair learns at 0.5 / sqrt(2).
    before = q[0, 1]
    batch_update(q, visits, [0], [1], [1.0], [0], [0.0], rate)
    assert q[0, 1] == pytest.approx(before + 0.5 / np.sqrt(2.0) * (1.0 - before))


def loop_of_scalar_updates(q, visits, states, actions, rewards, next_states, bootstrap, rate):
    """The reference: scalar updates in environment order, targets from the table before."""
    before = q.copy()
    for i in range(len(states)):
        target = rewards[i] + bootstrap[i] * before[next_states[i]].max()
        alpha = learning_rates(visits[states[i], actions[i]], rate)
        q[states[i], actions[i]] += alpha * (target - q[states[i], actions[i]])
        visits[states[i], actions[i]] += 1


@pytest.mark.parametrize("seed", range(5))
def test_vectorised_update_equals_a_loop_with_duplicate_pairs(seed: int) -> None:
    rng = np.random.default_rng(seed)
    q = rng.normal(size=(6, 3))
    visits = rng.integers(0, 4, size=(6, 3))
    count = 300  # 18 pairs: every pair is hit many times in the one batch
    states = rng.integers(0, 6, count)
    actions = rng.integers(0, 3, count)
    states[:50], actions[:50] = 2, 1  # and one pair 50+ times
    rewards = rng.normal(size=count)
    next_states = rng.integers(0, 6, count)
    bootstrap = np.where(rng.random(count) < 0.2, 0.0, 0.99 ** rng.integers(1, 12, count))
    rate = LearningRate(initial=0.5, floor=0.05, power=0.6)
    q_loop, visits_loop = q.copy(), visits.copy()
    loop_of_scalar_updates(
        q_loop, visits_loop, states, actions, rewards, next_states, bootstrap, rate
    )
    batch_update(q, visits, states, actions, rewards, next_states, bootstrap, rate)
    np.testing.assert_allclose(q, q_loop, rtol=1e-12, atol=1e-12)
    assert np.array_equal(visits, visits_loop)


def test_a_thousand_envs_on_one_pair_do_not_diverge() -> None:
    q = np.zeros((1, 1))
    visits = np.zeros((1, 1), dtype=np.int64)
    batch_update(q, visits, np.zeros(1000), np.zeros(1000), np.ones(1000), np.zeros(1000), 0.0,
                 LearningRate())  # fmt: skip
    assert q[0, 0] == pytest.approx(1.0)
    assert visits[0, 0] == 1000


def test_batch_update_refuses_mismatched_inputs() -> None:
    q = np.zeros((2, 2))
    visits = np.zeros((2, 2), dtype=np.int64)
    with pytest.raises(InvalidArgumentError, match="as many actions"):
        batch_update(q, visits, [0, 1], [0], [0.0, 0.0], [0, 0], 0.9, LearningRate())
    with pytest.raises(InvalidArgumentError, match="states as whole numbers from 0 to 1, found 2"):
        batch_update(q, visits, [2], [0], [0.0], [0], 0.9, LearningRate())


def test_greedy_and_epsilon_greedy() -> None:
    q = np.array([[0.0, 0.0, 0.0], [0.0, 2.0, 2.0], [-1.0, -3.0, 5.0]])
    assert greedy(q, [0, 1, 2]).tolist() == [0, 1, 2]  # ties go to the lowest index
    rng = np.random.default_rng(0)
    assert epsilon_greedy(q, [0, 1, 2], 0.0, rng).tolist() == [0, 1, 2]
    first = epsilon_greedy(q, np.zeros(50, int), 1.0, np.random.default_rng(7))
    second = epsilon_greedy(q, np.zeros(50, int), 1.0, np.random.default_rng(7))
    assert np.array_equal(first, second) and len(set(first.tolist())) == 3


def test_greedy_and_targets_keep_to_the_allowed_actions() -> None:
    q = np.array([[0.0, 1.0, 9.0], [4.0, 2.0, 7.0]])
    allowed = np.array([True, True, False])
    assert greedy(q, [0, 1], allowed).tolist() == [1, 0]
    assert greedy(q, [0, 1]).tolist() == [2, 2]
    # One mask per state, broadcast against the rows.
    per_state = np.array([[True, True, False], [True, True, True]])
    assert greedy(q, [0, 1], per_state).tolist() == [1, 2]
    unmasked = q.copy()
    visits = np.zeros(q.shape, dtype=np.int64)
    batch_update(unmasked, visits.copy(), [1], [0], [0.0], [0], [1.0], LearningRate())
    batch_update(q, visits, [1], [0], [0.0], [0], [1.0], LearningRate(), allowed)
    # The next state's value is its best allowed action's (1.0), not 9.0.
    assert q[1, 0] == pytest.approx(4.0 + 0.5 * (1.0 - 4.0))
    assert unmasked[1, 0] == pytest.approx(4.0 + 0.5 * (9.0 - 4.0))


@pytest.mark.parametrize("seed", range(3))
def test_the_batch_update_is_the_loop_of_scalar_updates_exactly(seed: int) -> None:
    """With the rate computed as the core computes it (the C library's pow), the batch is the
    loop bit for bit, duplicates of a pair applied one after the other in the batch's order."""
    rng = np.random.default_rng(seed)
    q = rng.normal(size=(5, 4))
    visits = rng.integers(0, 30, size=(5, 4))
    count = 200
    states, actions = rng.integers(0, 5, count), rng.integers(0, 4, count)
    rewards, next_states = rng.normal(size=count), rng.integers(0, 5, count)
    bootstrap = np.where(rng.random(count) < 0.3, 0.0, 0.99 ** rng.integers(1, 9, count))
    allowed = np.array([True, False, True, True])
    rate = LearningRate(initial=0.5, floor=0.03, power=0.7)
    expected_q, expected_visits = q.copy(), visits.copy()
    before = q.copy()
    for i in range(count):
        best = before[next_states[i], allowed].max() if bootstrap[i] else 0.0
        target = rewards[i] + bootstrap[i] * best
        pair = states[i], actions[i]
        alpha = max(rate.floor, rate.initial * math.pow(expected_visits[pair] + 1.0, -rate.power))
        expected_q[pair] += alpha * (target - expected_q[pair])
        expected_visits[pair] += 1
    batch_update(q, visits, states, actions, rewards, next_states, bootstrap, rate, allowed)
    assert np.array_equal(q, expected_q)
    assert np.array_equal(visits, expected_visits)


def test_negative_visit_counts_are_refused_before_any_update() -> None:
    q = np.zeros((2, 2))
    visits = np.array([[0, -1], [0, 0]])
    with pytest.raises(InvalidArgumentError, match="visit counts of 0 or more"):
        batch_update(q, visits, [0], [0], [1.0], [1], [0.5], LearningRate())
    assert np.all(q == 0.0)


def test_the_core_update_names_a_negative_index_and_ignores_an_unread_next_state() -> None:
    from mazesim._core import q_batch_update

    q, visits = np.zeros((3, 2)), np.zeros((3, 2), dtype=np.int64)
    ones = np.ones(2, dtype=bool)

    def update(states: list[int], next_states: list[int], bootstrap: list[float]) -> None:
        transitions = {
            "states": np.array(states),
            "actions": np.array([0, 1]),
            "rewards": np.array([1.0, 2.0]),
            "next_states": np.array(next_states),
            "bootstrap": np.array(bootstrap),
        }
        q_batch_update(q, visits, transitions, ones, (0.5, 0.02, 0.5))

    with pytest.raises(InvalidArgumentError, match="states of 0 or more, found -4 at transition 1"):
        update([0, -4], [0, 0], [0.9, 0.9])
    with pytest.raises(InvalidArgumentError, match="next_states of 0 or more, found -1"):
        update([0, 1], [0, -1], [0.9, 0.9])
    assert visits.sum() == 0
    # An episode's end reads no next state, so any number there is as good as another.
    update([0, 1], [0, -1], [0.9, 0.0])
    assert q[1, 1] == 1.0 and visits.sum() == 2


def test_rewards_and_bootstrap_factors_out_of_range_are_refused_before_any_update() -> None:
    from mazesim.learn.higher import HigherLearner, HigherLevel

    q, visits = np.zeros((4, 3)), np.zeros((4, 3), dtype=np.int64)
    for factor in (5.0, -0.1, math.nan):  # gamma ** tau is in [0, 1]; 5 made the table diverge
        with pytest.raises(InvalidArgumentError, match="bootstrap factors in \\[0, 1\\]"):
            batch_update(q, visits, [0], [0], [1.0], [1], [factor], LearningRate())
    with pytest.raises(InvalidArgumentError, match="next_states as whole numbers, found 1.5"):
        batch_update(q, visits, [0], [0], [1.0], [1.5], [0.0], LearningRate())
    assert not q.any() and not visits.any()
    # An episode's end reads no next state: -1 there is taken, as the core takes it.
    batch_update(q, visits, [0], [0], [1.0], [-1], [0.0], LearningRate())
    assert q[0, 0] > 0.0
    learner = HigherLearner(HigherLevel([[1, 2]]), 2)
    with pytest.raises(InvalidArgumentError, match="expected finite rewards, found nan"):
        learner.reward([math.nan, 0.0])  # once stored, and refused only at the decision's end
    assert not learner.earned.any()
