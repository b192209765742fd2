"""Every long command shows its progress through the one display: bars on a terminal (a real
pseudo-terminal here), plain lines in a log, nothing with ``--no-progress``."""

from __future__ import annotations

import fcntl
import os
import pty
import re
import struct
import subprocess
import sys
import termios
from pathlib import Path

import pytest

import mazesim.cli.progress
from mazesim.cli import main

REPO = Path(__file__).resolve().parents[2]
CONTROLLER = REPO / "examples" / "webots" / "avoid_collision.py"
#: A guard against a run that hangs, not a speed requirement.
TIME_LIMIT_S = 120

#: Each long command, small, with the stage and unit its bar shows.
COMMANDS = {
    "demo": (["demo", "--world", "arena", "--seconds", "3", "--out", "out"], "simulating", "steps"),
    "barcode-study": (
        [
            "barcode-study",
            "--readings",
            "4",
            "--envs",
            "4",
            "--thresholds",
            "1.4",
            "--speeds",
            "3.14",
            "--out",
            "out",
        ],
        "barcode-study",
        "readings",
    ),
    "transfer-study": (
        [
            "transfer-study",
            "--axes",
            "latency",
            "--episodes",
            "2",
            "--max-steps",
            "300",
            "--out",
            "out",
        ],
        "transfer",
        "episodes",
    ),
    "bench": (
        ["bench", "--envs", "1", "--blocks", "1", "--block-steps", "20", "--threads", "1"],
        "bench",
        "env-steps",
    ),
    "webots run": (
        ["webots", "run", str(CONTROLLER), "--seconds", "2", "--out", "out"],
        "simulating",
        "steps",
    ),
}


def _run_on_a_terminal(argv: list[str], cwd: Path) -> tuple[int, str, str]:
    """Runs ``mazesim argv`` with stderr on a pseudo-terminal and bars shown at once.

    Returns:
        The exit code, stdout, and what the terminal received.
    """
    code = (
        "import sys, mazesim.cli.progress as progress\n"
        "progress.BAR_DELAY_S = 0.0\n"
        "from mazesim.cli import main\n"
        "sys.exit(main(sys.argv[1:]))\n"
    )
    leader, follower = pty.openpty()
    # 24 rows of 120 columns: a new pseudo-terminal has no size.
    fcntl.ioctl(follower, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 120, 0, 0))
    with subprocess.Popen(
        [sys.executable, "-c", code, *argv],
        cwd=cwd,
        stdout=subprocess.PIPE,
        stderr=follower,
        stdin=subprocess.DEVNULL,
        env={**os.environ, "MPLBACKEND": "Agg"},
    ) as process:
        os.close(follower)
        received = bytearray()
        while True:
            try:
                chunk = os.read(leader, 4096)
            except OSError:  # the terminal's other end closed: the process ended
                break
            if not chunk:
                break
            received += chunk
        out = process.communicate(timeout=TIME_LIMIT_S)[0]
    os.close(leader)
    return process.returncode, out.decode(), received.decode(errors="replace")


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_a_long_command_shows_a_bar_with_eta_on_a_terminal(command: str, tmp_path: Path) -> None:
    argv, stage, unit = COMMANDS[command]
    code, out, terminal = _run_on_a_terminal(argv, tmp_path)
    assert code == 0, terminal
    assert f"{stage}: 100%" in terminal, terminal
    assert re.search(rf"\d+/\d+ {re.escape(unit)} \[\d\d:\d\d elapsed, ETA \d\d:\d\d, ", terminal)
    assert out  # the summary stays on stdout


def test_replay_shows_the_frames_of_a_video(tmp_path: Path) -> None:
    record = ["--record", str(tmp_path / "run.json.gz"), "--out", str(tmp_path / "demo")]
    assert main(["demo", "--world", "arena", "--seconds", "2", *record, "--no-progress"]) == 0
    code, _, terminal = _run_on_a_terminal(["replay", "run.json.gz", "-o", "run.gif"], tmp_path)
    assert code == 0, terminal
    assert "video: 100%" in terminal and " frames [" in terminal, terminal


def test_no_progress_leaves_the_terminal_alone(tmp_path: Path) -> None:
    argv, _, _ = COMMANDS["demo"]
    code, _, terminal = _run_on_a_terminal([*argv, "--no-progress"], tmp_path)
    assert code == 0
    assert terminal == ""


def test_in_a_log_a_long_run_writes_plain_lines_with_eta(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    monkeypatch.setattr(mazesim.cli.progress, "PLAIN_EVERY_S", 0.0)
    monkeypatch.chdir(tmp_path)
    argv, _, _ = COMMANDS["barcode-study"]
    assert main(argv) == 0
    lines = capsys.readouterr().err.splitlines()
    assert lines, "no progress lines"
    assert all(line.startswith("mazesim: barcode-study: ") for line in lines), lines
    stage, rate = "mazesim: barcode-study:", r"[\d.,]+ readings/s"
    assert re.fullmatch(rf"{stage} [1-3]/4 readings \(\d+%\), {rate}, ETA \d+:\d\d", lines[0])
    assert re.fullmatch(rf"{stage} 4/4 readings \(100%\) in \d:\d\d, {rate}", lines[-1])


def test_in_a_log_a_short_run_writes_no_progress(
    capsys: pytest.CaptureFixture[str], tmp_path: Path
) -> None:
    argv, _, _ = COMMANDS["demo"]
    assert main([*argv[:-1], str(tmp_path / "out")]) == 0
    assert capsys.readouterr().err == ""
