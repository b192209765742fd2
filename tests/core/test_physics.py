"""Physics acceptance through the Python API: kinematics, clamping, contacts, determinism."""

from __future__ import annotations

import math

import numpy as np
import pytest

import mazesim
from mazesim import InvalidActionError, MazesimError, Simulator, World

R = 0.02  # the e-puck as Webots simulates it (robots/e-puck.toml)
AXLE = 0.05685


def world(body: str = "", step_ms: float = 10.0) -> World:
    return World.from_toml(
        f'format = "mazesim-world"\nversion = 1\nbasic_time_step_ms = {step_ms}\n{body}',
        "test.toml",
    )


@pytest.mark.parametrize("w", [1.0, 4.0, 6.28])
def test_straight_drive_covers_r_w_per_second(w: float) -> None:
    sim = Simulator(world(), seed=1, noise=False)
    for _ in range(100):
        sim.step(w, w)
    x, y, yaw = sim.pose
    assert sim.time == pytest.approx(1.0)
    assert x == pytest.approx(R * w, rel=0.01)
    assert abs(y) < 1e-5 and abs(yaw) < 1e-5


def test_spinning_turns_at_2rw_over_axle() -> None:
    sim = Simulator(world(), seed=1, noise=False)
    turned, last = 0.0, sim.pose[2]
    for _ in range(100):
        sim.step(-3.0, 3.0)
        yaw = sim.pose[2]
        turned += (yaw - last + math.pi) % (2 * math.pi) - math.pi
        last = yaw
    assert turned == pytest.approx(2 * R * 3.0 / AXLE, rel=0.01)


def test_speeds_are_clamped_to_the_motor_limit() -> None:
    sim = Simulator(world(), noise=False)
    sim.step(50.0, -7.0)
    assert sim.wheel_speeds == pytest.approx((6.28, -6.28))


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_nan_and_infinite_speeds_raise(bad: float) -> None:
    sim = Simulator(world(), noise=False)
    with pytest.raises(InvalidActionError, match="finite"):
        sim.step(bad, 1.0)
    with pytest.raises(MazesimError):
        sim.step(1.0, bad)
    assert sim.steps == 0


def test_driving_into_a_wall_for_10_s_stays_within_a_millimetre() -> None:
    sim = Simulator(
        world("[[walls]]\ncenter = [0.3, 0.0]\nsize = [0.01, 1.0]\n", step_ms=32.0), noise=False
    )
    worst = math.inf
    for _ in range(int(10 / 0.032)):
        sim.step(6.28, 6.28)
        worst = min(worst, sim.wall_clearance)
    assert worst > -0.001
    assert sim.collisions >= 1
    assert sim.colliding
    assert sim.pose[0] < 0.295


def test_step_observe_reports_the_contact_and_the_collisions_the_getters_give() -> None:
    sim = Simulator(
        world("[[walls]]\ncenter = [0.3, 0.0]\nsize = [0.01, 1.0]\n", step_ms=32.0), noise=False
    )
    width = len(sim.distance_sensors()) + len(sim.ground_sensors())
    low = np.full(width, -np.inf, dtype=np.float32)
    high = np.full(width, np.inf, dtype=np.float32)
    seen = set()
    for _ in range(int(10 / 0.032)):
        readings, pose, colliding, _, collisions = sim.step_observe(6.28, 6.28, low, high)
        assert (colliding, collisions) == (sim.colliding, sim.collisions)
        assert pose.tolist() == np.array(sim.pose, dtype=np.float32).tolist()
        seen.add(collisions)
    assert min(seen) == 0 and max(seen) >= 1


def test_same_seed_same_stream_and_another_seed_differs() -> None:
    def run(seed: int) -> np.ndarray:
        sim = Simulator(mazesim.load_world("seed-maze"), seed=seed)
        rows = []
        for i in range(1000):
            sim.step(4.0 + 2.0 * math.sin(0.05 * i), 4.0 + 2.0 * math.cos(0.065 * i))
            rows.append(np.concatenate([sim.distance_sensors(), sim.ground_sensors()]))
        return np.array(rows)

    a = run(7)
    assert np.array_equal(a, run(7))
    assert not np.array_equal(a, run(8))


def test_bad_arguments_raise_the_packages_errors() -> None:
    with pytest.raises(mazesim.UnknownNameError, match="e-puck"):
        Simulator(world(), robot="khepera")
    with pytest.raises(mazesim.InvalidArgumentError, match="whole number"):
        Simulator(world(step_ms=32.0), control_step_ms=40.0)
    with pytest.raises(mazesim.InvalidArgumentError, match="seed"):
        Simulator(world(), seed=-1)
    sim = Simulator(world(), control_step_ms=30.0)
    sim.step(1.0, 1.0)
    assert sim.time == pytest.approx(0.03)
