"""Several robots in one world with movable bodies, their snapshots, and the batch's per-robot
read-outs: robots push a box and press on each other the same whatever the threads or the batch
size, a snapshot continues the run bit for bit and is re-checked when restored."""

from __future__ import annotations

import copy
import pickle
import struct

import numpy as np
import pytest

import mazesim
from env_worlds import CORRIDOR_WALLS

#: The box's half side and the e-puck's body radius, metres.
HALF, RADIUS = 0.02, 0.037


def box_world(crosser: tuple[float, float] = (-0.2, -0.06)) -> mazesim.World:
    """A corridor: robot "pusher" behind a box, robot "crosser" facing across the box's way."""
    x, y = crosser
    return mazesim.World.from_toml(
        f"""
format = "mazesim-world"
version = 1
{CORRIDOR_WALLS}
[[bodies]]
shape = "box"
center = [-0.2, 0.0]
size = [{2 * HALF}, {2 * HALF}]
mass = 0.05
[[robots]]
name = "pusher"
x = -0.3
y = 0.0
[[robots]]
name = "crosser"
x = {x}
y = {y}
yaw = 1.5707963267948966
"""
    )


def batch_run(envs: int, threads: int, steps: int = 60) -> list[np.ndarray]:
    """Every buffer of the first two environments, step after step, in a batch of ``envs``."""
    batch = mazesim.BatchSimulator(box_world(), num_envs=envs, seeds=4, threads=threads)
    obs, poses, colliding, crossings = batch.output_buffers()
    assert obs.shape == (envs, 2, batch.observation_width)
    batch.reset(obs, poses, colliding, crossings)
    rng = np.random.default_rng(5)
    seen, touching = [], 0
    for _ in range(steps):
        actions = np.resize(rng.uniform(2.0, 6.0, (2, 2, 2)), (envs, 2, 2)).astype(np.float32)
        batch.step(actions, obs, poses, colliding, crossings)
        touching += int(colliding[:2].sum())
        seen.append(np.concatenate([obs[:2].ravel(), poses[:2].ravel(), colliding[:2].ravel()]))
    assert touching > 10, "the robots press on each other"
    assert batch.collisions().shape == (envs, 2)
    return seen


def test_robots_and_a_box_in_contact_run_the_same_whatever_the_threads_and_batch_size() -> None:
    reference = batch_run(2, 1)
    for envs, threads in ((2, 2), (24, 1), (24, 2)):
        for a, b in zip(reference, batch_run(envs, threads)):
            assert np.array_equal(a.view(np.uint8), b.view(np.uint8)), (envs, threads)


def test_a_robot_pushes_the_box_and_the_other_robot_sees_it() -> None:
    sim = mazesim.Simulator(box_world((0.1, -0.06)), noise=False)
    [(x0, _, _)] = sim.body_poses()
    highest = 0.0
    for _ in range(120):
        sim.step_robots(np.array([[5.0, 5.0], [0.0, 0.0]]))
        highest = max(highest, float(sim.distance_sensors(robot_index=1)[[0, 1, 6, 7]].max()))
    [(x, y, _)] = sim.body_poses()
    assert x - x0 > 0.15, "pushed along the corridor, past the crosser's front"
    assert highest > 200.0, "the crosser's front sensors saw the box go by"
    sim.reset()
    assert sim.body_poses() == [(pytest.approx(-0.2), 0.0, 0.0)]


def run_record(sim: mazesim.Simulator, steps: int) -> list[bytes]:
    """Every robot's readings and pose and the box's pose after each of ``steps`` steps."""
    out = []
    for k in range(steps):
        sim.step_robots(np.array([[4.0 + k % 3, 5.0], [5.0, 3.0 + k % 2]]))
        rows = [sim.distance_sensors(robot_index=i).tobytes() for i in range(2)]
        out.append(b"".join(rows) + sim.poses().tobytes() + repr(sim.body_poses()).encode())
    return out


