"""The batch layer: one owner of the buffers, and placing robots without editing worlds."""

from __future__ import annotations

import numpy as np
import pytest

import mazesim
from mazesim._core import BatchSimulator
from mazesim.batch import RobotBatch
from mazesim.errors import InvalidArgumentError


def test_place_moves_the_listed_robots_only_and_equals_a_start_pose() -> None:
    world = mazesim.load_world("seed-maze")
    x, y, yaw = world.start
    pose = (x + 0.012, y - 0.008, yaw + 0.15)
    batch = RobotBatch([world], np.zeros(3, dtype=np.int64), threads=1)
    batch.reset(seeds=np.array([5, 6, 7], dtype=np.uint64))
    before = batch.poses.copy()
    batch.place([2], [pose], [99])
    assert np.array_equal(batch.poses[:2], before[:2])
    assert batch.poses[2] == pytest.approx(np.array(pose, dtype=np.float32))
    # The same robot started by the simulator from that start pose and seed drives identically.
    alone = BatchSimulator(
        [world], robot="seed", seeds=0, noise=True, control_step_ms=64.0, threads=1
    )
    alone.set_starts(np.array([pose]))
    buffers = (
        np.zeros((1, alone.observation_width), np.float32),
        np.zeros((1, 3), np.float32),
        np.zeros(1, bool),
        np.zeros(1, np.int32),
    )
    alone.reset(*buffers, seeds=np.array([99], dtype=np.uint64))
    actions = np.random.default_rng(0).integers(0, 12, (200, 3))
    for row in actions:
        batch.step(row)
        alone.step(batch.speeds_of(row[2:]), *buffers)
    assert np.array_equal(batch.observations[2:], buffers[0])
    assert np.array_equal(batch.poses[2:], buffers[1])


def test_bad_placements_name_the_robot() -> None:
    world = mazesim.load_world("seed-maze")
    batch = RobotBatch([world], np.zeros(2, dtype=np.int64), threads=1)
    with pytest.raises(InvalidArgumentError, match="from 0 to 1, found 2"):
        batch.place([2], [world.start], [0])
    with pytest.raises(InvalidArgumentError, match="environment 1"):
        batch.place([1], [(0.0, 0.125, 0.0)], [0])  # on the west wall
    with pytest.raises(InvalidArgumentError, match="starts"):
        batch.simulator.set_starts_at(np.array([0, 1]), np.zeros((1, 3)))
    with pytest.raises(
        InvalidArgumentError, match="world indices as whole numbers from 0 to 0, found 1"
    ):
        RobotBatch([world], [0, 1])


def test_robots_may_be_a_profile_or_one_per_robot() -> None:
    world = mazesim.load_world("seed-maze")
    seed = mazesim.RobotProfile.builtin("seed")
    faster = seed.perturbed(drive=mazesim.DrivePerturbation(wheel_radius_scale=1.05))
    mixed = RobotBatch([world], np.zeros(2, dtype=np.int64), robot=[seed, faster], noise=False)
    assert mixed.profile.name == "seed"
    alone = RobotBatch([world], np.zeros(1, dtype=np.int64), robot=faster, noise=False)
    assert alone.profile.name == "seed~perturbed"
    for _ in range(10):
        mixed.step(np.zeros(2, dtype=np.int64))
        alone.step(np.zeros(1, dtype=np.int64))
    np.testing.assert_array_equal(mixed.poses[1], alone.poses[0])
    # The same action drives the wider wheels 5 % farther.
    x, y, _ = world.start
    travelled = np.hypot(mixed.poses[:, 0] - x, mixed.poses[:, 1] - y)
    assert travelled[1] / travelled[0] == pytest.approx(1.05, rel=1e-4)
