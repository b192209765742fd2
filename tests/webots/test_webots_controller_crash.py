"""A controller run in the command's own process (``mazesim webots run CONTROLLER.py``) that
crashes that process in native code: the command says so in one line (it once ended with the
shell's "Segmentation fault" alone); a run that ends by itself, or by Ctrl-C, says nothing of
the kind (``mazesim.cli.crash_guard``)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from mazesim.cli.crash_guard import runs_a_controller_here

CRASHING = """from controller import Robot
import ctypes

robot = Robot()
robot.step(32)
ctypes.string_at(0)  # reads address 0: SIGSEGV
"""
#: Steps at about real time (600 s of simulated time would take a second, sooner than Ctrl-C).
STEPPING = """import os
import time
from controller import Robot

robot = Robot()
robot.step(32)
open(os.environ["READY"], "w").close()
while robot.step(32) != -1:
    time.sleep(0.03)
"""
WORDS = "the Python controller crashed the run's process"


def _run(tmp_path: Path, source: str, *more: str) -> subprocess.Popen[str]:
    controller = tmp_path / "controller.py"
    controller.write_text(source)
    return subprocess.Popen(
        [sys.executable, "-m", "mazesim", "webots", "run", str(controller), "--no-progress",
         "--out", str(tmp_path / "out"), *more],
        cwd=tmp_path, env=dict(os.environ, READY=str(tmp_path / "ready")),
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True,
    )  # fmt: skip


def test_a_segmentation_fault_in_the_controller_is_said_in_one_line(tmp_path: Path) -> None:
    process = _run(tmp_path, CRASHING, "--seconds", "2")
    _, stderr = process.communicate(timeout=300)
    assert process.returncode == -signal.SIGSEGV
    assert stderr.count(WORDS) == 1, stderr


def test_a_run_that_ends_by_itself_or_by_ctrl_c_says_no_crash(tmp_path: Path) -> None:
    process = _run(tmp_path, STEPPING, "--seconds", "0.3")
    _, stderr = process.communicate(timeout=300)
    assert process.returncode == 0 and WORDS not in stderr, stderr
    (tmp_path / "ready").unlink()  # the first run's
    process = _run(tmp_path, STEPPING, "--seconds", "600")
    try:
        deadline = time.monotonic() + 120
        while not (tmp_path / "ready").exists():
            assert process.poll() is None and time.monotonic() < deadline, "it never started"
            time.sleep(0.05)
        os.killpg(process.pid, signal.SIGINT)  # as a terminal sends Ctrl-C: to the group
        _, stderr = process.communicate(timeout=300)
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
            process.communicate()
    assert process.returncode == 130 and WORDS not in stderr, stderr
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["reached_end"] is False and 0 < summary["simulated_seconds"] < 600


#: Made outside the command (a script, the package's public surface): a normal exit is no crash.
MADE_AND_LEFT = "from mazesim.cli.crash_guard import CrashWatch\nwatch = CrashWatch()\n"
#: A controller that forks, its child going back through the command's end: one word, the parent's.
FORKED = """import os
from mazesim.cli.crash_guard import CrashWatch

watch = CrashWatch()
if os.fork() == 0:
    watch.ended()
    os._exit(0)
os.wait()
watch.ended()
"""
#: What the watch is for: a process killed by a signal.
KILLED = MADE_AND_LEFT + "import os, signal\nos.kill(os.getpid(), signal.SIGKILL)\n"


@pytest.mark.parametrize(
    ("source", "crashed"),
    [(MADE_AND_LEFT, False), (FORKED, False), (KILLED, True)],
    ids=["made-and-left", "forked", "killed"],
)
def test_only_a_process_that_died_is_said_to_have_crashed(source: str, crashed: bool) -> None:
    # The watcher holds stderr until it ends: communicate() waits for its word.
    process = subprocess.run(
        [sys.executable, "-c", source], capture_output=True, text=True, timeout=120
    )
    assert process.returncode == (-signal.SIGKILL if crashed else 0), process.stderr
    assert process.stderr.count(WORDS) == int(crashed), process.stderr


@pytest.mark.parametrize(
    ("arguments", "watched"),
    [
        (["webots", "run", "c.py"], True),
        (["webots", "run", "c.py", "--world", "Maze.wbt"], True),
        (["webots", "run", "worlds/Maze.WBT", "--seconds", "5"], False),
        (["webots", "run", "--help"], False),
        (["demo"], False),
    ],
)
def test_only_a_controller_run_in_this_process_is_watched(
    arguments: list[str], watched: bool
) -> None:
    assert runs_a_controller_here(arguments) is watched
