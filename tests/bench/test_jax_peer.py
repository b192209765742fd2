"""The JAX peer of ``make bench-peers`` models the same workload as the numpy peer and mazesim.

Skipped without jax (``make bench-peers`` installs it).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("jax", reason="jax is not installed (`make bench-peers` installs it)")

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benches"))

from peers import workload as wl  # noqa: E402
from peers.fidelity import step_agreement, trajectory_agreement  # noqa: E402
from peers.jax_peer import JaxPeer  # noqa: E402
from peers.numpy_peer import NumpyPeer  # noqa: E402

import mazesim  # noqa: E402

ENVS = 8


@pytest.fixture(scope="module")
def mazes() -> list[wl.Maze]:
    return [wl.maze_of(w) for w in wl.make_worlds(ENVS)]


def visited_poses(steps: int = 150) -> np.ndarray:
    """Poses mazesim's robots pass through under the workload (many of them near walls)."""
    batch = mazesim.BatchSimulator(wl.make_worlds(ENVS), robot="e-puck", seeds=0, threads=1)
    obs = np.zeros((ENVS, batch.observation_width), np.float32)
    poses = np.zeros((ENVS, 3), np.float32)
    colliding, crossings = np.zeros(ENVS, bool), np.zeros(ENVS, np.int32)
    actions, scratch = np.zeros((ENVS, 2), np.float32), np.zeros((8, ENVS), np.float32)
    batch.reset(obs, poses, colliding, crossings)
    for _ in range(steps):
        wl.braitenberg(obs[:, :8].T, actions[:, 0], actions[:, 1], scratch)
        batch.step(actions, obs, poses, colliding, crossings)
    return poses.copy()


def test_one_step_from_the_same_poses_agrees_with_the_numpy_peer(mazes: list[wl.Maze]) -> None:
    robot = wl.epuck()
    agreement = step_agreement(
        JaxPeer(mazes, robot, noise=False),
        NumpyPeer(mazes, robot, noise=False),
        visited_poses(),
    )
    assert agreement["max_position_gap_m"] < 1e-5
    assert agreement["max_heading_gap_rad"] < 1e-5
    assert agreement["max_relative_reading_gap"] < 1e-3


def test_trajectories_follow_the_numpy_peer(mazes: list[wl.Maze]) -> None:
    robot = wl.epuck()
    report = trajectory_agreement(
        JaxPeer(mazes, robot, noise=False), NumpyPeer(mazes, robot, noise=False), 200, 1e-3
    )
    assert report["share_within_tolerance"] == 1.0
    assert report["first_step_apart"] is None


def test_readings_match_mazesim_at_the_same_poses(mazes: list[wl.Maze]) -> None:
    poses = visited_poses()
    peer = JaxPeer(mazes, wl.epuck(), noise=False)
    peer.set_poses(poses)
    readings = peer.observations()
    worlds = wl.make_worlds(ENVS)
    for i in range(ENVS):
        sim = mazesim.Simulator(worlds[i], robot="e-puck", seed=0, noise=False)
        sim.set_pose(*(float(v) for v in poses[i]))
        assert np.allclose(readings[i, :8], sim.distance_sensors(), rtol=1e-3, atol=0.5)


def test_many_steps_per_call_equal_as_many_calls(mazes: list[wl.Maze]) -> None:
    robot = wl.epuck()
    one_by_one = JaxPeer(mazes, robot, seed=3)
    ten_at_once = JaxPeer(mazes, robot, seed=3, steps_per_call=10)
    one_by_one.reset()
    ten_at_once.reset()
    for _ in range(10):
        one_by_one.step()
    ten_at_once.step()
    assert np.allclose(one_by_one.poses(), ten_at_once.poses(), atol=1e-6)
    assert np.allclose(one_by_one.observations(), ten_at_once.observations(), rtol=1e-5)
    starts = np.array([m.start[:2] for m in mazes])
    moved = np.hypot(*(ten_at_once.poses()[:, :2] - starts).T)
    assert (moved > 0.01).all()


def test_lean_variant_reads_no_ground_sensors(mazes: list[wl.Maze]) -> None:
    lean = JaxPeer(mazes, wl.epuck(), noise=False, ground=False)
    lean.reset()
    lean.step()
    assert lean.name == "jax-lean" and lean.observations().shape == (ENVS, 8)
