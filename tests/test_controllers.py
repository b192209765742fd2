"""The report's Alg. 1 avoid-collision controller, on synthetic readings and in the arena."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import mazesim
from mazesim.controllers import AvoidCollision
from mazesim.errors import InvalidArgumentError

HALF = 0.5 * AvoidCollision.MAX_SPEED
STRAIGHT = (HALF, HALF)
TURN_RIGHT = (AvoidCollision.MAX_SPEED, 0.0)
TURN_LEFT = (0.0, AvoidCollision.MAX_SPEED)


def readings(**sensors: float) -> np.ndarray:
    """Eight readings of 60 (no obstacle) with some ``psK=value`` overrides."""
    values = np.full(8, 60.0)
    for name, value in sensors.items():
        values[int(name[2:])] = value
    return values


def test_constants_of_the_report() -> None:
    controller = AvoidCollision()
    assert AvoidCollision.MAX_SPEED == 6.28
    assert controller.threshold == 80.0


def test_no_obstacle_drives_straight_at_half_speed() -> None:
    assert AvoidCollision()(readings()) == pytest.approx(STRAIGHT)


@pytest.mark.parametrize("sensor", ["ps5", "ps6", "ps7"])
def test_obstacle_on_the_left_turns_right(sensor: str) -> None:
    assert AvoidCollision()(readings(**{sensor: 300.0})) == pytest.approx(TURN_RIGHT)


@pytest.mark.parametrize("sensor", ["ps0", "ps1", "ps2"])
def test_obstacle_on_the_right_turns_left(sensor: str) -> None:
    assert AvoidCollision()(readings(**{sensor: 300.0})) == pytest.approx(TURN_LEFT)


def test_left_obstacle_wins_when_both_sides_see_one() -> None:
    assert AvoidCollision()(readings(ps0=500.0, ps7=500.0)) == pytest.approx(TURN_RIGHT)


@pytest.mark.parametrize("sensor", ["ps3", "ps4"])
def test_rear_sensors_are_ignored(sensor: str) -> None:
    assert AvoidCollision()(readings(**{sensor: 4000.0})) == pytest.approx(STRAIGHT)


def test_threshold_is_strict() -> None:
    controller = AvoidCollision()
    assert controller(readings(ps0=80.0, ps7=80.0)) == pytest.approx(STRAIGHT)
    assert controller(readings(ps0=80.001)) == pytest.approx(TURN_LEFT)


def test_custom_threshold_and_speed() -> None:
    controller = AvoidCollision(threshold=200.0, max_speed=2.0)
    assert controller(readings(ps6=150.0)) == pytest.approx((1.0, 1.0))
    assert controller(readings(ps6=250.0)) == pytest.approx((2.0, 0.0))


@pytest.mark.parametrize("shape", [(7,), (9,), (2, 8), ()])
def test_wrong_number_of_readings_is_rejected(shape: tuple[int, ...]) -> None:
    with pytest.raises(InvalidArgumentError, match=r"\(8,\)"):
        AvoidCollision()(np.zeros(shape))


@pytest.mark.parametrize("shape", [(8,), (3, 7), (2, 8, 1)])
def test_batch_rejects_wrong_shapes(shape: tuple[int, ...]) -> None:
    with pytest.raises(InvalidArgumentError, match=r"\(N, 8\)"):
        AvoidCollision().batch(np.zeros(shape))


def _assert_batch_equals_rows(controller: AvoidCollision, batch: np.ndarray) -> None:
    wheel_speeds = controller.batch(batch)
    assert wheel_speeds.dtype == np.float32
    assert wheel_speeds.shape == (len(batch), 2)
    expected = np.array([controller(row) for row in batch], dtype=np.float32).reshape(-1, 2)
    np.testing.assert_array_equal(wheel_speeds, expected)


def test_batch_equals_per_row_calls() -> None:
    rng = np.random.default_rng(7)
    batch = rng.uniform(0.0, 200.0, size=(1000, 8))
    controller = AvoidCollision()
    _assert_batch_equals_rows(controller, batch)
    # All three outcomes occur in this sample, so the comparison covers each branch.
    outcomes = {tuple(row) for row in controller.batch(batch).tolist()}
    assert len(outcomes) == 3


def test_empty_batch() -> None:
    assert AvoidCollision().batch(np.zeros((0, 8))).shape == (0, 2)


@settings(max_examples=200, deadline=None)
@given(
    arrays(
        np.float32,
        st.tuples(st.integers(0, 12), st.just(8)),
        elements=st.floats(0.0, 4095.0, width=32),
    )
)
def test_batch_equals_per_row_calls_on_any_readings(batch: np.ndarray) -> None:
    _assert_batch_equals_rows(AvoidCollision(), batch)


def test_robot_keeps_moving_in_the_arena() -> None:
    simulator = mazesim.Simulator(mazesim.load_world("arena"), robot="e-puck", seed=0)
    controller = AvoidCollision()
    steps = math.ceil(60_000.0 / simulator.control_step_ms - 1e-9)
    positions = np.empty((steps, 2))
    for step in range(steps):
        left, right = controller(simulator.distance_sensors())
        simulator.step(left, right)
        positions[step] = simulator.pose[:2]
    assert simulator.time == pytest.approx(60.0, abs=simulator.control_step_ms / 1000.0)
    assert simulator.distance_travelled > 1.0
    # It explores: it is not circling on one spot, and it stays inside the walls.
    assert np.ptp(positions[:, 0]) > 0.2 or np.ptp(positions[:, 1]) > 0.2
    assert np.all(np.abs(positions) < 0.5)
