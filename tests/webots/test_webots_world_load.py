"""A supervisor's ``worldLoad``: Webots ends every controller of the world and opens the one
named (reference manual, Supervisor, ``wb_supervisor_world_load``). A run of mazesim simulates
one world, so the world being run is reloaded (as ``worldReload`` does) and another world ends
the run there, with a line saying how to run it; a public project that loads five worlds in
turn stopped at its first call with an AttributeError."""

from __future__ import annotations

from pathlib import Path

import pytest

from supervised_world import cruising_controller
from swarm_project import run_project

pytestmark = pytest.mark.usefixtures("own_cache")

WORLD = """#VRML_SIM R2023b utf8
EXTERNPROTO "webots://projects/objects/floors/protos/RectangleArena.proto"
EXTERNPROTO "webots://projects/robots/gctronic/e-puck/protos/E-puck.proto"
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 2 2 }
E-puck { name "driver" controller "driver" }
Robot { name "loader" controller "loader" supervisor TRUE }
"""
#: The e-puck drives both wheels at 3 rad/s until the run ends.
DRIVER = cruising_controller(3.0)
LOADER = """import os
from controller import Supervisor
supervisor = Supervisor()
logs = os.environ["SWARM_LOG"]
target = os.environ.get("LOAD_TARGET", "")
steps = 0
def note(line):
    with open(os.path.join(logs, "loader.log"), "a") as out:
        out.write(line + "\\n")
note("start %.3f" % supervisor.getTime())
while supervisor.step(32) != -1:
    steps += 1
    if steps == 10 and not os.path.exists(os.path.join(logs, "loaded")):
        open(os.path.join(logs, "loaded"), "w").close()
        supervisor.worldLoad("missing.wbt")
        supervisor.worldLoad(target)
note("end %.3f %d" % (supervisor.getTime(), steps))
"""


def _project(root: Path) -> Path:
    for name, text in (("driver", DRIVER), ("loader", LOADER)):
        (root / "controllers" / name).mkdir(parents=True)
        (root / "controllers" / name / f"{name}.py").write_text(text)
    (root / "worlds").mkdir()
    for name in ("first", "second"):
        (root / "worlds" / f"{name}.wbt").write_text(WORLD)
    return root


def test_loading_another_world_ends_the_run_there_saying_how_to_run_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capfd: pytest.CaptureFixture[str]
) -> None:
    project = _project(tmp_path / "project")
    monkeypatch.setenv("LOAD_TARGET", "../../worlds/second.wbt")
    logs = tmp_path / "logs"
    done, _ = run_project(project, "first", logs, 2.0)
    err = capfd.readouterr().err
    assert "wb_supervisor_world_load(): 'missing.wbt' is not a .wbt world file" in err
    assert "a run simulates one world, so it ends here" in err
    assert "mazesim webots run ../../worlds/second.wbt" in err
    lines = (logs / "loader.log").read_text().splitlines()
    assert lines == ["start 0.000", "end 0.320 10"]
    assert all(robot.exit_status == 0 for robot in done.robots)
    # The e-puck drove 10 steps of 3 rad/s, not the 2 s asked for.
    assert done.robots[0].final_pose[0] == pytest.approx(10 * 0.032 * 3.0 * 0.02, abs=3e-3)


def test_loading_the_world_being_run_reloads_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    project = _project(tmp_path / "project")
    monkeypatch.setenv("LOAD_TARGET", str(project / "worlds" / "first.wbt"))
    logs = tmp_path / "logs"
    done, _ = run_project(project, "first", logs, 1.0)
    lines = (logs / "loader.log").read_text().splitlines()
    assert lines == ["start 0.000", "end 0.320 10", "start 0.000", "end 0.704 22"]
    assert [r.restarts_s for r in done.robots] == [[pytest.approx(0.32)]] * 2
