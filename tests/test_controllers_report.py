"""The report's follow-the-line (Alg. 2) and exploration (section 4.2.2) controllers, and
Alg. 1 on a batch."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import mazesim
from mazesim.controllers import AvoidCollision, Explore, FollowLine
from mazesim.errors import InvalidArgumentError

WHITE, BLACK = 856.0, 300.0


# --- Alg. 2 ----------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("ground", "expected"),
    [
        ((WHITE, BLACK, WHITE), (3.14, 3.14)),  # on the line
        ((WHITE, WHITE, BLACK), (4.71, 1.57)),  # only the right sensor: turn right
        ((BLACK, WHITE, WHITE), (1.57, 4.71)),  # only the left sensor: turn left
        ((WHITE, BLACK, BLACK), (3.14, 3.14)),  # right and centre: straight on
        ((WHITE, WHITE, WHITE), (3.14, 3.14)),  # no line: straight on
        ((BLACK, BLACK, BLACK), (3.14, 3.14)),
    ],
)
def test_follow_line_rule(ground: tuple[float, ...], expected: tuple[float, float]) -> None:
    assert FollowLine()(np.array(ground)) == pytest.approx(expected)


def line_segments() -> tuple[np.ndarray, np.ndarray]:
    regions = mazesim.load_world("line-follow").paint_regions()
    starts = np.array([r["a"] for r in regions if r["shape"] == "capsule"], dtype=float)
    ends = np.array([r["b"] for r in regions if r["shape"] == "capsule"], dtype=float)
    return starts, ends


def distance_to_line(point: np.ndarray, starts: np.ndarray, ends: np.ndarray) -> float:
    along = ends - starts
    t = np.clip(((point - starts) * along).sum(1) / (along * along).sum(1), 0.0, 1.0)
    nearest = starts + t[:, None] * along
    return float(np.min(np.hypot(*(point - nearest).T)))


def test_follow_line_completes_laps_without_losing_the_line() -> None:
    world = mazesim.load_world("line-follow")
    sim = mazesim.Simulator(world, robot="e-puck", seed=0)
    controller = FollowLine()
    starts, ends = line_segments()
    centre = np.array([0.6, 0.5])
    turned = 0.0
    previous = None
    worst = 0.0
    for _ in range(math.ceil(120_000.0 / sim.control_step_ms)):
        sim.step(*controller(sim.ground_sensors()))
        x, y, yaw = sim.pose
        gs1 = np.array([x + 0.03 * math.cos(yaw), y + 0.03 * math.sin(yaw)])
        worst = max(worst, distance_to_line(gs1, starts, ends))
        angle = math.atan2(y - centre[1], x - centre[0])
        if previous is not None:
            turned += math.remainder(angle - previous, 2 * math.pi)
        previous = angle
    # Counter-clockwise laps around the loop's centre; the centre sensor never leaves the line
    # (half of its 1.5 cm width).
    assert turned / (2 * math.pi) >= 3.0
    assert worst < 0.0075
    assert sim.collisions == 0


def test_follow_line_batch_equals_rows() -> None:
    rng = np.random.default_rng(2)
    ground = rng.choice([BLACK, 450.0, 550.0, WHITE], size=(500, 3))
    controller = FollowLine()
    batch = controller.batch(ground)
    assert batch.dtype == np.float32 and batch.shape == (500, 2)
    expected = np.array([controller(row) for row in ground], dtype=np.float32)
    np.testing.assert_array_equal(batch, expected)
    with pytest.raises(InvalidArgumentError, match=r"\(N, 3\)"):
        controller.batch(np.zeros((4, 8)))
    with pytest.raises(InvalidArgumentError, match=r"\(3,\)"):
        controller(np.zeros(8))


# --- the exploration controller ---------------------------------------------------------------

OPEN = [0.5, 0.5, 1.0, 1.0, 0.9, 0.9]


def test_explore_rule() -> None:
    controller = Explore(threshold=1.4, speed=3.0, seed=0)
    assert controller(OPEN) == pytest.approx((3.0, 3.0))
    # A wall on the right-front only: veer left; on the left-front only: veer right.
    assert controller([0.5, 0.5, 1.0, 1.0, 0.9, 1.5]) == pytest.approx((1.5, 4.5))
    assert controller([0.5, 0.5, 1.0, 1.0, 1.5, 0.9]) == pytest.approx((4.5, 1.5))
    assert controller([0.5, 0.5, 1.0, 1.0, 1.5, 1.5]) == pytest.approx((3.0, 3.0))
    # An obstacle in front: turn on the spot towards the more open side (here the left) ...
    assert controller([1.6, 0.5, 0.4, 2.0, 0.5, 1.3]) == pytest.approx((-3.0, 3.0))
    # ... and keep turning that way while the front sees it, whatever the sides say ...
    assert controller([1.5, 0.5, 2.0, 0.4, 1.3, 0.5]) == pytest.approx((-3.0, 3.0))
    # ... until the front is clear.
    assert controller(OPEN) == pytest.approx((3.0, 3.0))
    assert controller([1.6, 0.5, 2.0, 0.4, 1.3, 0.5]) == pytest.approx((3.0, -3.0))


def test_explore_picks_a_random_side_when_both_are_open() -> None:
    sides = set()
    for seed in range(20):
        controller = Explore(seed=seed)
        sides.add(controller([2.0, 0.5, 0.5, 0.5, 0.6, 0.6]))
    assert sides == {(3.14, -3.14), (-3.14, 3.14)}


def test_explore_batch_keeps_a_state_per_robot() -> None:
    controller = Explore(threshold=1.4, speed=2.0, seed=0)
    blocked_left = [1.6, 0.5, 2.0, 0.4, 1.3, 0.5]
    blocked_right = [1.6, 0.5, 0.4, 2.0, 0.5, 1.3]
    first = controller.batch(np.array([blocked_left, blocked_right, OPEN]))
    np.testing.assert_allclose(first, [[2.0, -2.0], [-2.0, 2.0], [2.0, 2.0]])
    # Swapped sides: each robot keeps turning its own way while blocked.
    second = controller.batch(np.array([blocked_right, blocked_left, OPEN]))
    np.testing.assert_allclose(second, first)
    controller.reset_robots(np.array([True, False, False]))
    third = controller.batch(np.array([blocked_right, blocked_left, OPEN]))
    np.testing.assert_allclose(third, [[-2.0, 2.0], [-2.0, 2.0], [2.0, 2.0]])
    assert third.dtype == np.float32
    with pytest.raises(InvalidArgumentError, match=r"\(N, 6\)"):
        controller.batch(np.zeros((3, 8)))


def test_explore_batch_mask_keeps_the_state_of_robots_that_do_not_act() -> None:
    controller = Explore(threshold=1.4, speed=2.0, seed=0)
    blocked_left = [1.6, 0.5, 2.0, 0.4, 1.3, 0.5]
    blocked_right = [1.6, 0.5, 0.4, 2.0, 0.5, 1.3]
    controller.batch(np.array([blocked_left, blocked_left]))  # both turn right (clockwise)
    # Robot 1 does not act on a clear front: it is still turning when it acts next.
    controller.batch(np.array([OPEN, OPEN]), np.array([True, False]))
    after = controller.batch(np.array([blocked_right, blocked_right]))
    np.testing.assert_allclose(after, [[-2.0, 2.0], [2.0, -2.0]])
    with pytest.raises(InvalidArgumentError, match="mask of shape"):
        controller.batch(np.array([OPEN, OPEN]), np.array([True]))
    with pytest.raises(InvalidArgumentError, match=r"mask of shape \(2,\), found \(3,\)"):
        controller.reset_robots(np.array([True, False, True]))


@settings(max_examples=100, deadline=None)
@given(
    arrays(
        np.float64,
        st.tuples(st.integers(1, 10), st.just(6)),
        elements=st.floats(0.3, 3.1),
    )
)
def test_explore_batch_equals_single_robot_controllers(readings: np.ndarray) -> None:
    # Far from a tie, the random side is never drawn, so each row equals its own controller.
    readings[:, 2] = readings[:, 3] + 0.5
    readings[:, 4] = readings[:, 5]
    batch = Explore(seed=1)
    singles = [Explore(seed=1) for _ in readings]
    for _ in range(3):
        expected = [single(row) for single, row in zip(singles, readings)]
        np.testing.assert_allclose(batch.batch(readings), expected, rtol=1e-6)
        readings = readings[:, [1, 0, 3, 2, 5, 4]]


@pytest.mark.parametrize("threshold", [1.2, 2.0])
def test_explore_wanders_seed_maze_and_crosses_codes(threshold: float) -> None:
    world = mazesim.load_world("seed-maze")
    count = 16
    batch = mazesim.BatchSimulator(world, num_envs=count, robot="seed", seeds=range(count))
    observations = np.zeros((count, batch.observation_width), dtype=np.float32)
    poses = np.zeros((count, 3), dtype=np.float32)
    colliding = np.zeros(count, dtype=bool)
    crossings = np.zeros(count, dtype=np.int32)
    batch.observe(observations, poses, colliding, crossings)
    controller = Explore(threshold=threshold, seed=0)
    seen = set()
    cells = [set() for _ in range(count)]
    for _ in range(math.ceil(120_000.0 / 32.0)):
        batch.step(controller.batch(observations[:, :6]), observations, poses, colliding, crossings)
        seen.update(int(c) for c in crossings if c)
        for env in range(count):
            cells[env].add((int(poses[env, 0] // 0.25), int(poses[env, 1] // 0.25)))
    assert batch.collisions().sum() == 0
    assert min(len(visited) for visited in cells) >= 5
    # Codes are crossed in both directions.
    assert any(c > 0 for c in seen) and any(c < 0 for c in seen)


# --- Alg. 1 on a batch ------------------------------------------------------------------------


def test_avoid_collision_keeps_a_batch_moving_in_the_arena() -> None:
    count = 8
    batch = mazesim.BatchSimulator(
        mazesim.load_world("arena"), num_envs=count, robot="e-puck", seeds=range(count)
    )
    observations = np.zeros((count, batch.observation_width), dtype=np.float32)
    poses = np.zeros((count, 3), dtype=np.float32)
    colliding = np.zeros(count, dtype=bool)
    crossings = np.zeros(count, dtype=np.int32)
    batch.observe(observations, poses, colliding, crossings)
    controller = AvoidCollision()
    steps = math.ceil(60_000.0 / 32.0)
    trace = np.empty((steps, count, 2))
    for step in range(steps):
        batch.step(controller.batch(observations[:, :8]), observations, poses, colliding, crossings)
        trace[step] = poses[:, :2]
    distances = batch.distances_travelled()
    assert np.all(distances > 1.0)
    # Every robot is still driving in the last ten seconds, and stays inside the walls.
    recent = trace[-310:]
    driven = np.hypot(*np.diff(recent, axis=0).transpose(2, 0, 1)).sum(axis=0)
    assert np.all(driven > 0.2), driven
    assert np.all(np.abs(trace) < 0.5)
