"""Rewards, ends and infos of the multi-robot tasks on constructed worlds."""

from __future__ import annotations

import math

import numpy as np
import pytest

from env_worlds import CORRIDOR_WALLS
from mazesim.marl.batch import MultiRobotBatch
from mazesim.marl.tasks import (
    AggregationTask,
    EpisodeDraw,
    MazeGoalsTask,
    dispersion,
    robots_world,
)

CORRIDOR = f"""format = "mazesim-world"
version = 1
name = "corridor"
{CORRIDOR_WALLS}"""


class FixedMazeGoals(MazeGoalsTask):
    """``maze_goals`` in a fixed corridor: two robots at given starts, with given goals."""

    def __init__(self, starts: list[tuple[float, float, float]], goals: list, **options) -> None:  # type: ignore[no-untyped-def]
        super().__init__(2, maze_size=(2, 2), **options)
        self.starts = np.array(starts)
        self.goals = np.array(goals, dtype=np.float64)

    def draw(self, rng: np.random.Generator) -> EpisodeDraw:
        return EpisodeDraw(robots_world(CORRIDOR, self.starts, "corridor"), 7, self.goals)


def facing_pair(**options: object) -> MultiRobotBatch:
    """Two e-pucks 20 cm apart facing each other, goals behind each other's backs."""
    task = FixedMazeGoals(
        [(-0.1, 0.0, 0.0), (0.1, 0.0, math.pi)], [(0.5, 0.0, 0.05), (-0.5, 0.0, 0.05)], **options
    )
    batch = MultiRobotBatch(task, 1, noise=False, threads=1, autoreset=False)
    batch.reset(0)
    return batch


def test_collision_ends_both_robots_with_the_penalty() -> None:
    batch = facing_pair()
    forward = np.ones((1, 2, 2), np.float32)
    for _ in range(20):
        live = batch.live.copy()
        before = batch.poses.copy()
        _, rewards, terminations, truncations, infos = batch.step(forward)
        if terminations.any():
            break
    assert terminations.all() and not truncations.any()
    assert infos["colliding"].all() and infos["touching_robot"].all()
    assert not infos["is_success"].any()
    # Progress (each moved towards its goal) + step penalty + collision penalty.
    goals = batch.task.goals[:, :2]  # type: ignore[attr-defined]
    for i in range(2):
        was = np.hypot(*(before[0, i, :2].astype(np.float64) - goals[i]))
        now = np.hypot(*(batch.poses[0, i, :2].astype(np.float64) - goals[i]))
        expected = 10.0 * (was - now) - 0.01 - 5.0
        assert rewards[0, i] == pytest.approx(expected, abs=1e-5)
    assert live.all() and not batch.live.any()
    # Ended robots stand still and earn nothing.
    resting = batch.poses.copy()
    _, rewards, terminations, _, _ = batch.step(forward)
    assert np.array_equal(batch.poses, resting) and not rewards.any() and not terminations.any()


def test_without_end_on_collision_contact_is_penalised_every_step() -> None:
    batch = facing_pair(end_on_collision=False)
    forward = np.ones((1, 2, 2), np.float32)
    penalised = 0
    previous = None
    for _ in range(30):
        _, rewards, terminations, _, infos = batch.step(forward)
        assert not terminations.any()
        distances = infos["distance_to_goal"]
        if previous is not None:
            contact = np.where(infos["colliding"], -5.0, 0.0)
            expected = 10.0 * (previous - distances) - 0.01 + contact
            assert np.allclose(rewards, expected, atol=1e-5)
        penalised += int(infos["colliding"].all())
        previous = distances
    assert penalised >= 20 and batch.live.all()  # pressed against each other, step after step


