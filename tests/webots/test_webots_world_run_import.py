"""A world run (``mazesim webots run WORLD``) starts as a run of one controller does: one line
summing up the import, then each thing the import lost, those about the world's other e-pucks
left out (the world run simulates them); ``summary.json`` keeps them and ``--strict`` refuses
them before any controller starts."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from mazesim.cli import main
from mazesim.webots.importer import import_wbt, world_run_warnings

#: Two e-pucks and a node type mazesim does not import.
WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 1 1 }
UNKNOWN
E-puck { translation 0.2 0 0 name "first" controller "step_once" }
E-puck { translation -0.2 0 0 name "second" controller "step_once" }
"""


def _project(tmp_path: Path, unknown: str) -> Path:
    """A project of :data:`WORLD` (``unknown`` in place of its third node); its world."""
    folder = tmp_path / "controllers" / "step_once"
    folder.mkdir(parents=True)
    (folder / "step_once.py").write_text("from controller import Robot\nRobot().step(32)\n")
    world = tmp_path / "worlds" / "two.wbt"
    world.parent.mkdir()
    world.write_text(WORLD.replace("UNKNOWN", unknown))
    return world


def test_the_other_e_pucks_warnings_concern_a_run_of_one_controller_only(tmp_path: Path) -> None:
    _, report = import_wbt(str(_project(tmp_path, "SomethingUnknown { }")))
    assert len(report["warnings"]) == 2, report["warnings"]
    (second,) = report["one_controller_warnings"]
    assert 'E-puck "second": a second e-puck: a run of one controller' in second
    (lost,) = world_run_warnings(report)
    assert "SomethingUnknown" in lost


def test_a_world_run_prints_and_keeps_what_its_import_lost(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    world = _project(tmp_path, "SomethingUnknown { }")
    status = main(["webots", "run", str(world), "--seconds", "0.1", "--out", str(tmp_path / "out")])
    stderr = capfd.readouterr().err
    assert status == 0, stderr
    assert "mazesim: two.wbt: 2 robots, each run by its own controller; 1 thing(s)" in stderr
    warnings = [line for line in stderr.splitlines() if line.startswith("mazesim: warning: ")]
    assert len(warnings) == 1 and "SomethingUnknown" in warnings[0], stderr
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    (lost,) = summary["import"]["not_imported"]
    assert "SomethingUnknown" in lost
    assert [robot["name"] for robot in summary["robots"]] == ["first", "second"]


def test_strict_refuses_a_world_whose_run_would_lose_something(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    world = _project(tmp_path, "SomethingUnknown { }")
    out = tmp_path / "out"
    status = main(["webots", "run", str(world), "--strict", "--out", str(out)])
    stderr = capfd.readouterr().err
    assert status == 2, stderr
    assert "--strict expects a world imported without warnings, found 1" in stderr
    assert not out.exists(), "nothing runs under --strict"


def test_strict_runs_a_world_of_several_e_pucks_that_loses_nothing(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    world = _project(tmp_path, "")
    out = tmp_path / "out"
    status = main(["webots", "run", str(world), "--strict", "--seconds", "0.1", "--out", str(out)])
    stderr = capfd.readouterr().err
    assert status == 0, stderr
    assert "everything imported" in stderr and "mazesim: warning:" not in stderr
    assert json.loads((out / "summary.json").read_text())["import"]["not_imported"] == []
