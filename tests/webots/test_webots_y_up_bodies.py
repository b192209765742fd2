"""A robot whose body is modelled Y-up (forward along its node's local -z, up its local y, as
every robot before Webots R2022a) and stood upright by its ``rotation`` in a later, Z-up world
(a world Webots converted, RoboCup Junior's e-puck-based PROTOs) drives, senses and reads its
GPS as its Z-up twin does: the import decides robot by robot which way its body is built
(#32)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from mazesim.webots.lockstep import run_world

WORLDS = Path(__file__).resolve().parent.parent / "data" / "webots-y-up-body" / "worlds"

pytestmark = pytest.mark.usefixtures("fresh_robot")

_LINE = re.compile(r"step (\d+) gps (\S+) (\S+) (\S+) ps0 (\S+) front (\S+)")
_FRAMES = re.compile(r"attitude (\S+) (\S+) (\S+) gravity (\S+) (\S+) (\S+)")


def _run(world: str, capfd: pytest.CaptureFixture[str]) -> list[str]:
    run = run_world(str(WORLDS / world), seconds=1.2)
    (robot,) = run.robots
    assert robot.exit_status == 0, robot.error
    return capfd.readouterr().out.splitlines()


def _readings(world: str, capfd: pytest.CaptureFixture[str]) -> dict[int, list[float]]:
    found = [_LINE.match(line) for line in _run(world, capfd)]
    return {int(m[1]): [float(v) for v in m.groups()[1:]] for m in found if m}


def _frames(world: str, capfd: pytest.CaptureFixture[str]) -> list[list[float]]:
    found = [_FRAMES.match(line) for line in _run(world, capfd)]
    return [[float(v) for v in m.groups()] for m in found if m]


def test_a_body_built_y_up_reads_and_drives_as_its_z_up_twin(
    capfd: pytest.CaptureFixture[str],
) -> None:
    y_up = _readings("y_up_body.wbt", capfd)
    # It faces +y (its local -z stood up by 1 0 0 1.5708) and drives there; its GPS, at its
    # local y 0.0185, reads 1.85 cm above the floor.
    x, y, z, _, front = y_up[1]
    assert abs(x) < 1e-4 and 0.0 < y < 0.01 and z == pytest.approx(0.0185, abs=1e-6)
    assert y_up[30][1] > 0.03 and abs(y_up[30][0]) < 1e-3
    # "front", 3.5 cm ahead and looking along the robot's forward, sees the wall's face at
    # y = 0.14 through its table (0.2 m: 1000): 0.1037 m at the first step, 518.6.
    assert front == pytest.approx((0.14 - 0.035 - y) * 5000.0, abs=0.5)
    # ps0, written in the node among its children (the profile's sensor, placed by the
    # world), casts its ray 17 degrees right of forward as its twin's.
    z_up = _readings("z_up_body.wbt", capfd)
    assert y_up.keys() == z_up.keys() == {1, 30}
    for count in (1, 30):
        assert y_up[count] == pytest.approx(z_up[count], rel=1e-4, abs=1e-5), count
    assert y_up[30][3] < 900.0, "ps0 sees the wall ahead by the end"


def test_its_devices_read_in_their_own_y_up_frames(capfd: pytest.CaptureFixture[str]) -> None:
    # An unturned InertialUnit and Accelerometer of a Y-up body: x right, y up, z back. In the
    # world (ENU) that frame is Rx(pi/2) with the robot facing +y: roll pi/2, yaw 0 (its x
    # axis points east); gravity's reaction along its y, the start's push forward along -z.
    (start, steady) = _frames("y_up_body.wbt", capfd)
    assert start[:3] == pytest.approx([1.5708, 0.0, 0.0], abs=1e-3)
    assert start[5] < -0.5 and abs(start[3]) < 0.05, "driving off pushes it along -z"
    assert steady[3:] == pytest.approx([0.0, 9.81, 0.0], abs=0.1)
    # Its Z-up twin's: x forward, z up.
    (start, steady) = _frames("z_up_body.wbt", capfd)
    assert start[:3] == pytest.approx([0.0, 0.0, 1.5708], abs=1e-3)
    assert start[3] > 0.5 and steady[3:] == pytest.approx([0.0, 0.0, 9.81], abs=0.1)


def test_a_still_robot_built_y_up_looks_ahead_with_its_camera_upright(
    capfd: pytest.CaptureFixture[str],
) -> None:
    # A robot that is no e-puck stays where its node stands; built Y-up and stood upright, its
    # camera (turned to look along the body's -z, its own z along the body's y) looks at the
    # red box 0.4 m ahead (+y), upright: 0.2 m wide and 0.1 m high at 0.375 m, it fills about
    # 10.7 of the 16 columns (0.785 rad across) and 5.2 of the 8 rows, centred.
    run = run_world(str(WORLDS / "still_camera.wbt"), seconds=0.1)
    assert [robot.exit_status for robot in run.robots] == [0, 0], run.robots
    (line,) = [x for x in capfd.readouterr().out.splitlines() if x.startswith("image ")]
    rows = line.split()[1].split("|")
    seen = [row for row in rows if "R" in row]
    assert 4 <= len(seen) <= 6 and "R" not in rows[0] + rows[-1], rows
    for row in seen:
        left, right = len(row) - len(row.lstrip(".")), len(row) - len(row.rstrip("."))
        assert abs(left - right) <= 1 and 9 <= row.count("R") <= 12, rows
