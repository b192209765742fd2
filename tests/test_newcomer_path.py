"""The parts of ``make newcomer-check`` (tests/newcomer_path.py), quickly: what it takes for a
misleading line or a missing duration, and the refusal of a maze without checkpoints, run with
this installation's ``mazesim``."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import newcomer_path

ROOT = Path(__file__).resolve().parents[1]
VENV_BIN = Path(sys.executable).parent

#: What pip printed before `make demo` kept its notes on skipped extras out.
PIP_NOTE = "Ignoring gymnasium: markers 'extra == \"gym\"' don't match your environment"


#: The command `make demo` runs, after its build.
DEMO = [
    "demo",
    "--controller",
    "hrl",
    "--out",
    "mazesim-demo",
    "--html",
    "mazesim-demo/replay.html",
]


def _demo_output(tmp_path: Path) -> str:
    finished = subprocess.run(
        [str(VENV_BIN / "mazesim"), *DEMO],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        check=True,
    )
    return finished.stdout + finished.stderr


def test_the_demo_says_how_long_its_run_took_and_warns_of_nothing(tmp_path: Path) -> None:
    printed = _demo_output(tmp_path)
    assert newcomer_path.misleading_lines(printed) == []
    (timed,) = newcomer_path.duration_lines(printed)
    assert timed.startswith("wall-clock time")
    # With the lines that `make build` and `make demo` print, nothing is missing.
    built = "make build: built and installed in 98 s\n"
    assert newcomer_path.demo_problems(built + printed + _make_demo_last_line()) == []
    missing = newcomer_path.demo_problems(printed)
    assert missing == [
        "the build does not say how long it took ('make build: ... in N s')",
        "make demo does not say where the mazesim command is",
    ]
    assert "mazesim-demo/replay.html in a browser" in printed


def _make_demo_last_line() -> str:
    """The line ``make demo`` prints after the demo's run, as a dry run of it gives it."""
    dry_run = subprocess.run(
        ["make", "--no-print-directory", "-n", "demo"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    assert " ".join(DEMO) in dry_run, dry_run
    (said,) = [line for line in dry_run.splitlines() if line.startswith('echo "make demo:')]
    return subprocess.run(["sh", "-c", said], capture_output=True, text=True, check=True).stdout


@pytest.mark.parametrize(
    "line",
    [
        PIP_NOTE,
        "WARNING: Running pip as the 'root' user can result in broken permissions",
        "warning: unused variable: `x`",
        "/x/y.py:3: DeprecationWarning: mazesim.hrl is deprecated",
        "Traceback (most recent call last):",
    ],
)
def test_a_line_that_looks_like_trouble_is_caught(line: str) -> None:
    output = f"make venv: installed in 12 s\n{line}\nwall-clock time    2.5 s (the run)\n"
    assert newcomer_path.misleading_lines(output) == [line]
    assert f"misleading line: {line!r}" in newcomer_path.demo_problems(output)


@pytest.mark.skipif(shutil.which("make") is None, reason="needs make")
def test_make_build_and_venv_say_how_long_they_took(tmp_path: Path) -> None:
    dry_run = subprocess.run(
        ["make", "--no-print-directory", "-n", "demo", f"VENV={tmp_path / 'venv'}"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    develop = next(line for line in dry_run.splitlines() if "maturin develop" in line)
    after = dry_run[dry_run.index(develop) :]
    assert 'echo "make build: built and installed in $(( $(date +%s) - start )) s"' in after
    assert 'echo "make venv: installed in $(( $(date +%s) - start )) s"' in dry_run


def test_a_maze_without_checkpoints_is_refused_before_training(tmp_path: Path) -> None:
    problems, (made, train) = newcomer_path.refusal_problems(VENV_BIN, tmp_path)
    assert problems == [], problems
    assert made.returncode == 0 and (tmp_path / "corridor.toml").exists()
    assert train.returncode == 2 and "no barcode checkpoints" in train.output
    assert "the navigator cannot learn world" in train.output
    assert not (tmp_path / "corridor-navigator").exists()


def test_the_recipe_the_check_runs_is_the_pages() -> None:
    commands, shown = newcomer_path.recipe_commands(ROOT)
    page = (ROOT / newcomer_path.RECIPE).read_text(encoding="utf-8")
    assert len(commands) == 5 and all(f"$ {command}" in page for command in commands)
    assert shown.startswith("wrote my-maze.png\n")
