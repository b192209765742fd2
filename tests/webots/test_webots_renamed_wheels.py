"""An e-puck saved expanded (a plain Robot node, the E-puck PROTO's tree written out) whose world
names its wheels' motors and position sensors otherwise (``left_motor``, ``encoder L``) has
them by those names, each driving its own wheel, as Webots finds devices by the names the
world gives (#32)."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import pytest

from mazesim.webots.lockstep import run_world

WORLD = Path(__file__).resolve().parent.parent / "data" / "webots-renamed-wheels" / "worlds"

pytestmark = pytest.mark.usefixtures("fresh_robot")


def test_an_expanded_e_puck_drives_by_the_wheel_names_its_world_gives(
    capfd: pytest.CaptureFixture[str],
) -> None:
    run = run_world(str(WORLD / "renamed_wheels.wbt"), seconds=2.0)
    (robot,) = run.robots
    assert robot.exit_status == 0, robot.error
    # 30 steps of 32 ms at 2 rad/s: the left wheel's encoder reads its 1.92 rad, unrounded (its
    # node writes no resolution: Webots' -1, not the E-puck PROTO's 0.00628, which would read
    # 1.92168); the right one's 3.84 rad to its node's resolution 0.5, int(7.68 + 0.5) steps.
    out = capfd.readouterr().out
    assert "left wheel turned 1.92 rad" in out
    (line,) = [line for line in out.splitlines() if line.startswith("encoders read")]
    left, right = (float(word) for word in line.split()[2:])
    assert left == pytest.approx(1.92, abs=1e-9) and right == 4.0
    assert robot.final_pose[0] > -0.5 + 0.03, "it drives ahead, not standing still"
    turned = math.remainder(robot.final_pose[2], 2 * math.pi)
    assert turned > 0.5, "the right wheel, faster, turns it left: each name drives its own wheel"


@pytest.mark.parametrize("noise", [False, True])
def test_a_wheel_sensor_s_noise_field_adds_webots_gaussian_before_its_rounding(
    tmp_path: Path, capfd: pytest.CaptureFixture[str], noise: bool
) -> None:
    # WbPositionSensor::position: the angle plus noise * a gaussian draw, then rounded to the
    # node's resolution. Both encoders get noise 0.05 rad; the right one still reads whole
    # steps of its 0.5.
    project = tmp_path / "project"
    shutil.copytree(WORLD.parent, project)
    world = project / "worlds" / "renamed_wheels.wbt"
    text = world.read_text()
    for name in ("encoder L", "encoder R"):
        text = text.replace(f'name "{name}"', f'name "{name}"\n          noise 0.05')
    world.write_text(text)
    run = run_world(str(world), seconds=2.0, noise=noise, seed=3)
    assert run.robots[0].exit_status == 0, run.robots[0].error
    (line,) = [x for x in capfd.readouterr().out.splitlines() if x.startswith("encoders read")]
    left, right = (float(word) for word in line.split()[2:])
    if not noise:
        assert (left, right) == (pytest.approx(1.92, abs=1e-9), 4.0), "no noise: exact"
    else:
        assert left != pytest.approx(1.92, abs=1e-6) and abs(left - 1.92) < 5 * 0.05
        assert right % 0.5 == 0.0 and abs(right - 3.84) < 0.5 + 5 * 0.05
