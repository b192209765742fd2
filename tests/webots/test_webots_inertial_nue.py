"""An InertialUnit in a world before R2022a (NUE, Y-up devices) reads as Webots' R2020b-R2021b
InertialUnit page has it: its attitude in the reference frame of north, up and their cross
product, the x-z-y extrinsic sequence (Ry(yaw) Rz(pitch) Rx(roll)). A unit unturned in the
E-puck's turret (its x axis the robot's right, north's default the file's x) reads the robot's
heading as the imported world has it, not a quarter turn off; one the world tilts reads its
roll and pitch; another northDirection turns the yaw by as much."""

from __future__ import annotations

import math

import pytest

import mazesim
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.importer import import_wbt_text
from mazesim.webots.scene import read_scene

pytestmark = pytest.mark.usefixtures("fresh_robot")

UNITS = ("level", "rolled", "pitched", "turned")


def nue_world(north: str = "") -> str:
    """An R2021a world of an E-puck with four InertialUnits in its turret."""
    info = f"WorldInfo {{ northDirection {north} }}\n" if north else ""
    return f"""#VRML_SIM R2021a utf8
{info}E-puck {{
  turretSlot [
    InertialUnit {{ name "level" }}
    InertialUnit {{ rotation 1 0 0 1.5707963267948966 name "rolled" }}
    InertialUnit {{ rotation 0 0 1 0.5 name "pitched" }}
    InertialUnit {{ rotation 0 1 0 0.25 name "turned" }}
  ]
}}
"""


def attitudes(yaw: float, north: str = "") -> dict[str, tuple[list[float], list[float]]]:
    """Each unit's roll, pitch and yaw and its quaternion, the robot heading ``yaw``."""
    text = nue_world(north)
    _, report = import_wbt_text(text, "nue.wbt")
    world = mazesim.load_world("line-follow")
    prepare(world, seconds=2.0, noise=False, report=report, scene=read_scene(text))
    controller.Robot.created = None
    robot = controller.Robot()
    units = {name: robot.getDevice(name) for name in UNITS}
    for unit in units.values():
        unit.enable(32)
    simulations.current().simulator.set_pose(0.5, 0.5, yaw)
    robot.step(32)
    return {n: (u.getRollPitchYaw(), u.getQuaternion()) for n, u in units.items()}


def test_a_unit_reads_the_heading_and_its_own_tilt_in_an_nue_world() -> None:
    read = attitudes(0.3)
    assert read["level"][0] == pytest.approx([0.0, 0.0, 0.3], abs=1e-6)
    # Turned about the unit's y axis (up), its yaw grows, turning left.
    assert read["turned"][0] == pytest.approx([0.0, 0.0, 0.55], abs=1e-6)
    # Its x axis (the roll axis) and its z axis (the pitch axis) as Webots' NUE sequence.
    assert read["rolled"][0] == pytest.approx([math.pi / 2, 0.0, 0.3], abs=1e-6)
    assert read["pitched"][0] == pytest.approx([0.0, 0.5, 0.3], abs=1e-6)


def test_the_quaternion_is_that_of_ry_yaw_rz_pitch_rx_roll() -> None:
    read = attitudes(-1.0)
    assert read["level"][1] == pytest.approx([0.0, math.sin(-0.5), 0.0, math.cos(-0.5)])
    # Ry(-1) Rz(0.5): the product of the two half-angle quaternions.
    y = (0.0, math.sin(-0.5), 0.0, math.cos(-0.5))
    z = (0.0, 0.0, math.sin(0.25), math.cos(0.25))
    expected = [
        y[3] * z[0] + y[0] * z[3] + y[1] * z[2] - y[2] * z[1],
        y[3] * z[1] - y[0] * z[2] + y[1] * z[3] + y[2] * z[0],
        y[3] * z[2] + y[0] * z[1] - y[1] * z[0] + y[2] * z[3],
        y[3] * z[3] - y[0] * z[0] - y[1] * z[1] - y[2] * z[2],
    ]
    assert read["pitched"][1] == pytest.approx(expected, abs=1e-6)


def test_another_north_turns_the_yaw_by_as_much() -> None:
    # North along the file's -z, a quarter turn left of its x seen from above (y up): the
    # same unit reads a quarter turn less.
    read = attitudes(0.3, north="0 0 -1")
    assert read["level"][0] == pytest.approx([0.0, 0.0, 0.3 - math.pi / 2], abs=1e-6)
