"""``mazesim webots run --robot NAME|FILE``: a controller drives the robot profile given, as the
other commands' ``--robot`` does (issue 37)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import mazesim
from mazesim.cli import main

#: The avoid-collision example controller, as the Webots page runs it.
CONTROLLER = Path(__file__).resolve().parents[2] / "examples" / "webots" / "avoid_collision.py"


def _run(tmp_path: Path, *options: str) -> int:
    out = tmp_path / "out"
    return main(
        ["webots", "run", str(CONTROLLER), "--seconds", "0.5", "--out", str(out), "--no-progress"]
        + list(options)
    )


@pytest.mark.parametrize("kind", ["name", "file"])
def test_the_controller_drives_the_profile_given(tmp_path: Path, kind: str) -> None:
    if kind == "name":
        robot, expected = "e-puck2", "e-puck2"
    else:
        text = mazesim.RobotProfile.builtin("e-puck").to_toml()
        assert 'name = "e-puck"' in text
        profile = tmp_path / "my-epuck.toml"
        profile.write_text(text.replace('name = "e-puck"', 'name = "my-epuck"', 1))
        robot, expected = str(profile), "my-epuck"
    assert _run(tmp_path, "--robot", robot) == 0
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["robot"] == expected


def test_a_world_run_refuses_robot_and_says_why(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    world = tmp_path / "w.wbt"
    world.write_text("#VRML_SIM R2023b utf8\n")
    assert main(["webots", "run", str(world), "--robot", "e-puck2", "--no-progress"]) == 2
    assert "whose robots are the world's" in capsys.readouterr().err


def test_an_unknown_profile_is_named(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert _run(tmp_path, "--robot", "e-pluck") == 2
    assert "e-pluck" in capsys.readouterr().err
