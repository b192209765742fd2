"""A two-wheeled robot built by hand as in Webots' own example worlds (a plain ``Robot`` whose
two HingeJoints hold RotationalMotors of the e-puck's names) is simulated as an e-puck in a
run of the whole world as in a run of its controller alone: one test decides, wherever the
run starts from (#32)."""

from __future__ import annotations

from pathlib import Path

import pytest

from mazesim.webots.importer import import_wbt, world_run_warnings
from mazesim.webots.lockstep import run_world

WORLD = Path(__file__).resolve().parent.parent / "data" / "webots-hand-built" / "worlds"

pytestmark = pytest.mark.usefixtures("fresh_robot")


def test_a_hand_built_two_wheeled_robot_drives_in_a_world_run_as_alone() -> None:
    path = str(WORLD / "hand_built.wbt")
    _, whole = import_wbt(path)
    _, alone = import_wbt(path, controller="drive")
    for report in (whole, alone):
        assert [robot["profile"] for robot in report["robots"]] == ["e-puck", None]
        assert report["robot_model"] == "E-puck"
    # The supervisor's warning says what the world run does with it: nothing stands in for it.
    said = [w for w in world_run_warnings(whole) if "Driver" in w]
    assert said and "its controller runs, its body does not move" in said[0], said
    assert not any("in its place" in w for w in whole["warnings"])
    run = run_world(path, seconds=1.0)
    robot, driver = run.robots
    assert [robot.exit_status, driver.exit_status] == [0, 0], [robot.error, driver.error]
    assert robot.xs[0] == pytest.approx(-0.5)
    assert robot.final_pose[0] > -0.5 + 0.05, "it drives ahead, not standing still"
    assert driver.distance_m == 0.0
