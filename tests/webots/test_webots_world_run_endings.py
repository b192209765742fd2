"""How a world run (``mazesim webots run WORLD``) ends when a controller fails or Ctrl-C is
pressed: a controller's traceback is printed once; Ctrl-C stops every controller quietly, and
the command exits with 130, one line saying the run was interrupted, and whole output files
that cover the run until then."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from mazesim.cli import main
from supervised_world import project_of

#: Two e-pucks, each running the controller its name says.
WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 1 1 }
E-puck { translation 0.2 0 0 name "first" controller "FIRST" }
E-puck { translation -0.2 0 0 name "second" controller "SECOND" }
"""
#: A controller that fails in a function of its own after a step.
FAILING = """
from controller import Robot

robot = Robot()
robot.step(32)

def steer():
    raise ValueError("no wall to follow")

steer()
"""
#: A controller that reads its sensors at every step (each reading a call to the world's
#: process), and says once it has taken ten steps.
BUSY = """
import os
from controller import Robot

robot = Robot()
sensors = [robot.getDevice(f"ps{i}") for i in range(8)]
for sensor in sensors:
    sensor.enable(32)
steps = 0
while robot.step(32) != -1:
    values = [sensor.getValue() for sensor in sensors]
    steps += 1
    if steps == 10:
        open(os.path.join(os.environ["READY_DIR"], robot.getName()), "w").close()
"""


def _project(tmp_path: Path, first: str, second: str) -> Path:
    """A project of :data:`WORLD` whose robots run ``first`` and ``second``; its world."""
    text = WORLD.replace("FIRST", "first").replace("SECOND", "second")
    return project_of(tmp_path, "two.wbt", text, {"first": first, "second": second})


