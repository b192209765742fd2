"""Snapshots, pickling and copies of World, RobotProfile and Simulator: a copy goes on exactly as
the original, in contact with walls and movable bodies and with noise on; bytes that are not a
snapshot of the same set-up are refused with SnapshotError."""

from __future__ import annotations

import copy
import pickle

import pytest

import mazesim
from mazesim import RobotProfile, Simulator, SnapshotError, World

BODIES_WORLD = """format = "mazesim-world"
version = 1
name = "pushing"
basic_time_step_ms = 16

[start]
x = 0
y = 0

[[bodies]]
shape = "box"
center = [0.12, 0]
size = [0.05, 0.05]
mass = 0.1
friction = 0.5

[[walls]]
center = [0.35, 0]
size = [0.02, 0.6]
"""


def wheel_speeds(k: int) -> tuple[float, float]:
    """Mostly full speed ahead (into walls), with turns."""
    return [(6.28, 6.28), (6.28, 6.28), (6.28, -2.0), (-1.0, 5.0)][(k // 37) % 4]


def trace(sim: Simulator, start: int, steps: int) -> list[tuple[object, ...]]:
    """Steps `sim` and returns everything each step shows."""
    out: list[tuple[object, ...]] = []
    for k in range(start, start + steps):
        sim.step(*wheel_speeds(k))
        out.append(
            (
                sim.pose,
                sim.distance_sensors().tobytes(),
                sim.ground_sensors().tobytes(),
                sim.body_poses(),
                sim.collisions,
                sim.colliding,
                sim.wall_clearance,
                sim.encoders,
                sim.last_crossing,
                sim.time,
            )
        )
    return out


def test_world_and_profile_pickle_and_copy() -> None:
    world = mazesim.generate_maze(4, 3, seed=11)
    for protocol in range(2, pickle.HIGHEST_PROTOCOL + 1):
        again = pickle.loads(pickle.dumps(world, protocol=protocol))
        assert again.to_toml() == world.to_toml()
        assert again.name == world.name
        assert again.wall_boxes().tobytes() == world.wall_boxes().tobytes()
    assert copy.deepcopy(world) is world
    profile = RobotProfile.builtin("seed")
    assert pickle.loads(pickle.dumps(profile)).distance_sensor_names == (
        profile.distance_sensor_names
    )
    assert copy.copy(profile) is profile


@pytest.mark.parametrize("how", ["pickle", "deepcopy", "copy", "snapshot"])
def test_a_copy_goes_on_exactly_as_the_original_in_a_maze(how: str) -> None:
    sim = Simulator(World.builtin("seed-maze"), seed=5, noise=True)
    trace(sim, 0, 300)
    assert sim.collisions > 0
    if how == "pickle":
        other = pickle.loads(pickle.dumps(sim))
    elif how == "deepcopy":
        other = copy.deepcopy(sim)
    elif how == "copy":
        other = copy.copy(sim)
    else:
        other = Simulator(World.builtin("seed-maze"), seed=99, noise=True)
        other.restore(sim.snapshot())
    assert trace(other, 300, 2000) == trace(sim, 300, 2000)


def test_restoring_rewinds_in_contact_with_a_movable_body() -> None:
    sim = Simulator(World.from_toml(BODIES_WORLD), robot="e-puck2", seed=2, noise=True)
    trace(sim, 0, 40)
    saved = sim.snapshot()
    first = trace(sim, 40, 1500)
    assert any(row[5] for row in first), "the run touches the wall"
    sim.restore(saved)
    assert trace(sim, 40, 1500) == first
    clone = pickle.loads(pickle.dumps(sim))
    assert trace(clone, 1540, 200) == trace(sim, 1540, 200)


def test_a_copy_is_independent() -> None:
    sim = Simulator(World.builtin("arena"), seed=1)
    trace(sim, 0, 20)
    other = copy.deepcopy(sim)
    pose = other.pose
    trace(sim, 20, 50)
    assert other.pose == pose
    assert other.world.name == "arena"


def test_snapshots_of_another_set_up_are_refused() -> None:
    maze = Simulator(World.builtin("seed-maze"))
    snapshot = maze.snapshot()
    with pytest.raises(SnapshotError, match='"arena".*"seed-maze"'):
        Simulator(World.builtin("arena")).restore(snapshot)
    with pytest.raises(SnapshotError, match='robot profile "e-puck2"'):
        Simulator(World.builtin("seed-maze"), robot="e-puck2").restore(snapshot)
    with pytest.raises(SnapshotError, match="noise off"):
        Simulator(World.builtin("seed-maze"), noise=False).restore(snapshot)
    with pytest.raises(SnapshotError, match="64 ms control step"):
        Simulator(World.builtin("seed-maze"), control_step_ms=64).restore(snapshot)


def test_hostile_snapshots_are_refused_and_change_nothing() -> None:
    sim = Simulator(World.builtin("seed-maze"), seed=4)
    trace(sim, 0, 60)
    snapshot = sim.snapshot()
    pose = sim.pose
    bad: list[bytes] = [b"", b"MZSNAPSH", b"not a snapshot", snapshot + b"\0"]
    bad += [snapshot[:cut] for cut in range(0, len(snapshot), 11)]
    for at in range(0, len(snapshot), 9):
        flipped = bytearray(snapshot)
        flipped[at] ^= 0x41
        bad.append(bytes(flipped))
    for data in bad:
        with pytest.raises(SnapshotError):
            sim.restore(data)
        assert sim.pose == pose
    with pytest.raises(SnapshotError, match="truncated"):
        sim.restore(snapshot[:-3])
    with pytest.raises(mazesim.InvalidArgumentError):
        sim.restore(snapshot[:40])
    with pytest.raises(
        mazesim.InvalidArgumentError, match="expected snapshot to be bytes, found a str"
    ):
        sim.restore("a string")  # type: ignore[arg-type]
    sim.restore(snapshot)
