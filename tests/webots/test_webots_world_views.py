"""A Webots world run of several robots with ``--record`` and ``--html``: the run file and the
replay hold every robot, where the summary has it (``--live`` alongside, headless here);
``--keys`` is refused there."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from mazesim.cli import main
from mazesim.replay import load_run

SWARM = Path(__file__).resolve().parent.parent / "data" / "webots-swarm"
WORLD = SWARM / "worlds" / "leader_followers.wbt"


def test_the_run_file_and_the_replay_hold_every_robot(tmp_path: Path) -> None:
    out = tmp_path / "run"
    env = dict(os.environ, SWARM_LOG=str(tmp_path), MPLBACKEND="Agg")
    result = subprocess.run(
        [sys.executable, "-m", "mazesim", "webots", "run", str(WORLD), "--seconds", "3"]
        + ["--out", str(out), "--record", str(tmp_path / "run.json.gz")]
        + ["--html", str(tmp_path / "replay.html"), "--live"],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
        check=False,
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


def test_keys_are_refused_in_a_world_run_naming_what_to_give(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    code = main(["webots", "run", str(WORLD), "--out", str(tmp_path / "o"), "--keys", "k.txt"])
    assert code == 2
    error = capsys.readouterr().err
    assert "--keys types on one controller's Keyboard; a world run" in error
    assert f"'mazesim webots run CONTROLLER --world {WORLD} --keys k.txt'" in error