def test_a_snapshot_of_several_robots_continues_the_run_bit_for_bit() -> None:
    sim = mazesim.Simulator(box_world(), seed=11)
    run_record(sim, 25)
    sim.set_wheel_speeds(1.0, -2.0, robot_index=1)
    snapshot = sim.snapshot()
    expected = run_record(sim, 40)
    sim.restore(snapshot)
    assert run_record(sim, 40) == expected
    again = mazesim.Simulator(box_world(), seed=0)
    again.restore(snapshot)
    assert run_record(again, 40) == expected
    for duplicate in (lambda s: pickle.loads(pickle.dumps(s)), copy.copy):
        other = duplicate(again)
        assert other.snapshot() == again.snapshot()
        assert run_record(other, 10) == run_record(again, 10)


def fnv1a(data: bytes) -> int:
    """FNV-1a 64 of ``data``, the snapshot's checksum."""
    h = 0xCBF29CE484222325
    for byte in data:
        h = ((h ^ byte) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return h


def resealed(head: bytes, body: bytes) -> bytes:
    """A swarm snapshot of header ``head`` (magic, version, count) and ``body``, its checksum
    recomputed, as an edit by hand would be."""
    return head + struct.pack("<Q", fnv1a(body)) + body


def test_restore_rechecks_a_snapshot_of_several_robots_and_changes_nothing_when_refused() -> None:
    sim = mazesim.Simulator(box_world(), seed=2)
    run_record(sim, 5)
    good = sim.snapshot()
    head, body = good[:16], good[24:]
    before = sim.snapshot()
    far = struct.pack("<dd", 1e300, 0.0) + body[16:]
    nan = struct.pack("<dd", 0.0, float("nan")) + body[16:]
    # Robot 1's part put first: robot 0's holds the box's scene, robot 1's does not.
    first = 32 + struct.unpack("<Q", body[32:40])[0] + 8
    parts = body[32:first], body[first:]
    swapped = body[:32] + parts[1] + parts[0]
    three = head[:12] + struct.pack("<I", 3)
    for bad, match in (
        (resealed(head, far), "wheel command"),
        (resealed(head, nan), "wheel command"),
        (resealed(head, swapped), "robot 0"),
        (resealed(three, body), "3 robots"),
        (good[:-7], "checksum|truncated"),
        (good[:20], "truncated"),
        (mazesim.Simulator(mazesim.World.builtin("arena")).snapshot(), "MZSNAPSH"),
    ):
        with pytest.raises(mazesim.SnapshotError, match=match):
            sim.restore(bad)
        assert sim.snapshot() == before, match


def test_robot_index_out_of_range_names_the_robot_count() -> None:
    sim = mazesim.Simulator(box_world())
    two = r"from 0 to 1 \(the world has 2 robots\), found"
    for index in (2, -1, 2**70):
        with pytest.raises(mazesim.InvalidArgumentError, match=two):
            sim.robot_state(index)
    with pytest.raises(mazesim.InvalidArgumentError, match="the world has 1 robot\\)"):
        mazesim.Simulator(mazesim.World.builtin("arena")).distance_sensors(robot_index=1)


def test_per_environment_read_outs_have_a_robot_axis() -> None:
    batch = mazesim.BatchSimulator(box_world(), num_envs=3)
    buffers = batch.output_buffers()
    assert [b.shape for b in buffers] == [(3, 2, 11), (3, 2, 3), (3, 2), (3, 2)]
    batch.reset(*buffers)
    batch.step(np.full((3, 2, 2), 3.0, np.float32), *buffers)
    for read in (batch.times, batch.steps, batch.collisions, batch.distances_travelled):
        assert read().shape == (3, 2), read
    assert batch.encoders().shape == (3, 2, 2) and batch.goals().shape == (3, 2, 3)
    assert np.array_equal(batch.steps(), np.ones((3, 2)))
    # A batch of worlds of one robot keeps its shapes.
    one = mazesim.BatchSimulator(mazesim.World.builtin("arena"), num_envs=3)
    assert [b.shape for b in one.output_buffers()] == [(3, 11), (3, 3), (3,), (3,)]
    assert one.times().shape == (3,) and one.encoders().shape == (3, 2)