def test_reaching_the_goal_ends_the_robot_with_the_goal_reward() -> None:
    task = FixedMazeGoals(
        [(-0.2, 0.0, 0.0), (0.3, 0.0, 0.0)], [(-0.1, 0.0, 0.03), (0.5, 0.0, 0.03)]
    )
    batch = MultiRobotBatch(task, 1, noise=False, threads=1, autoreset=False)
    batch.reset(0)
    actions = np.array([[[1.0, 1.0], [0.0, 0.0]]], np.float32)
    total = 0.0
    for _ in range(40):
        _, rewards, terminations, _, infos = batch.step(actions)
        total += float(rewards[0, 0])
        if terminations[0, 0]:
            break
    assert infos["is_success"][0, 0] and not infos["colliding"][0, 0]
    assert rewards[0, 0] > 9.9 and batch.live.tolist() == [[False, True]]
    # The return is the progress (10 per metre from 0.1 m to the goal's edge or further),
    # the goal reward and the step penalties.
    steps = int(batch.steps[0])
    end = float(infos["distance_to_goal"][0, 0])
    assert total == pytest.approx(10.0 * (0.1 - end) + 10.0 - 0.01 * steps, abs=1e-4)
    assert end <= 0.03


def test_time_limit_truncates_every_live_robot() -> None:
    task = FixedMazeGoals(
        [(-0.2, 0.0, 0.0), (0.3, 0.0, 0.0)], [(-0.5, 0.0, 0.03), (0.5, 0.0, 0.03)], max_cycles=3
    )
    batch = MultiRobotBatch(task, 1, noise=False, threads=1, autoreset=False)
    batch.reset(0)
    still = np.zeros((1, 2, 2), np.float32)
    flags = [batch.step(still)[3].tolist() for _ in range(3)]
    assert flags == [[[False, False]], [[False, False]], [[True, True]]]
    assert not batch.live.any()


def test_aggregation_reward_is_minus_the_distance_to_the_centroid() -> None:
    task = AggregationTask(4)
    batch = MultiRobotBatch(task, 2, noise=False, threads=1)
    batch.reset(11)
    _, rewards, terminations, truncations, infos = batch.step(np.zeros((2, 4, 2), np.float32))
    xy = batch.poses[..., :2].astype(np.float64)
    centroid = xy.mean(axis=1, keepdims=True)
    assert np.allclose(rewards, -np.linalg.norm(xy - centroid, axis=-1), atol=1e-6)
    assert not terminations.any() and not truncations.any()
    expected = ((xy - centroid) ** 2).sum(axis=(1, 2)) / (4 * 0.037**2)
    assert np.allclose(infos["dispersion"][:, 0], expected)


def test_dispersion_of_a_known_cluster() -> None:
    # Four robots at the corners of a square of side 2r round the origin: each 2r / sqrt(2) =
    # sqrt(2) r from the centroid, so u = 4 * 2 r^2 / (4 r^2) = 2.
    r = 0.037
    poses = np.array([[[r, r, 0], [-r, r, 0], [-r, -r, 0], [r, -r, 0]]], np.float32)
    assert dispersion(poses, r)[0] == pytest.approx(2.0, rel=1e-6)


def test_aggregation_observes_the_nearest_robot_and_the_centroid() -> None:
    task = AggregationTask(3, arena_side=1.0)
    batch = MultiRobotBatch(task, 1, noise=False, threads=1)
    batch.reset(2)
    observations = task.observe(batch._states())
    xy = batch.poses[0, :, :2].astype(np.float64)
    for i in range(3):
        gaps = np.hypot(*(xy - xy[i]).T)
        gaps[i] = np.inf
        assert observations[0, i, 8] == pytest.approx(gaps.min(), rel=1e-5)
        others = np.delete(xy, i, axis=0).mean(axis=0)
        assert observations[0, i, 11] == pytest.approx(np.hypot(*(others - xy[i])), rel=1e-5)
        bearing = math.atan2(others[1] - xy[i, 1], others[0] - xy[i, 0]) - batch.poses[0, i, 2]
        assert observations[0, i, 12] == pytest.approx(math.cos(bearing), abs=1e-5)
        assert observations[0, i, 13] == pytest.approx(math.sin(bearing), abs=1e-5)
