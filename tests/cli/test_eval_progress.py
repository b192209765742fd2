"""``mazesim eval`` shows its progress with an ETA: the episodes, through the one display."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from test_command_progress import _run_on_a_terminal

from mazesim.cli import main
from mazesim.cli import progress as progress_module
from mazesim.learn import evaluate as learn_evaluate

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
    monkeypatch.setattr(progress_module, "PLAIN_EVERY_S", 0.0)
    monkeypatch.setattr(learn_evaluate, "ADAPT_EPISODES", 4)
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


def test_sweep_shows_its_runs_with_eta(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    monkeypatch.setattr(progress_module, "PLAIN_EVERY_S", 0.0)
    config = tmp_path / "tiny.toml"
    config.write_text(
        '[grid]\ntrainer = "baseline"\nseed = [0, 1]\nmaze_size = 3\nenvs = 2\nsteps = 20\n'
        "episode_steps = 30\neval_episodes = 1\n"
    )
    out = str(tmp_path / "out")
    assert main(["sweep", str(config), "--out", out, "--sequential", "--quiet"]) == 0
    lines = capsys.readouterr().err.splitlines()
    assert any(re.fullmatch(r"mazesim: sweep: 1/2 runs \(50%\), .*ETA \d+:\d\d", x) for x in lines)
    assert re.fullmatch(r"mazesim: sweep: 2/2 runs \(100%\) in \d:\d\d, .*", lines[-1]), lines
