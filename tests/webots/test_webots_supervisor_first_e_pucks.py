"""A world without an e-puck whose only robot is a supervisor that imports the swarm (as a
lecture's coverage supervisor does): the imported e-pucks are the world's first; they make
the e-pucks' shared simulator on the running clock, their controllers start at the import and
drive in lockstep, and their nodes follow them (#33)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from mazesim.webots.lockstep import run_world
from supervised_world import SWARM

pytestmark = pytest.mark.usefixtures("fresh_robot")

#: The importer's step of 32 ms at which it imports the e-pucks.
IMPORT_STEP = 5
STEP_S = 0.032


def test_a_supervisor_alone_imports_the_worlds_first_e_pucks_which_then_drive(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capfd: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    run = run_world(str(SWARM / "worlds" / "swarm_importer.wbt"), seconds=3.0)
    assert "refused by mazesim" not in capfd.readouterr().err
    assert [r.name for r in run.robots] == ["importer", "new-a", "new-b"]
    assert [r.exit_status for r in run.robots] == [0, 0, 0], [r.error for r in run.robots]
    importer, new_a, new_b = run.robots
    assert new_a.imported_s == pytest.approx(IMPORT_STEP * STEP_S)
    # On the running clock: their first step is the world's next one, not its first.
    for name in ("new-a", "new-b"):
        log = json.loads((tmp_path / f"{name}.json").read_text())
        assert log["first_step_time"] == pytest.approx((IMPORT_STEP + 1) * STEP_S)
        # The run's 3 s are world time (94 steps of 32 ms), as Webots' one clock: an e-puck
        # imported at step 5 has the 89 steps left, not 3 s of its own from its import.
        assert log["steps"] == 89 and log["ended"]
    assert run.steps == 94
    # Each drives ahead from where it was put (new-b faces -x).
    assert new_a.xs[0] == pytest.approx(-0.6) and new_a.final_pose[0] > -0.6 + 0.2
    assert new_b.xs[0] == pytest.approx(0.2) and new_b.final_pose[0] < 0.2 - 0.2
    seen = json.loads((tmp_path / "importer.json").read_text())
    assert seen["new_a_at_import"][:2] == pytest.approx([-0.6, -0.3])
    assert seen["new_a_later"][0] > -0.6 + 0.05, "its node follows it"
    assert seen["new_b_later"][0] < 0.2 - 0.05
