"""A Webots world run of several robots with ``--record`` and ``--html``: the run file and the
replay hold every robot, where the summary has it (``--live`` alongside, headless here), also
when one controller runs in such a world; ``--keys`` is refused in a world run."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pytest

from mazesim.cli import main
from mazesim.replay import load_run
from mazesim_process import mazesim_command

SWARM = Path(__file__).resolve().parent.parent / "data" / "webots-swarm"
WORLD = SWARM / "worlds" / "leader_followers.wbt"


def test_the_run_file_and_the_replay_hold_every_robot(tmp_path: Path) -> None:
    out = tmp_path / "run"
    env = dict(os.environ, SWARM_LOG=str(tmp_path), MPLBACKEND="Agg")
    result = mazesim_command(
        *("webots", "run", str(WORLD), "--seconds", "3", "--out", str(out), "--live"),
        *("--record", str(tmp_path / "run.json.gz"), "--html", str(tmp_path / "replay.html")),
        cwd=tmp_path,
        env=env,
    )
    assert result.returncode == 0, result.stderr
    assert "live view off" in result.stderr  # MPLBACKEND=Agg: the window would not show
    summary = json.loads((out / "summary.json").read_text())
    run = load_run(tmp_path / "run.json.gz")
    assert [robot.name for robot in run.robots] == ["leader", "near", "far"]
    episode = run.episodes[0]
    assert episode.frames == summary["steps"] + 1
    for track, robot in zip([episode, *episode.robots], summary["robots"]):
        assert track.poses[-1, :2] == pytest.approx(robot["final_pose"][:2], abs=1e-4)
        assert track.wheel_speeds is not None
    travelled = [
        float(np.linalg.norm(np.diff(track.poses[:, :2], axis=0), axis=1).sum())
        for track in [episode, *episode.robots]
    ]
    assert travelled == pytest.approx(
        [robot["distance_m"] for robot in summary["robots"]], abs=0.02
    )
    assert max(travelled) > 0.05
    page = (tmp_path / "replay.html").read_text()
    assert '"robot_name":"far"' in page
    assert str(tmp_path / "replay.html") in result.stdout


def test_one_controller_run_in_a_world_of_several_records_every_robot(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """``webots run CONTROLLER --world WORLD.toml`` of several robots: the controller drives
    robot 0, the others stand still, and the run file, the replay, the summary, the picture and
    the table hold them all."""
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    world = tmp_path / "pair.toml"
    world.write_text(
        'format = "mazesim-world"\nversion = 1\n'
        '[[robots]]\nname = "west"\nx = -0.3\ny = 0.0\n'
        '[[robots]]\nname = "east"\nx = 0.3\ny = 0.05\nyaw = 3.141592653589793\n'
    )
    controller = SWARM / "controllers" / "forward" / "forward.py"
    record, page = tmp_path / "run.json.gz", tmp_path / "replay.html"
    code = main(
        ["webots", "run", str(controller), "--world", str(world), "--seconds", "2"]
        + ["--out", str(tmp_path / "out"), "--record", str(record), "--html", str(page)]
    )
    assert code == 0, capsys.readouterr().err
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    run = load_run(record)
    assert [robot.name for robot in run.robots] == ["west", "east"]
    episode = run.episodes[0]
    (east,) = episode.robots
    assert episode.frames == east.frames == summary["steps"] + 1
    assert episode.poses[-1, :2] == pytest.approx(summary["final_pose"][:2], abs=1e-4)
    assert episode.poses[-1, 0] - episode.poses[0, 0] > 0.1, "west drove ahead"
    assert east.poses[0, :2] == pytest.approx([0.3, 0.05], abs=1e-6)
    assert np.array_equal(east.poses, np.repeat(east.poses[:1], east.frames, axis=0))
    assert east.wheel_speeds is not None and not east.wheel_speeds.any(), "east stood still"
    assert '"robot_name":"east"' in page.read_text()
    # The summary, the picture and the table hold every robot too.
    west_entry, east_entry = summary["robots"]
    assert west_entry["name"] == "west" and west_entry["controller"] == str(controller)
    assert west_entry["final_pose"] == pytest.approx(summary["final_pose"])
    assert west_entry["distance_m"] == pytest.approx(summary["distance_m"])
    assert east_entry["name"] == "east" and east_entry["controller"] is None
    assert east_entry["distance_m"] == 0.0 and east_entry["robot"] == west_entry["robot"]
    assert east_entry["final_pose"][:2] == pytest.approx([0.3, 0.05], abs=1e-6)
    rows = (tmp_path / "out" / "trajectory.csv").read_text().splitlines()
    assert rows[0] == "robot,time_s,x_m,y_m"
    for robot, track in (("west", episode), ("east", east)):
        points = np.array([row.split(",")[2:] for row in rows[1:] if row.startswith(robot + ",")])
        assert points.astype(float) == pytest.approx(track.poses[:, :2], abs=1e-4)
    assert (tmp_path / "out" / "trajectory.png").stat().st_size > 0
    assert "east             no controller: 0.00 m" in capsys.readouterr().out


def test_a_controller_that_fails_at_once_in_a_world_of_several_lists_every_robot(
    tmp_path: Path,
) -> None:
    world = tmp_path / "pair.toml"
    world.write_text(
        'format = "mazesim-world"\nversion = 1\n'
        '[[robots]]\nname = "west"\nx = -0.3\ny = 0.0\n'
        '[[robots]]\nname = "east"\nx = 0.3\ny = 0.05\nprofile = "e-puck2"\n'
    )
    controller = tmp_path / "broken.py"
    controller.write_text("raise RuntimeError('no robot today')\n")
    code = main(["webots", "run", str(controller), "--world", str(world), "--out", str(tmp_path)])
    assert code == 1
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert [(r["name"], r["robot"], r["distance_m"]) for r in summary["robots"]] == [
        ("west", "e-puck", 0.0),
        ("east", "e-puck2", 0.0),
    ]
    assert summary["robots"][1]["final_pose"] == pytest.approx([0.3, 0.05, 0.0])
    assert (tmp_path / "trajectory.csv").read_text().splitlines()[1:] == [
        "west,0.000,-0.30000,0.00000",
        "east,0.000,0.30000,0.05000",
    ]


def test_a_world_run_takes_a_key_script_and_refuses_a_malformed_one(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    """``--keys`` types on every controller of a world run (these enable no keyboard, so they
    run as without it); a malformed script is refused before the run, naming its line."""
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    keys = tmp_path / "k.txt"
    keys.write_text("0.1 UP\n")
    out = tmp_path / "o"
    code = main(
        ["webots", "run", str(WORLD), "--seconds", "0.5", "--out", str(out), "--keys", str(keys)]
    )
    assert code == 0
    assert len(json.loads((out / "summary.json").read_text())["robots"]) > 1
    keys.write_text("0.1 UP\nsoon UP\n")
    code = main(["webots", "run", str(WORLD), "--out", str(tmp_path / "p"), "--keys", str(keys)])
    assert code == 2
    assert f"{keys}:2" in capsys.readouterr().err
    assert not (tmp_path / "p" / "summary.json").exists()