def test_a_failing_controller_s_traceback_is_printed_once(
    tmp_path: Path, capfd: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    world = _project(tmp_path, FAILING, BUSY)
    monkeypatch.setenv("READY_DIR", str(tmp_path))
    status = main(["webots", "run", str(world), "--seconds", "0.5", "--out", str(tmp_path / "out")])
    # The controllers' processes write to the same file descriptors as this one.
    stderr = capfd.readouterr().err
    assert status == 1, stderr
    assert stderr.count("Traceback (most recent call last)") == 1, stderr
    assert stderr.count("ValueError: no wall to follow") == 1, stderr
    assert 'in steer\n    raise ValueError("no wall to follow")' in stderr
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    first = summary["robots"][0]
    assert first["controller_error"] == "ValueError: no wall to follow"


def test_ctrl_c_stops_every_controller_quietly_and_exits_130(tmp_path: Path) -> None:
    world = _project(tmp_path, BUSY, BUSY)
    out = tmp_path / "out"
    process = subprocess.Popen(
        [sys.executable, "-m", "mazesim", "webots", "run", str(world), "--seconds", "600",
         "--out", str(out)],
        cwd=tmp_path, env=dict(os.environ, READY_DIR=str(tmp_path)), stdout=subprocess.PIPE,
        stderr=subprocess.PIPE, text=True, start_new_session=True,
    )  # fmt: skip
    try:
        deadline = time.monotonic() + 120
        while not all((tmp_path / name).exists() for name in ("first", "second")):
            assert process.poll() is None and time.monotonic() < deadline, "the run went on"
            time.sleep(0.05)
        # Ctrl-C reaches the terminal's whole process group: the world's process and every
        # controller's.
        os.killpg(process.pid, signal.SIGINT)
        stdout, stderr = process.communicate(timeout=300)
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
            process.communicate()
    assert process.returncode == 130, stderr
    assert "Traceback" not in stderr, stderr
    (line,) = [line for line in stderr.splitlines() if "interrupted" in line]
    assert line.startswith("mazesim: interrupted at ")
    summary = json.loads((out / "summary.json").read_text())
    assert summary["interrupted"] is True and summary["exit_status"] == 130
    assert summary["steps"] >= 10
    assert [robot["exit_status"] for robot in summary["robots"]] == [0, 0]
    rows = (out / "trajectory.csv").read_text().splitlines()
    assert len(rows) == 1 + 2 * (summary["steps"] + 1)
    assert "(seed 0, 2 robots)" in stdout


#: A supervisor that quits the simulation once it has taken ten steps.
QUITTING = """
from controller import Supervisor

supervisor = Supervisor()
steps = 0
while supervisor.step(32) != -1:
    steps += 1
    if steps == 10:
        supervisor.simulationQuit(0)
"""
#: A controller that says how many steps it took, and at what time, once ``step`` returns -1.
COUNTING = """
from controller import Robot

robot = Robot()
steps = 0
while robot.step(32) != -1:
    steps += 1
print(f"counted {steps} steps, at {robot.getTime():.3f} s")
"""


def test_another_robot_s_quit_ends_a_controller_s_step_without_one_more_step(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    text = WORLD.replace('controller "FIRST"', 'controller "first" supervisor TRUE')
    text = text.replace("SECOND", "second")
    world = project_of(tmp_path, "two.wbt", text, {"first": QUITTING, "second": COUNTING})
    status = main(["webots", "run", str(world), "--seconds", "5", "--out", str(tmp_path / "out")])
    stdout = capfd.readouterr().out
    assert status == 0, stdout
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    # The world takes the supervisor's ten steps; the other controller's eleventh is answered
    # with the end, as in Webots, not with a step in which no time passes.
    assert summary["steps"] == 10
    assert "counted 10 steps, at 0.320 s" in stdout, stdout


#: A C controller that never steps: it runs until the run is stopped.
NEVER_STEPPING_C = """#include <webots/robot.h>
int main(void) {
  wb_robot_init();
  for (;;) {
  }
}
"""


def _running(program: Path) -> list[int]:
    """The processes whose ``argv[0]`` is ``program`` (a built controller runs from the build
    cache under the name Webots starts it by, its folder's)."""
    found = []
    for entry in Path("/proc").iterdir():
        try:
            if not entry.name.isdigit():
                continue
            command = (entry / "cmdline").read_bytes().split(b"\0")[0]
            if command == os.fsencode(program) and (entry / "stat").read_text().split()[2] != "Z":
                found.append(int(entry.name))
        except OSError:
            continue
    return found


@pytest.mark.skipif(not Path("/proc/self/exe").exists(), reason="reads /proc")
def test_ctrl_c_ends_a_c_controller_that_never_steps_with_the_run(tmp_path: Path) -> None:
    # Its own process, started by the robot's controller process, outlived the run at 100 % CPU
    # (the controller process was killed, the program not), holding the terminal's output open.
    world = _project(tmp_path, "", BUSY)
    folder = tmp_path / "controllers" / "first"
    for old in folder.iterdir():
        old.unlink()
    (folder / "first.c").write_text(NEVER_STEPPING_C)
    program = folder / "first"
    process = subprocess.Popen(
        [sys.executable, "-m", "mazesim", "webots", "run", str(world), "--seconds", "600",
         "--out", str(tmp_path / "out"), "--no-progress"],
        cwd=tmp_path, env=dict(os.environ, READY_DIR=str(tmp_path)), stdout=subprocess.PIPE,
        stderr=subprocess.PIPE, text=True, start_new_session=True,
    )  # fmt: skip
    try:
        deadline = time.monotonic() + 120
        while not _running(program):
            assert process.poll() is None and time.monotonic() < deadline, "it never started"
            time.sleep(0.05)
        os.killpg(process.pid, signal.SIGINT)
        _, stderr = process.communicate(timeout=300)
        assert process.returncode == 130, stderr
        deadline = time.monotonic() + 10
        while _running(program) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert _running(program) == [], "the controller ran on after the run"
    finally:
        for pid in _running(program):
            os.kill(pid, signal.SIGKILL)
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
            process.communicate()


#: A controller that steps while the other robot's controller counts its steps, then ends as
#: ENDING says (a line of Python).
ENDING_AFTER_A_STEP = """
import os
import signal
import sys

from controller import Robot

robot = Robot()
robot.step(32)
ENDING
"""


def _run_ending(
    tmp_path: Path, capfd: pytest.CaptureFixture[str], ending: str
) -> tuple[int, str, dict[str, object]]:
    """Runs :data:`WORLD` with the first robot ending as ``ending`` says; the command's status,
    its stderr and the summary of the first robot (the second's is checked here)."""
    world = _project(tmp_path, ENDING_AFTER_A_STEP.replace("ENDING", ending), COUNTING)
    out = tmp_path / "out"
    status = main(["webots", "run", str(world), "--seconds", "0.5", "--out", str(out)])
    captured = capfd.readouterr()
    assert "Traceback" not in captured.err, captured.err
    # The other robot's run is whole, and so are the outputs.
    assert "counted 16 steps, at 0.512 s" in captured.out, captured.out
    summary = json.loads((out / "summary.json").read_text())
    assert summary["exit_status"] == status
    assert summary["robots"][1]["exit_status"] == 0
    assert summary["robots"][1]["controller_error"] is None
    assert "  second           second.py:" in captured.out
    rows = (out / "trajectory.csv").read_text().splitlines()
    assert len(rows) == 1 + 2 * (summary["steps"] + 1)
    return status, captured.err, summary["robots"][0]


def _robot_lines(stderr: str) -> list[str]:
    return [line for line in stderr.splitlines() if line.startswith("mazesim: robot 'first'")]


@pytest.mark.parametrize(
    ("ending", "error"),
    [
        (
            "os.kill(os.getpid(), signal.SIGSEGV)",
            "the Python controller crashed: killed by SIGSEGV",
        ),
        (
            "os.kill(os.getpid(), signal.SIGKILL)",
            "the Python controller crashed: killed by SIGKILL",
        ),
    ],
)
def test_a_python_controller_killed_by_a_signal_is_reported_as_a_c_one(
    tmp_path: Path, capfd: pytest.CaptureFixture[str], ending: str, error: str
) -> None:
    status, stderr, first = _run_ending(tmp_path, capfd, ending)
    assert status == 1
    assert _robot_lines(stderr) == [f"mazesim: robot 'first': {error}"]
    assert first["exit_status"] == 1
    assert first["controller_error"] == error


def test_a_python_controller_s_os_exit_is_reported_with_its_status(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    status, stderr, first = _run_ending(tmp_path, capfd, "os._exit(3)")
    assert status == 3
    error = (
        "the Python controller's process exited with status 3 without its report (as os._exit "
        "ends a process; sys.exit or a return sends it)"
    )
    assert _robot_lines(stderr) == [f"mazesim: robot 'first': {error}"]
    assert first["exit_status"] == 3
    assert first["controller_error"] == error


def test_an_os_exit_0_is_a_quiet_end(tmp_path: Path, capfd: pytest.CaptureFixture[str]) -> None:
    status, stderr, first = _run_ending(tmp_path, capfd, "sys.stdout.flush(); os._exit(0)")
    assert status == 0
    assert _robot_lines(stderr) == []
    assert first["exit_status"] == 0 and first["controller_error"] is None


@pytest.mark.parametrize("code", [2**40, 2**40 + 3, -1, 2**70])
def test_a_huge_sys_exit_status_is_the_one_the_process_would_have(
    tmp_path: Path, capfd: pytest.CaptureFixture[str], code: int
) -> None:
    real = subprocess.run([sys.executable, "-c", f"raise SystemExit({code})"]).returncode
    status, stderr, first = _run_ending(tmp_path, capfd, f"raise SystemExit({code})")
    assert first["exit_status"] == real
    assert status == real, "the command's status is its robot's"
    assert _robot_lines(stderr) == []


def test_a_controller_that_closes_its_standard_streams_still_reports(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    ending = "sys.stdout.close()\nsys.stderr.close()\nrobot.step(32)"
    status, stderr, first = _run_ending(tmp_path, capfd, ending)
    assert status == 0
    assert _robot_lines(stderr) == []
    assert first["exit_status"] == 0 and first["controller_error"] is None


def test_a_run_of_one_controller_that_closes_its_streams_prints_its_summary(
    tmp_path: Path,
) -> None:
    ending = "sys.stdout.close()\nsys.stderr.close()\nrobot.step(32)"
    world = _project(tmp_path, ENDING_AFTER_A_STEP.replace("ENDING", ending), BUSY)
    controller = world.parent.parent / "controllers" / "first" / "first.py"
    done = subprocess.run(
        [sys.executable, "-m", "mazesim", "webots", "run", str(controller), "--seconds", "0.5",
         "--out", str(tmp_path / "out"), "--no-progress"],
        cwd=tmp_path, capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert done.stderr == "", done.stderr
    assert "controller         first.py (the controller returned)" in done.stdout
    assert "wrote " in done.stdout
    assert json.loads((tmp_path / "out" / "summary.json").read_text())["exit_status"] == 0


@pytest.mark.parametrize(
    ("ending", "error"),
    [
        (
            "os.closerange(3, 256)\nrobot.step(32)",
            "the controller's link to the world's process was lost: the controller closed its "
            "file descriptor (os.close or os.closerange): close only the files it opened",
        ),
        (
            # Both processes step; the controller's waits for the other, then steps on.
            "pid = os.fork()\nrobot.step(32)\nos.waitpid(pid, 0) if pid else None\nrobot.step(32)",
            "a process the controller forked (pid PID) called Robot.step: only the controller's "
            "own process is linked to the world's process, so that process was stopped; call "
            "the API from the controller's process (a thread, or a forked process that only "
            "computes)",
        ),
    ],
    ids=["closerange", "fork"],
)
def test_a_controller_that_breaks_its_link_is_reported_in_one_line(
    tmp_path: Path, capfd: pytest.CaptureFixture[str], ending: str, error: str
) -> None:
    status, stderr, first = _run_ending(tmp_path, capfd, ending)
    assert status == 1
    (line,) = _robot_lines(stderr)
    said = str(first["controller_error"])
    if "PID" in error:
        error = error.replace("PID", said.split("(pid ")[1].split(")")[0])
    assert line == f"mazesim: robot 'first': {error}"
    assert first["exit_status"] == 1
    assert said == error
    assert stderr.count("mazesim: ") == 2, stderr  # the import's line and the robot's


def test_a_controller_leaving_a_thread_running_does_not_keep_the_command_alive(
    tmp_path: Path,
) -> None:
    """A controller run in mazesim's own process that starts a thread (not a daemon) and
    returns: the run's outputs were written, then Python waited for the thread at exit for
    ever. The command ends with the run, saying so, as Webots ends a controller's process."""
    controller = tmp_path / "spinner.py"
    controller.write_text(
        "import threading, time\nfrom controller import Robot\nr = Robot()\n"
        "threading.Thread(target=lambda: time.sleep(10**6), name='server').start()\n"
        "r.step(32)\n"
    )
    out = tmp_path / "run"
    result = subprocess.run(
        [sys.executable, "-m", "mazesim", "webots", "run", str(controller), "--seconds", "0.5"]
        + ["--out", str(out), "--no-progress"],
        capture_output=True,
        text=True,
        timeout=300,  # a ceiling: it waited for ever
        check=False,
    )
    assert result.returncode == 0, result.stderr
    assert "left 1 thread(s) running ('server')" in result.stderr
    assert json.loads((out / "summary.json").read_text())["steps"] >= 1


def test_a_pipe_the_controller_closed_is_collected_without_a_second_report() -> None:
    # The controller closed the pipe's descriptor; its object, collected at the process's end,
    # closes it again and fails: Python printed that as an ignored exception (a traceback
    # after the one-line report above), by the order of the collection, now and then.
    code = textwrap.dedent(
        """
        import errno, gc, os
        from multiprocessing.connection import Connection
        from mazesim.webots import controller_process

        reading, writing = os.pipe()
        pipe = Connection(reading)
        os.close(reading)
        controller_process._lost(OSError(errno.EBADF, "Bad file descriptor"))
        del pipe
        gc.collect()

        class Failing:
            def __del__(self):
                raise ValueError("another failure")

        Failing()  # any other failure is still printed
        """
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert "Bad file descriptor" not in done.stderr, done.stderr
    assert "another failure" in done.stderr
