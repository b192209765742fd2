"""A run in a world with a goal says whether the robot reached it and when: `mazesim demo` and
`mazesim webots run` alike, so one controller run over a folder of mazes gives a table."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from mazesim.cli import main
from mazesim.cli.demo import goal_summary

CORRIDOR = '''format = "mazesim-world"
version = 1

[grid]
map = """
+--+--+--+
|S     G |
+--+--+--+
"""
'''

STRAIGHT = """from controller import Robot

robot = Robot()
step = int(robot.getBasicTimeStep())
left = robot.getDevice("left wheel motor")
right = robot.getDevice("right wheel motor")
left.setPosition(float("inf"))
right.setPosition(float("inf"))
while robot.step(step) != -1:
    left.setVelocity(4.0)
    right.setVelocity(4.0)
"""


def test_goal_summary_gives_the_first_time_the_path_enters_the_goal_disc() -> None:
    class World:
        goal = (1.0, 0.0, 0.1)

    xs, ys = [0.0, 0.5, 0.95, 1.0, 2.0], [0.0] * 5
    assert goal_summary(World(), xs, ys, 0.5) == {"goal_reached": True, "goal_time_s": 1.0}
    assert goal_summary(World(), xs[:2], ys[:2], 0.5) == {
        "goal_reached": False,
        "goal_time_s": None,
    }
    World.goal = None  # type: ignore[assignment]
    assert goal_summary(World(), xs, ys, 0.5) == {"goal_reached": None, "goal_time_s": None}


def test_webots_run_reports_reaching_the_goal(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "corridor.toml").write_text(CORRIDOR)
    (tmp_path / "straight.py").write_text(STRAIGHT)
    runs = {"reached": "10", "short": "1"}
    for out, seconds in runs.items():
        status = main(
            [
                "webots", "run", str(tmp_path / "straight.py"),
                "--world", str(tmp_path / "corridor.toml"),
                "--seconds", seconds, "--out", str(tmp_path / out), "--no-progress",
            ]
        )  # fmt: skip
        assert status == 0
    printed = capsys.readouterr().out
    reached = json.loads((tmp_path / "reached" / "summary.json").read_text())
    short = json.loads((tmp_path / "short" / "summary.json").read_text())
    assert reached["goal_reached"] is True and 3.0 < reached["goal_time_s"] < 10.0
    assert f"goal reached       yes, at {reached['goal_time_s']:.2f} s" in printed
    assert short["goal_reached"] is False and short["goal_time_s"] is None
    assert "goal reached       no" in printed


def test_demo_summary_keeps_the_goals_time_too(tmp_path: Path) -> None:
    (tmp_path / "corridor.toml").write_text(CORRIDOR)
    out = tmp_path / "demo"
    world = str(tmp_path / "corridor.toml")
    assert (
        main(["demo", "--world", world, "--seconds", "2", "--out", str(out), "--no-progress"]) == 0
    )
    summary = json.loads((out / "summary.json").read_text())
    assert summary["goal_reached"] is False and summary["goal_time_s"] is None
