"""The benchmark's workloads: the rules behind ``mazesim bench --workload``."""

from __future__ import annotations

import numpy as np
import pytest

from mazesim.benchmark import WORKLOADS, braitenberg, make_workload
from mazesim.benchmark.workloads import (
    CONTACT_AVOID_STEPS,
    CONTACT_PUSH_STEPS,
    MAX_WHEEL_SPEED,
    braitenberg_one,
    seek_walls,
)
from mazesim.errors import UnknownNameError


def test_workloads_are_named() -> None:
    assert list(WORKLOADS) == ["braitenberg", "contact", "random"]
    with pytest.raises(UnknownNameError, match="braitenberg, contact, random.*'push'"):
        make_workload("push", 4)


def test_braitenberg_turns_away_from_an_obstacle_on_the_right() -> None:
    ps = np.full((1, 8), 67.19, np.float32)
    ps[0, 1] = 1000.0  # front right
    left, right = braitenberg(ps, np.zeros((1, 2), np.float32))[0]
    assert right > left  # turns left


def test_seeking_turns_towards_a_wall_at_full_speed() -> None:
    ps = np.full((2, 8), 67.19, np.float32)
    ps[1, 6] = ps[1, 7] = 1000.0  # a wall front left
    (left_free, right_free), (left_wall, right_wall) = seek_walls(ps, np.zeros((2, 2), np.float32))
    assert left_free == MAX_WHEEL_SPEED and right_free < left_free  # curves right
    assert right_wall == MAX_WHEEL_SPEED and left_wall < right_wall  # turns left, to the wall


def test_contact_workload_seeks_walls_for_its_push_phase() -> None:
    envs = 48
    workload = make_workload("contact", envs)
    period = CONTACT_PUSH_STEPS + CONTACT_AVOID_STEPS
    clear = np.full((envs, 11), 67.19, np.float32)  # nothing in sight: Braitenberg drives at 5
    pushing = np.zeros((period, envs), bool)
    for k in range(period):
        actions = workload.act(clear, np.zeros((envs, 2), np.float32))
        pushing[k] = (actions[:, 0] == np.float32(MAX_WHEEL_SPEED)) & (actions[:, 1] < 5.0)
    # Every env pushes for exactly its push phase in each period...
    assert (pushing.sum(axis=0) == CONTACT_PUSH_STEPS).all()
    # ... and the envs are spread over the phases, so each step pushes about the same share.
    share = pushing.mean(axis=1)
    expected = CONTACT_PUSH_STEPS / period
    assert np.abs(share - expected).max() <= 1.0 / envs + 1e-9


def test_random_workload_is_seeded_and_bounded() -> None:
    obs = np.zeros((64, 11), np.float32)

    def draws(seed: int) -> np.ndarray:
        workload = make_workload("random", 64, seed=seed)
        return np.stack([workload.act(obs, np.zeros((64, 2), np.float32)) for _ in range(20)])

    first, again, other = draws(3), draws(3), draws(4)
    assert np.array_equal(first, again)
    assert not np.array_equal(first, other)
    assert first.min() >= -MAX_WHEEL_SPEED and first.max() <= MAX_WHEEL_SPEED
    # Uniform over the whole range: both signs and both ends are reached.
    assert first.min() < -0.9 * MAX_WHEEL_SPEED and first.max() > 0.9 * MAX_WHEEL_SPEED


def test_vector_and_scalar_braitenberg_agree() -> None:
    rng = np.random.default_rng(0)
    ps = rng.uniform(60, 1500, size=(50, 8)).astype(np.float32)
    out = braitenberg(ps, np.zeros((50, 2), np.float32))
    for row, (left, right) in zip(ps, out):
        expected = np.clip(braitenberg_one(row.tolist()), -MAX_WHEEL_SPEED, MAX_WHEEL_SPEED)
        assert np.allclose([left, right], expected, atol=1e-4)


@pytest.mark.parametrize("actions", [-1, 0, 2**70, None, [0.0] * 8, "x", object(), np.float32(1)])
def test_an_action_buffer_that_is_not_an_array_is_refused_before_numpy_reads_it(
    actions: object,
) -> None:
    # numpy's generators read an ``out`` of another kind as an array without looking: the
    # random workload's fill of an int crashed the process (found by the fuzzed registry).
    from mazesim.errors import InvalidArgumentError, WrongTypeError

    with pytest.raises(WrongTypeError, match="actions"):
        make_workload("random", 4).act(np.zeros((4, 8), np.float32), actions)  # type: ignore[arg-type]
    for name in ("braitenberg", "contact"):
        with pytest.raises(InvalidArgumentError):
            make_workload(name, 4).act(np.zeros((4, 8), np.float32), actions)  # type: ignore[arg-type]
