"""Movable bodies (issue #16): the world file's [[bodies]] in Python, pushed by the robot."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import mazesim
from mazesim.errors import WorldFormatError

HEADER = 'format = "mazesim-world"\nversion = 1\n\n[start]\nx = 0\ny = 0\n'

BOX = '\n[[bodies]]\nshape = "box"\ncenter = [0.15, 0.0]\nsize = [0.05, 0.05]\nmass = 0.1\n'


def test_bodies_are_listed_and_round_trip_through_a_file(tmp_path: Path) -> None:
    world = mazesim.World.from_toml(  # named: a world without a name takes its file's
        HEADER.replace("version = 1\n", 'version = 1\nname = "bodies"\n')
        + BOX
        + '\n[[bodies]]\nshape = "circle"\ncenter = [-0.2, 0.1]\nradius = 0.03\nmass = 0.2\n'
        + "friction = 0.1\nreflectance = 0.5\n"
    )
    assert world.bodies() == [
        {
            "shape": "box",
            "center": (0.15, 0.0),
            "size": (0.05, 0.05),
            "yaw": 0.0,
            "mass": 0.1,
            "friction": 0.5,
            "reflectance": 1.0,
        },
        {
            "shape": "circle",
            "center": (-0.2, 0.1),
            "radius": 0.03,
            "mass": 0.2,
            "friction": 0.1,
            "reflectance": 0.5,
        },
    ]
    path = tmp_path / "bodies.toml"
    world.save(str(path))
    assert "[[bodies]]" in path.read_text()
    assert mazesim.load_world(path) == world
    assert mazesim.load_world(path).bodies() == world.bodies()
    assert mazesim.World.from_toml(HEADER).bodies() == []


@settings(max_examples=30, deadline=None)
@given(
    x=st.floats(-10, 10),
    size=st.floats(0.001, 1.0),
    yaw=st.floats(-3.0, 3.0),
    mass=st.floats(1e-3, 100.0),
    friction=st.floats(0.0, 2.0),
)
def test_any_body_round_trips(
    x: float, size: float, yaw: float, mass: float, friction: float
) -> None:
    text = (
        HEADER + f'\n[[bodies]]\nshape = "box"\ncenter = [{x!r}, 0.0]\nsize = [{size!r}, '
        f"{size!r}]\nyaw = {yaw!r}\nmass = {mass!r}\nfriction = {friction!r}\n"
    )
    world = mazesim.World.from_toml(text)
    again = mazesim.World.from_toml(world.to_toml())
    assert again == world and again.bodies() == world.bodies()


@pytest.mark.parametrize(
    ("body", "words"),
    [
        ('shape = "box"\ncenter = [0, 0]\nsize = [0.1, 0.1]\nmass = 0\n', "above zero"),
        (
            'shape = "circle"\ncenter = [0, 0]\nradius = 0.1\nmass = 1\nfriction = -1\n',
            "at or above zero",
        ),
        ('shape = "circle"\ncenter = [5000, 0]\nradius = 0.1\nmass = 1\n', "bodies[0]"),
    ],
)
def test_bad_bodies_name_the_field(body: str, words: str) -> None:
    with pytest.raises(WorldFormatError) as error:
        mazesim.World.from_toml(HEADER + "\n[[bodies]]\n" + body, source="bad.toml")
    message = str(error.value)
    assert words in message and "bad.toml:" in message and "bodies[0]" in message


def test_the_robot_pushes_a_box_and_a_reset_puts_it_back() -> None:
    world = mazesim.World.from_toml(HEADER + BOX)
    sim = mazesim.Simulator(world, noise=False)
    near = mazesim.World.from_toml(HEADER + BOX.replace("0.15, 0.0", "0.08, 0.0"))
    seen = mazesim.Simulator(near, noise=False).distance_sensors()[[0, 7]]
    empty = mazesim.Simulator(mazesim.World.from_toml(HEADER), noise=False)
    assert (seen > empty.distance_sensors()[[0, 7]] + 100.0).all()
    for _ in range(100):
        sim.step(6.0, 6.0)
    [(x, y, _)] = sim.body_poses()
    assert x > 0.35 and abs(y) < 0.02
    sim.reset()
    assert sim.body_poses() == [(pytest.approx(0.15), 0.0, 0.0)]


def test_moving_the_robot_leaves_a_pushed_box_and_reset_scene_puts_it_back() -> None:
    sim = mazesim.Simulator(mazesim.World.from_toml(HEADER + BOX), noise=False)
    for _ in range(60):
        sim.step(6.0, 6.0)
    [pushed] = sim.body_poses()
    assert pushed[0] > 0.25
    sim.set_pose(-0.3, 0.3, 1.0)
    assert sim.body_poses() == [pushed]
    steps = sim.steps
    sim.reset_scene()
    assert sim.body_poses() == [(pytest.approx(0.15), 0.0, 0.0)]
    assert sim.pose == (0.0, 0.0, 0.0) and sim.steps == steps


def test_a_box_set_moving_slides_and_slows() -> None:
    sim = mazesim.Simulator(mazesim.World.from_toml(HEADER + BOX), noise=False)
    sim.set_body_velocity(0, 0.0, 0.3, 0.0)
    sim.step(0.0, 0.0)
    [(x, y, _)] = sim.body_poses()
    [(_, vy, _)] = sim.body_velocities()
    assert x == pytest.approx(0.15) and y > 0.005 and 0.0 < vy < 0.3
    with pytest.raises(mazesim.InvalidArgumentError, match="below the world's 1 bodies"):
        sim.set_body_velocity(1, 0.0, 0.0, 0.0)
    with pytest.raises(mazesim.InvalidArgumentError, match="vy"):
        sim.set_body_velocity(0, 0.0, 11.0, 0.0)
