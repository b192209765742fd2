"""An InertialUnit whose ``rotation`` tilts it on the robot reports its own frame's roll and
pitch, as Webots' does (the x-y-z extrinsic sequence of worlds since R2022a), read through the
device axes the compass, accelerometer and gyro read in; a level one reads roll and pitch 0."""

from __future__ import annotations

import math

import pytest

import mazesim
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.importer import import_wbt_text

pytestmark = pytest.mark.usefixtures("fresh_robot")

TILTED = """#VRML_SIM R2023b utf8
E-puck {
  turretSlot [
    InertialUnit { rotation 1 0 0 1.5707963267948966 name "rolled" }
    InertialUnit { rotation 0 1 0 0.5 name "pitched" }
    InertialUnit { rotation 0 0 1 0.25 name "level" }
  ]
}
"""


def attitudes(yaw: float) -> dict[str, tuple[list[float], list[float]]]:
    """Each unit's roll, pitch and yaw and its quaternion, the robot heading ``yaw``."""
    _, report = import_wbt_text(TILTED, "tilted.wbt")
    prepare(mazesim.load_world("line-follow"), seconds=2.0, noise=False, report=report)
    controller.Robot.created = None
    robot = controller.Robot()
    units = {name: robot.getDevice(name) for name in ("rolled", "pitched", "level")}
    for unit in units.values():
        unit.enable(32)
    simulations.current().simulator.set_pose(0.5, 0.5, yaw)
    robot.step(32)
    return {n: (u.getRollPitchYaw(), u.getQuaternion()) for n, u in units.items()}


def test_a_rolled_unit_reads_its_roll_and_a_pitched_one_its_pitch() -> None:
    read = attitudes(0.3)
    assert read["rolled"][0] == pytest.approx([math.pi / 2, 0.0, 0.3], abs=1e-6)
    assert read["pitched"][0] == pytest.approx([0.0, 0.5, 0.3], abs=1e-6)
    assert read["level"][0] == pytest.approx([0.0, 0.0, 0.55], abs=1e-6)


def test_the_quaternion_is_the_whole_attitude() -> None:
    read = attitudes(-1.0)
    # Rz(-1) Ry(0.5): the product of the two half-angle quaternions.
    z = (0.0, 0.0, math.sin(-0.5), math.cos(-0.5))
    y = (0.0, math.sin(0.25), 0.0, math.cos(0.25))
    expected = [
        z[3] * y[0] + z[0] * y[3] + z[1] * y[2] - z[2] * y[1],
        z[3] * y[1] - z[0] * y[2] + z[1] * y[3] + z[2] * y[0],
        z[3] * y[2] + z[0] * y[1] - z[1] * y[0] + z[2] * y[3],
        z[3] * y[3] - z[0] * y[0] - z[1] * y[1] - z[2] * y[2],
    ]
    assert read["pitched"][1] == pytest.approx(expected, abs=1e-6)
    assert read["level"][1] == pytest.approx([0.0, 0.0, math.sin(-0.375), math.cos(-0.375)])
