"""A robot that is not an e-puck stands in the world as its collision shapes, a static obstacle,
whichever run it is in: a run of the whole world and a run of an e-puck's controller alone stop
the e-puck at its face alike, and so does a run of the whole world whose only robot of the file
is that robot, a supervisor that imports the e-puck (#33)."""

from __future__ import annotations

from pathlib import Path

import pytest

from mazesim.webots.importer import import_wbt
from mazesim.webots.lockstep import run_world
from mazesim.webots.runner import run_controller
from mazesim.webots.scene import read_scene
from supervised_world import SWARM

pytestmark = pytest.mark.usefixtures("fresh_robot")

#: Where the e-puck's centre stops: the box's face (x = -0.05) less the e-puck's radius.
AT_THE_FACE = -0.05 - 0.037
#: Where it would be after 2 s without the box: 6.28 rad/s on 0.02 m wheels from x = -0.3.
WITHOUT_THE_BOX = -0.3 + 6.28 * 0.02 * 2.0


def test_a_robot_of_the_file_that_is_no_e_puck_stops_an_e_puck_in_every_run(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    monkeypatch.setenv("CRUISE_SPEED", "6.28")
    path = SWARM / "worlds" / "rover_ahead.wbt"
    rover, first = run_world(str(path), seconds=2.0, noise=False).robots
    assert [rover.name, first.name] == ["rover", "first"]
    world, report = import_wbt(path, controller="cruise")
    scene = read_scene(path.read_text(), report.get("robot_model"), report.get("robot_line"))
    cruise = SWARM / "controllers" / "cruise"
    alone = run_controller(
        cruise, world, seconds=2.0, noise=False, report=dict(report), scene=scene
    )
    for run in (first, alone):
        assert run.exit_status == 0, run.error
        assert run.final_pose[0] == pytest.approx(AT_THE_FACE, abs=2e-3), run.final_pose
        assert run.final_pose[0] < WITHOUT_THE_BOX - 0.03, "held at the rover, not through it"
    assert first.final_pose[0] == pytest.approx(alone.final_pose[0], abs=1e-6)


def test_a_supervisor_that_is_the_only_robot_of_its_file_stops_the_e_puck_it_imports(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    monkeypatch.setenv("CRUISE_SPEED", "6.28")
    path = SWARM / "worlds" / "station.wbt"
    # The run of its controller alone simulates the e-puck in the station's place; the run of
    # the whole world simulates nothing there: the station's box stays a box.
    _, whole = import_wbt(path)
    said = [w for w in whole["warnings"] if '"station"' in w]
    assert said and "a run of the whole world simulates nothing in its place" in said[0], said
    station, first = run_world(str(path), seconds=2.0, noise=False).robots
    assert [station.name, first.name] == ["station", "first"]
    assert [station.exit_status, first.exit_status] == [0, 0], [station.error, first.error]
    assert first.final_pose[0] == pytest.approx(AT_THE_FACE, abs=2e-3), first.final_pose
    assert first.collisions > 0
