"""Controllers in the styles real e-puck users write, each run to its end through
``mazesim webots run`` in a subprocess (from a copy in its own folder, as its files land there).
"""

from __future__ import annotations

import csv
import json
import math
import re
import shutil
import subprocess
from pathlib import Path
from typing import Any

import numpy as np

from mazesim_process import mazesim_command

CONTROLLERS = Path(__file__).resolve().parents[1] / "data" / "controllers"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def run_copy(
    controller: str, folder: Path, *args: str, seconds: float = 5.0
) -> tuple[subprocess.CompletedProcess[str], dict[str, Any]]:
    """Copies the controller into ``folder``, runs it there with ``--seconds``, and gives the
    process and the run's summary; the run must end with exit status 0."""
    shutil.copy(CONTROLLERS / controller, folder / controller)
    result = mazesim_command(
        "webots", "run", controller, "--out", "out", "--seconds", str(seconds), *args, cwd=folder
    )
    assert result.returncode == 0, result.stderr
    summary = json.loads((folder / "out" / "summary.json").read_text())
    assert summary["controller_error"] is None
    return result, summary


def test_state_machine_left_wall_follower_turns_on_datasheet_encoders(tmp_path: Path) -> None:
    result, summary = run_copy(
        "left_wall_state_machine.py", tmp_path, "--world", "seed-maze", seconds=40.0
    )
    turns = int(result.stdout.split("turns ")[1].split()[0])
    assert turns >= 3 and "TURN_RIGHT" in result.stdout
    assert summary["reached_end"] and summary["collisions"] == 0
    assert summary["distance_m"] > 1.5


def test_robot_subclass_with_run_steps_until_the_end(tmp_path: Path) -> None:
    result, summary = run_copy("my_robot_class.py", tmp_path, "--world", "arena")
    assert f"MyRobot stepped {summary['steps']} times" in result.stdout
    assert summary["distance_m"] > 0.1 and summary["collisions"] == 0


def test_supervisor_resets_its_robot_every_fifty_steps(tmp_path: Path) -> None:
    world = CONTROLLERS / "worlds" / "supervised_arena.wbt"
    result, summary = run_copy("supervisor_reset.py", tmp_path, "--world", str(world), seconds=10)
    assert "last child E-puck EPUCK" in result.stdout
    resets = int(result.stdout.split("resets ")[1].split()[0])
    worst = float(result.stdout.split("worst ")[1].split()[0])
    assert resets >= summary["steps"] // 60
    # One step after the reset at 5 rad/s: 5 * 0.02 m * 0.032 s from the start at most.
    assert worst < 0.004
    start_x, start_y = -0.2, -0.1
    assert math.hypot(summary["final_pose"][0] - start_x, summary["final_pose"][1] - start_y) < 0.4


def test_numpy_and_matplotlib_controller_saves_its_plot(tmp_path: Path) -> None:
    result, summary = run_copy("numpy_plot.py", tmp_path, "--world", "arena")
    assert (tmp_path / "proximity.png").read_bytes()[:8] == PNG_MAGIC
    data = np.load(tmp_path / "proximity.npy")
    assert data.shape == (summary["steps"], 8)
    assert not np.isnan(data[1:]).any()
    assert f"saved {summary['steps']} rows" in result.stdout


def test_missing_devices_are_none(tmp_path: Path) -> None:
    result, summary = run_copy("missing_devices.py", tmp_path, "--world", "arena")
    for name in ("gps", "lidar", "ds_left", "display", "inertial unit"):
        assert f"no {name}\n" in result.stdout
        assert f'"{name}" was not found' in result.stderr
    assert "found ['camera', 'ps0']" in result.stdout
    assert summary["reached_end"] and summary["distance_m"] > 0.1


def test_reading_before_the_first_step_gives_nan(tmp_path: Path) -> None:
    result, summary = run_copy("nan_before_step.py", tmp_path, "--world", "arena")
    assert "before the first step: nan" in result.stdout
    assert "steps that read NaN: 0" in result.stdout
    assert summary["reached_end"]


def test_wall_clock_paced_controller_runs_to_the_time_limit(tmp_path: Path) -> None:
    result, summary = run_copy("wall_clock_pacing.py", tmp_path, "--world", "arena", seconds=1.5)
    assert f"paced {summary['steps']} steps" in result.stdout
    # A status line after half a second of wall-clock time; the simulated time it shows is
    # where a loaded machine let the run get by then (behind the wall clock when it lags).
    status = re.findall(r"^t=(\d+\.\d\d) s wall=(\d+\.\d\d) s$", result.stdout, re.MULTILINE)
    assert status and float(status[0][1]) >= 0.5 and 0.0 < float(status[0][0]) <= 1.5, status
    assert summary["reached_end"] and summary["simulated_seconds"] >= 1.5


def test_csv_logger_writes_into_its_own_folder(tmp_path: Path) -> None:
    result, summary = run_copy("csv_logger.py", tmp_path, "--world", "arena")
    with open(tmp_path / "robot_log.csv", newline="") as handle:
        rows = list(csv.reader(handle))
    assert rows[0][:3] == ["time", "left_encoder", "right_encoder"] and len(rows[0]) == 11
    assert len(rows) - 1 == summary["steps"]
    last = [float(v) for v in rows[-1]]
    assert (
        last[0] == summary["simulated_seconds"]
        or abs(last[0] - summary["simulated_seconds"]) < 1e-6
    )
    # Left wheel at 2 rad/s, right at 3 rad/s: the encoders read the turned angles.
    assert 0 < last[1] < last[2]
    assert "log written to robot_log.csv" in result.stdout
