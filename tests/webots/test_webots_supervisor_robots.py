"""A supervisor imports e-pucks into a running world of several robots and removes robots:
an imported e-puck's controller starts and steps in lockstep with the others, its node is found
by DEF name and id and follows it; a removed robot's controller sees ``Robot.step`` return -1;
the first robot runs bit for bit as without the imports until them (#33)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from mazesim.webots.lockstep import run_world
from supervised_world import SWARM

pytestmark = pytest.mark.usefixtures("fresh_robot")

#: The spawner's steps of 32 ms at which it imports the e-pucks and removes them.
IMPORT_STEP, REMOVE_STEP, REMOVE_FIRST_STEP = 5, 40, 60


def spawned(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, spawn: bool = True) -> list:
    """The robots' runs of ``robot_spawner.wbt`` (the imports left out unless ``spawn``)."""
    tmp_path.mkdir(exist_ok=True)
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    if spawn:
        monkeypatch.delenv("SPAWN_NONE", raising=False)
    else:
        monkeypatch.setenv("SPAWN_NONE", "1")
    robots = run_world(str(SWARM / "worlds" / "robot_spawner.wbt"), seconds=3.0).robots
    assert [r.exit_status for r in robots] == [0] * len(robots), [r.error for r in robots]
    return list(robots)


def log(tmp_path: Path, name: str) -> dict:
    return json.loads((tmp_path / f"{name}.json").read_text())


def test_imported_e_pucks_run_their_controllers_and_removed_robots_end(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capfd: pytest.CaptureFixture[str]
) -> None:
    robots = spawned(tmp_path, monkeypatch)
    # The imports say nothing of a run of one controller, which this run is not.
    assert "alone simulates only" not in capfd.readouterr().err
    assert [r.name for r in robots] == ["spawner", "first", "new-a", "new-b"]
    spawner, first, new_a, new_b = robots
    seen = log(tmp_path, "spawner")
    # The scene tree: both imported, found by DEF name and id, their nodes live.
    assert seen["count_with"] == seen["count_before"] + 2 == seen["count_after"] + 1
    assert seen["new_a_type"] == "E-puck" and seen["new_a_found_by_id"] and seen["new_b_gone"]
    # Where its node puts it, in double precision, as Webots' fields hold it (not the
    # simulation's single precision, -0.6000000238418579).
    assert seen["new_a_at_import"][:2] == [-0.6, -0.3]
    assert seen["new_a_later"][0] > -0.6 + 0.05, "new-a's node follows it as it drives"
    # The imported robots' controllers started at the import and drove in lockstep.
    step_s = 0.032
    assert new_a.imported_s == pytest.approx(IMPORT_STEP * step_s)
    assert new_a.controller and new_a.controller.endswith("cruise.py")
    assert new_a.final_pose[0] > -0.6 + 0.15 and new_a.xs[0] == pytest.approx(-0.6)
    a_log = log(tmp_path, "new-a")
    # The run's 3 s are world time, as Webots' one clock: imported at step 5 of the 94, new-a
    # has the 89 steps left (its controller would take 90), not 3 s of its own.
    assert a_log["steps"] == 89 and a_log["ended"]
    # Its node's own camera width and turret device, not the built-in e-puck's.
    assert a_log["camera_width"] == 80 and "compass" in a_log["devices"]
    b_log = log(tmp_path, "new-b")
    assert b_log["camera_width"] == 52 and "compass" not in b_log["devices"]
    assert a_log["first_step_time"] == pytest.approx((IMPORT_STEP + 1) * step_s)
    # A removed robot's controller is answered the end at its next step, as after a
    # supervisor's quit: that step returns -1 (no step in which no time passes), and its path
    # ends there.
    assert b_log["ended"] and b_log["steps"] == REMOVE_STEP - IMPORT_STEP
    assert new_b.removed_s == pytest.approx(REMOVE_STEP * step_s)
    assert len(new_b.xs) == REMOVE_STEP - IMPORT_STEP + 1
    first_log = log(tmp_path, "first")
    assert first_log["ended"] and first_log["steps"] == REMOVE_FIRST_STEP
    assert first.removed_s == pytest.approx(REMOVE_FIRST_STEP * step_s)
    assert spawner.removed_s is None and new_a.removed_s is None


def test_the_first_robot_runs_as_without_the_imports_until_them(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    alone = spawned(tmp_path / "alone", monkeypatch, spawn=False)
    joined = spawned(tmp_path, monkeypatch)
    assert len(alone) == 2
    # Bit for bit until the import, and on after it (the new e-pucks are out of its reach).
    until = IMPORT_STEP + 1
    assert alone[1].xs[:until] == joined[1].xs[:until]
    assert alone[1].xs[:REMOVE_FIRST_STEP] == joined[1].xs[:REMOVE_FIRST_STEP]
    assert alone[1].ys[:REMOVE_FIRST_STEP] == joined[1].ys[:REMOVE_FIRST_STEP]


def test_an_imported_robot_that_is_no_e_puck_stands_as_an_obstacle_in_a_world_run(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capfd: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    robots = run_world(str(SWARM / "worlds" / "rover_spawner.wbt"), seconds=3.0).robots
    said = capfd.readouterr().err
    rover = [line for line in said.splitlines() if 'Robot "ROVER": a robot that is not' in line]
    assert len(rover) == 1 and "static obstacles" in rover[0], said
    # Said as the run has it: no controller of the rover starts, as the robots show.
    assert "imported while the world runs: its controller does not start" in rover[0], rover
    assert "its controller runs" not in rover[0], rover
    assert [r.exit_status for r in robots] == [0, 0], [r.error for r in robots]
    assert [r.name for r in robots] == ["spawner", "first"], "the rover is no robot of the run"
    seen = log(tmp_path, "spawner")
    assert seen["count_with"] == seen["count_before"] + 1 == seen["count_after"] + 1
    assert seen["crate"] == pytest.approx([-0.5, 0.3, 0.05]) and seen["gone"]
    # Held at the rover's face (x = -0.52) while it stood (step 3 to 40; about -0.50 there
    # without it), then on past it.
    first = robots[1]
    assert first.xs[38] < -0.52 - 0.037 + 1e-3, first.xs[38]
    assert first.final_pose[0] > first.xs[38] + 0.02


def test_an_imported_e_puck_gets_going_with_the_traction_of_the_world_files(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    monkeypatch.setenv("CRUISE_SPEED", "6.28")
    world = SWARM / "worlds" / "robot_spawner_8ms.wbt"  # 8 ms steps: traction takes 2 of them
    _, first, new_a, _ = run_world(str(world), seconds=1.0).robots
    went = [first.xs[k] - first.xs[0] for k in range(1, 6)]
    # From rest, the floor's friction holds the body back in its first step, at full speed.
    assert went[0] < 0.75 * 6.28 * 0.0205 * 0.008
    assert [new_a.xs[k] - new_a.xs[0] for k in range(1, 6)] == pytest.approx(went, abs=1e-6)
