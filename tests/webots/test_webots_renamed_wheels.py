"""An e-puck saved expanded (a plain Robot node, the E-puck PROTO's tree written out) whose world
names its wheels' motors and position sensors otherwise (``left_motor``, ``encoder L``) has
them by those names, each driving its own wheel, as Webots finds devices by the names the
world gives (#32)."""

from __future__ import annotations

import math
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
    # 30 steps of 32 ms at 2 rad/s: the left wheel's encoder reads its 1.92 rad.
    assert "left wheel turned 1.92 rad" in capfd.readouterr().out
    assert robot.final_pose[0] > -0.5 + 0.03, "it drives ahead, not standing still"
    turned = math.remainder(robot.final_pose[2], 2 * math.pi)
    assert turned > 0.5, "the right wheel, faster, turns it left: each name drives its own wheel"
