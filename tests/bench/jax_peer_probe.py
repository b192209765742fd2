"""The JAX peer's fidelity measured in a process of its own, printed as one JSON object.

JAX starts threads when it loads, and a process with them warns at every later ``fork``; so the
tests of the JAX peer run this script in a subprocess and read its standard output, and JAX never
loads into the test runner.

    jax_peer_probe.py ENVS
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benches"))

from peers import workload as wl  # noqa: E402
from peers.fidelity import step_agreement, trajectory_agreement  # noqa: E402
from peers.jax_peer import JaxPeer  # noqa: E402
from peers.numpy_peer import NumpyPeer  # noqa: E402

import mazesim  # noqa: E402


def visited_poses(worlds: list[mazesim.World], steps: int = 150) -> np.ndarray:
    """Poses mazesim's robots pass through under the workload (many of them near walls)."""
    n = len(worlds)
    batch = mazesim.BatchSimulator(worlds, robot="e-puck", seeds=0, threads=1)
    obs = np.zeros((n, batch.observation_width), np.float32)
    poses = np.zeros((n, 3), np.float32)
    colliding, crossings = np.zeros(n, bool), np.zeros(n, np.int32)
    actions, scratch = np.zeros((n, 2), np.float32), np.zeros((8, n), np.float32)
    batch.reset(obs, poses, colliding, crossings)
    for _ in range(steps):
        wl.braitenberg(obs[:, :8].T, actions[:, 0], actions[:, 1], scratch)
        batch.step(actions, obs, poses, colliding, crossings)
    return poses.copy()


def probe(envs: int) -> dict[str, Any]:
    worlds = wl.make_worlds(envs)
    mazes = [wl.maze_of(w) for w in worlds]
    robot = wl.epuck()
    poses = visited_poses(worlds)
    report: dict[str, Any] = {
        "step": step_agreement(
            JaxPeer(mazes, robot, noise=False), NumpyPeer(mazes, robot, noise=False), poses
        ),
        "trajectories": trajectory_agreement(
            JaxPeer(mazes, robot, noise=False), NumpyPeer(mazes, robot, noise=False), 200, 1e-3
        ),
    }
    # Readings against mazesim's at the same poses, noise off.
    peer = JaxPeer(mazes, robot, noise=False)
    peer.set_poses(poses)
    readings = peer.observations()
    gaps = []
    for i in range(envs):
        sim = mazesim.Simulator(worlds[i], robot="e-puck", seed=0, noise=False)
        sim.set_pose(*(float(v) for v in poses[i]))
        gaps.append(np.abs(readings[i, :8] - sim.distance_sensors()).max())
    report["ps_max_abs_gap_to_mazesim"] = float(max(gaps))
    # Ten steps in one call against ten calls of one step.
    one_by_one = JaxPeer(mazes, robot, seed=3)
    ten_at_once = JaxPeer(mazes, robot, seed=3, steps_per_call=10)
    one_by_one.reset()
    ten_at_once.reset()
    for _ in range(10):
        one_by_one.step()
    ten_at_once.step()
    starts = np.array([m.start[:2] for m in mazes])
    report["ten_steps"] = {
        "pose_gap": float(np.abs(one_by_one.poses() - ten_at_once.poses()).max()),
        "reading_gap": float(
            (
                np.abs(one_by_one.observations() - ten_at_once.observations())
                / np.maximum(np.abs(one_by_one.observations()), 1.0)
            ).max()
        ),
        "least_distance_moved": float(np.hypot(*(ten_at_once.poses()[:, :2] - starts).T).min()),
    }
    lean = JaxPeer(mazes, robot, noise=False, ground=False)
    lean.reset()
    lean.step()
    report["lean"] = {"name": lean.name, "width": int(lean.observations().shape[1])}
    return report


if __name__ == "__main__":
    print(json.dumps(probe(int(sys.argv[1]))))
