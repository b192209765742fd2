"""A two-wheeled robot built by hand as in Webots' own example worlds (a plain ``Robot`` whose
two HingeJoints hold RotationalMotors of the e-puck's names) is simulated, on its own wheels
(2.5 cm, 9 cm apart), in a run of the whole world as in a run of its controller alone: one test
decides, wherever the run starts from (#32)."""

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
        # Its node type: neither its name, its model nor a ps0 says it is an e-puck.
        assert report["robot_model"] == "Robot"
    # The supervisor's warning says what the world run does with it: nothing stands in for it.
    said = [w for w in world_run_warnings(whole) if "Driver" in w]
    assert said and "its controller runs, its body does not move" in said[0], said
    assert not any("in its place" in w for w in whole["warnings"])
    run = run_world(path, seconds=1.0)
    robot, driver = run.robots
    assert [robot.exit_status, driver.exit_status] == [0, 0], [robot.error, driver.error]
    assert robot.xs[0] == pytest.approx(-0.5)
    # 4 rad/s on its own wheels of 2.5 cm (its end points' height: they have no
    # boundingObject): 0.1 m/s, where the e-puck's 2 cm wheels would roll 0.08 m/s.
    steps = len(robot.xs) - 1
    assert robot.final_pose[0] + 0.5 == pytest.approx(steps * 0.032 * 4.0 * 0.025, rel=0.02)
    assert driver.distance_m == 0.0
