"""``mazesim eval`` shows its progress with an ETA: the episodes, through the one display."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from test_command_progress import _run_on_a_terminal

from mazesim.cli import main

EVAL = ["eval", "--episodes", "3", "--max-steps", "300", "--events", "truth"]


def test_eval_shows_a_bar_with_eta_on_a_terminal(tmp_path: Path) -> None:
    code, out, terminal = _run_on_a_terminal(EVAL, tmp_path)
    assert code == 0, terminal
    assert "evaluate: 100%" in terminal, terminal
    assert re.search(r"3/3 episodes \[\d\d:\d\d elapsed, ETA \d\d:\d\d, ", terminal), terminal
    assert "success rate" in out


def test_eval_in_unseen_mazes_shows_the_adaptation_then_the_episodes(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    import mazesim.learn.evaluate

    monkeypatch.setattr(mazesim.cli.progress, "PLAIN_EVERY_S", 0.0)
    monkeypatch.setattr(mazesim.learn.evaluate, "ADAPT_EPISODES", 4)
    argv = ["eval", "--world", "random", "--mazes", "2", "--episodes", "2", "--max-steps", "300"]
    assert main([*argv, "--events", "truth"]) == 0
    lines = capsys.readouterr().err.splitlines()
    stages = [line.split(":")[1].strip() for line in lines]
    assert stages[0] == "adapt" and stages[-1] == "evaluate", lines
    assert re.fullmatch(r"mazesim: evaluate: 2/2 episodes \(100%\) in \d:\d\d, .*", lines[-1])
    assert any("ETA" in line for line in lines), lines


def test_no_progress_keeps_eval_quiet(capsys: pytest.CaptureFixture[str]) -> None:
    assert main([*EVAL, "--no-progress"]) == 0
    assert capsys.readouterr().err == ""
