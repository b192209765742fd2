"""One environment of a batch of worlds of several robots: its starts, goals, snapshot and restore
are every robot's, and what stays for one robot only says what to do instead."""

from __future__ import annotations

import numpy as np
import pytest
from test_multi_robot import corridor

import mazesim
from mazesim.errors import InvalidArgumentError, MazesimError

#: Two e-pucks 0.08 m either side of the corridor's middle, facing each other.
GAP = 0.086

#: A box between them: robot 0's snapshot holds the shared scene.
BOX = '[[bodies]]\nshape = "box"\ncenter = [0.0, 0.0]\nsize = [0.04, 0.04]\nmass = 0.05\n'


def batch_of(extra: str = "") -> tuple[mazesim.BatchSimulator, tuple[np.ndarray, ...]]:
    batch = mazesim.BatchSimulator(corridor(GAP, extra=extra), num_envs=3, seeds=[4, 8, 9])
    buffers = batch.output_buffers()
    batch.reset(*buffers)
    return batch, buffers


def actions(k: int, envs: int = 3) -> np.ndarray:
    return np.full((envs, 2, 2), 2.0 + k % 4, np.float32)


@pytest.mark.parametrize("extra", ["", BOX], ids=["robots", "robots-and-a-box"])
def test_a_snapshot_of_one_environment_continues_bit_for_bit_in_another(extra: str) -> None:
    batch, buffers = batch_of(extra)
    for k in range(10):
        batch.step(actions(k), *buffers)
    saved = batch.snapshot_env(1)
    assert saved.startswith(b"MZSWARMS")
    later = []
    for k in range(10, 25):
        batch.step(actions(k), *buffers)
        later.append((buffers[0][1].copy(), buffers[1][1].copy(), buffers[2][1].copy()))
    if not extra:
        assert buffers[2][1].all(), "the robots press on each other"
    else:
        assert buffers[1][1, 1, 0] - buffers[1][1, 0, 0] > 0.074 + 0.039, "the box between them"
    # Environment 2 (another seed) takes environment 1's state, noise streams and all.
    batch.restore_env(2, saved)
    for k, (obs, poses, colliding) in zip(range(10, 25), later):
        batch.step(actions(k), *buffers)
        assert np.array_equal(buffers[0][2], obs) and np.array_equal(buffers[1][2], poses), k
        assert np.array_equal(buffers[2][2], colliding)
    # A simulator of the world reads the same bytes and goes on as the environment did.
    sim = mazesim.Simulator(corridor(GAP, extra=extra), seed=1)
    sim.restore(saved)
    for k, (_, poses, _) in zip(range(10, 25), later):
        sim.step_robots(actions(k)[0].astype(np.float64))
        assert np.array_equal(sim.poses(), poses), k


def test_restore_env_refuses_another_world_and_changes_nothing() -> None:
    batch, buffers = batch_of()
    other = mazesim.Simulator(corridor(GAP, extra=BOX), seed=1)
    before = batch.snapshot_env(0)
    with pytest.raises(MazesimError):
        batch.restore_env(0, other.snapshot())
    with pytest.raises(MazesimError, match="several robots"):
        batch.restore_env(0, b"MZSIMSNP" + bytes(40))
    assert batch.snapshot_env(0) == before
    with pytest.raises(InvalidArgumentError, match="0..=2, found 3"):
        batch.snapshot_env(3)


def test_starts_and_goals_are_set_per_robot() -> None:
    batch, buffers = batch_of()
    starts = np.array(
        [[[-0.3, 0.0, 0.0], [0.3, 0.0, 3.0]]] * 3 + np.arange(3)[:, None, None] * 0.01
    )
    batch.set_starts(starts)
    batch.set_starts_at(np.array([2]), np.array([[[-0.1, 0.02, 1.0], [0.1, -0.02, 2.0]]]))
    starts[2] = [[-0.1, 0.02, 1.0], [0.1, -0.02, 2.0]]
    batch.reset(*buffers)
    assert np.array_equal(buffers[1], starts.astype(np.float32))
    goals = np.array([[[0.4, 0.0, 0.05], [-0.4, 0.0, 0.06]]])
    batch.set_goals_at(np.array([1]), goals)
    assert np.array_equal(batch.goals()[1], goals[0])


def test_bad_starts_are_refused_naming_the_environment_and_robot_and_change_nothing() -> None:
    batch, buffers = batch_of()
    overlapping = np.array(
        [[[-0.3, 0.0, 0.0], [0.3, 0.0, 0.0]], [[0.0, 0.0, 0.0], [0.05, 0.0, 0.0]]]
    )
    with pytest.raises(InvalidArgumentError, match="environment 1, robot 0: .*overlapping robot 1"):
        batch.set_starts_at(np.array([0, 1]), overlapping)
    in_wall = np.array([[[0.0, 0.1, 0.0], [0.3, 0.0, 0.0]]])
    with pytest.raises(InvalidArgumentError, match="environment 2, robot 0"):
        batch.set_starts_at(np.array([2]), in_wall)
    with pytest.raises(InvalidArgumentError, match=r"\(3, 2, 3\)"):
        batch.set_starts(np.zeros((3, 3)))
    batch.reset(*buffers)
    assert np.allclose(buffers[1][:, :, 0], [[-0.08, 0.08]] * 3), "the world's starts still"
