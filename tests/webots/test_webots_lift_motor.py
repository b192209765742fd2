"""An e-puck saved expanded whose wheels keep the PROTO's device names and which carries one more
motor of its own, naming neither wheel (a gripper's lift ``motor``), drives on its wheels' own
motors: the lone motor is a device of its own, not a wheel's, as in Webots (#32)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from mazesim.webots.lockstep import run_world

WORLD = Path(__file__).resolve().parent.parent / "data" / "webots-lift-motor" / "worlds"

pytestmark = pytest.mark.usefixtures("fresh_robot")


def test_a_lone_motor_naming_no_wheel_leaves_the_wheels_their_names(
    capfd: pytest.CaptureFixture[str],
) -> None:
    run = run_world(str(WORLD / "lift_motor.wbt"), seconds=2.0)
    (robot,) = run.robots
    assert robot.exit_status == 0, robot.error
    assert "left wheel motor found: True; lift motor found: True" in capfd.readouterr().out
    assert robot.final_pose[0] > -0.5 + 0.03, "both wheels drive it ahead"
    turned = math.remainder(robot.final_pose[2], 2 * math.pi)
    assert abs(turned) < 0.1, "the wheels turn alike: no wheel's motor is the lift's"
