"""Webots-style controllers of every kind through ``mazesim webots run``: the test controllers
in ``tests/data/controllers/`` (encoders, camera line following, keyboard, GPS + compass,
supervisor, multi-step ``step()``, a Robot subclass, controllers that fail) each run in a
subprocess with a time limit, and what they do is checked against the robot profile's numbers.
"""

from __future__ import annotations

import csv
import json
import math
import subprocess
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import mazesim
from mazesim.webots import import_wbt, run_controller
from mazesim.webots.keyboard import KeyScript
from mazesim_process import mazesim_command

ROOT = Path(__file__).resolve().parents[2]
CONTROLLERS = ROOT / "tests" / "data" / "controllers"
GPS_WORLD = CONTROLLERS / "worlds" / "gps_compass_arena.wbt"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
PROFILE = mazesim.RobotProfile.builtin("e-puck")


def webots_run(controller: str | Path, *args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    """``mazesim webots run CONTROLLER --out out ARGS`` in a subprocess, with a time limit."""
    path = controller if isinstance(controller, Path) else CONTROLLERS / controller
    return mazesim_command("webots", "run", str(path), "--out", "out", *args, cwd=cwd)


def outputs(cwd: Path) -> tuple[dict[str, Any], np.ndarray]:
    """The summary and the trajectory (rows of time, x, y) a run wrote; the picture exists."""
    assert (cwd / "out" / "trajectory.png").read_bytes()[:8] == PNG_MAGIC
    summary = json.loads((cwd / "out" / "summary.json").read_text())
    with open(cwd / "out" / "trajectory.csv", newline="") as handle:
        rows = list(csv.reader(handle))
    assert rows[0] == ["time_s", "x_m", "y_m"]
    return summary, np.array([[float(v) for v in row] for row in rows[1:]])


def test_position_control_with_encoders_travels_turn_times_wheel_radius(tmp_path: Path) -> None:
    result = webots_run("encoder_position_control.py", "--world", "arena", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    turned = [float(line.split()[2]) for line in result.stdout.splitlines() if " turned " in line]
    assert turned == [pytest.approx(12.0, abs=0.01)] * 2
    summary, trajectory = outputs(tmp_path)
    assert summary["reached_end"] is False, "the controller ends once the wheels have settled"
    assert summary["distance_m"] == pytest.approx(12.0 * PROFILE.wheel_radius, rel=0.01)
    start, end = trajectory[0, 1:], trajectory[-1, 1:]
    assert np.hypot(*(end - start)) == pytest.approx(12.0 * PROFILE.wheel_radius, rel=0.01)


def _distance_to_line(world: mazesim.World, x: float, y: float) -> float:
    best = math.inf
    for region in world.paint_regions():
        if region["shape"] != "capsule":
            continue
        (ax, ay), (bx, by) = region["a"], region["b"]  # type: ignore[misc]
        abx, aby = bx - ax, by - ay
        t = min(1.0, max(0.0, ((x - ax) * abx + (y - ay) * aby) / (abx * abx + aby * aby)))
        best = min(best, math.hypot(x - ax - t * abx, y - ay - t * aby))
    return best


def test_camera_line_follower_goes_round_the_line_follow_loop(tmp_path: Path) -> None:
    result = webots_run(
        "camera_line_follower.py", "--world", "line-follow", "--seconds", "45", cwd=tmp_path
    )
    assert result.returncode == 0, result.stderr
    summary, trajectory = outputs(tmp_path)
    assert summary["collisions"] == 0
    world = mazesim.load_world("line-follow")
    offsets = [_distance_to_line(world, x, y) for _, x, y in trajectory[::10]]
    # The camera's nearest floor is 0.13 m ahead of the wheels, so the robot cuts the
    # corners (of radius 0.16 m) by a few centimetres and the short straights barely straighten it.
    assert max(offsets) < 0.08, f"left the line by {max(offsets):.3f} m"
    assert np.median(offsets) < 0.04
    # One whole lap round the loop's centre (0.6, 0.5), counter-clockwise.
    angles = np.unwrap(np.arctan2(trajectory[:, 2] - 0.5, trajectory[:, 1] - 0.6))
    assert angles[-1] - angles[0] > 2 * math.pi


def test_ground_sensor_line_follower_stays_on_the_line(tmp_path: Path) -> None:
    result = webots_run("ground_line_follower.py", "--world", "line-follow", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    summary, trajectory = outputs(tmp_path)
    assert summary["collisions"] == 0 and summary["reached_end"] is True
    world = mazesim.load_world("line-follow")
    offsets = [_distance_to_line(world, x, y) for _, x, y in trajectory[::10]]
    # The ground sensors are 0.03 m ahead of the wheels, 0.01 m apart.
    assert max(offsets) < 0.03, f"left the line by {max(offsets):.3f} m"
    angles = np.unwrap(np.arctan2(trajectory[:, 2] - 0.5, trajectory[:, 1] - 0.6))
    assert angles[-1] - angles[0] > 2 * math.pi


def test_student_maze_solver_reaches_the_seed_maze_goal(tmp_path: Path) -> None:
    result = webots_run("maze_wall_follower.py", "--world", "seed-maze", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert int(result.stdout.split("turns")[1].split()[0]) > 0
    summary, trajectory = outputs(tmp_path)
    goal = mazesim.load_world("seed-maze").goal
    assert goal is not None
    gx, gy, radius = goal
    closest = np.min(np.hypot(trajectory[:, 1] - gx, trajectory[:, 2] - gy))
    assert closest < radius, f"came no nearer the goal than {closest:.3f} m"


def test_keyboard_script_drives_the_teleop_controller(tmp_path: Path) -> None:
    keys = tmp_path / "keys.txt"
    keys.write_text("# time_s key [duration_s]\n0.5 UP\n2.5 -\n3.0 LEFT 0.5\n4.0 SHIFT+q\n")
    result = webots_run("keyboard_teleop.py", "--world", "arena", "--keys", str(keys), cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "quit key" in result.stdout
    summary, trajectory = outputs(tmp_path)
    assert summary["simulated_seconds"] == pytest.approx(4.0, abs=0.05)
    # UP held 2 s at 4 rad/s: straight along the start heading (+x in the arena).
    forward = 2.0 * 4.0 * PROFILE.wheel_radius
    assert trajectory[-1, 1] == pytest.approx(forward, rel=0.03)
    assert abs(trajectory[-1, 2]) < 0.002
    # LEFT for 0.5 s spins in place: yaw 0.5 * 2 * r * 2 / axle.
    assert summary["final_pose"][2] == pytest.approx(
        0.5 * 2.0 * PROFILE.wheel_radius * 2.0 / PROFILE.axle_length, rel=0.05
    )


def test_without_a_key_script_get_key_returns_minus_one(tmp_path: Path) -> None:
    result = webots_run("keyboard_teleop.py", "--world", "arena", "--seconds", "1", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "keys seen: []" in result.stdout
    summary, _ = outputs(tmp_path)
    assert summary["distance_m"] == 0.0


def test_bad_key_scripts_are_mazesim_errors(tmp_path: Path) -> None:
    keys = tmp_path / "keys.txt"
    keys.write_text("0.5 UP\n1.0 WARP\n")
    result = webots_run("keyboard_teleop.py", "--keys", str(keys), cwd=tmp_path)
    assert result.returncode == 2
    assert result.stderr.startswith("mazesim: error: ") and "keys.txt:2" in result.stderr
    assert "WARP" in result.stderr


GPS_AND_COMPASS = [
    {"type": "GPS", "name": "gps", "slot": "turretSlot", "translation": [0.0, 0.0, 0.05]},
    {"type": "Compass", "name": "compass", "slot": "turretSlot", "translation": [0.0, 0.0, 0.05]},
]


def test_gps_compass_controller_reaches_its_goal() -> None:
    world, imported = import_wbt(GPS_WORLD)
    report = {**imported, "extension_devices": GPS_AND_COMPASS}
    run = run_controller(
        CONTROLLERS / "gps_compass_goal.py", world, seconds=30.0, report=report, seed=4
    )
    assert run.exit_status == 0, run.error
    assert not run.reached_end, "the controller stops at the goal"
    x, y, _ = run.final_pose
    assert math.hypot(x - 0.3, y - 0.25) < 0.025


def test_gps_compass_controller_through_the_command(tmp_path: Path) -> None:
    if "extension_devices" not in import_wbt(GPS_WORLD)[1]:
        pytest.skip("this build's importer does not list turretSlot devices yet")
    result = webots_run("gps_compass_goal.py", "--world", str(GPS_WORLD), cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "reached the goal" in result.stdout
    summary, _ = outputs(tmp_path)
    x, y, _ = summary["final_pose"]
    assert math.hypot(x - 0.3, y - 0.25) < 0.025


def test_supervisor_moves_its_robot_and_quits_with_a_status(tmp_path: Path) -> None:
    result = webots_run("supervisor_teleport.py", "--world", str(GPS_WORLD), cwd=tmp_path)
    assert result.returncode == 3, result.stderr
    assert "start [-0.2" in result.stdout and "moved [0.2, -0.1, 0.0]" in result.stdout
    summary, trajectory = outputs(tmp_path)
    assert summary["quit_requested"] is True and summary["exit_status"] == 3
    x, y, yaw = summary["final_pose"]
    # Facing +y after setSFRotation, it drove about 1 s at 3 rad/s.
    assert x == pytest.approx(0.2, abs=1e-3) and yaw == pytest.approx(1.5708, abs=1e-3)
    travelled = y + 0.1
    expected = summary["simulated_seconds"] * 3 * PROFILE.wheel_radius
    assert travelled == pytest.approx(expected, rel=0.1)
    assert trajectory[0, 1] == pytest.approx(0.2), "the move replaces the start of the trail"


def test_step_of_four_basic_steps(tmp_path: Path) -> None:
    result = webots_run("multi_step_counter.py", "--world", "arena", "--seconds", "4", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    steps = math.ceil(4000 / 32)
    assert f"control steps {steps // 4}" in result.stdout
    assert "gaps ms [128]" in result.stdout
    summary, _ = outputs(tmp_path)
    assert summary["steps"] == steps and summary["reached_end"] is True


def test_robot_subclass_follows_walls(tmp_path: Path) -> None:
    result = webots_run(
        "subclassed_wall_follower.py", "--world", "arena", "--seconds", "30", cwd=tmp_path
    )
    assert result.returncode == 0, result.stderr
    summary, trajectory = outputs(tmp_path)
    assert summary["reached_end"] is True
    assert summary["distance_m"] > 1.0
    assert summary["longest_stop_s"] < 2.0
    assert np.all(np.abs(trajectory[:, 1:]) < 0.5), "it stays inside the arena"


def test_a_controller_raising_after_its_loop_keeps_its_run(tmp_path: Path) -> None:
    result = webots_run("raises_after_loop.py", "--world", "arena", "--seconds", "3", cwd=tmp_path)
    assert result.returncode == 1
    controller = CONTROLLERS / "raises_after_loop.py"
    assert f'File "{controller}", line 19, in <module>' in result.stderr
    assert result.stderr.rstrip().endswith("ZeroDivisionError: division by zero")
    assert "mazesim: error" not in result.stderr
    summary, trajectory = outputs(tmp_path)
    assert summary["reached_end"] is True and summary["exit_status"] == 1
    assert summary["controller_error"] == "ZeroDivisionError: division by zero"
    assert summary["distance_m"] == pytest.approx(3.0 * 2.0 * PROFILE.wheel_radius, rel=0.02)
    assert len(trajectory) == summary["steps"] + 1


def test_a_controllers_own_oserror_is_its_traceback(tmp_path: Path) -> None:
    result = webots_run("own_oserror.py", "--world", "arena", cwd=tmp_path)
    assert result.returncode == 1
    controller = CONTROLLERS / "own_oserror.py"
    assert f'File "{controller}", line 12, in <module>' in result.stderr
    assert "FileNotFoundError" in result.stderr and "mazesim: error" not in result.stderr
    summary, _ = outputs(tmp_path)
    assert summary["steps"] == 10


@pytest.mark.parametrize(
    ("ending", "status"),
    [
        ("import sys\nsys.exit(4)\n", 4),
        ("import sys\nsys.exit('giving up')\n", 1),
        ("raise KeyboardInterrupt\n", 130),
        ("import sys\nsys.exit()\n", 0),
        # Python ends with status 1: a number in the summary, not JSON's true.
        ("import sys\nsys.exit(True)\n", 1),
        # os._exit ends the controller alone, as its process in Webots: the run keeps its files.
        ("import os\nos._exit(7)\n", 7),
        ("while True\n    pass\n", 1),
        # Deeper than Python's parser goes: the controller fails to compile, as under Webots;
        # the import scan before the run once let the RecursionError out as an internal error.
        ("x = " + "+".join(["1"] * 100_000) + "\n", 1),
    ],
)
def test_exit_statuses_and_files_whatever_the_ending(
    tmp_path: Path, ending: str, status: int
) -> None:
    script = tmp_path / "ending.py"
    script.write_text(
        "from controller import Robot\nrobot = Robot()\nfor _ in range(5):\n"
        "    robot.step(32)\n" + ending
    )
    result = webots_run(script, "--world", "arena", cwd=tmp_path)
    assert result.returncode == status, result.stderr
    summary, _ = outputs(tmp_path)
    assert summary["exit_status"] == status and type(summary["exit_status"]) is int
    if "while True" in ending:
        assert summary["steps"] == 0, "a controller that does not compile does not run"
        assert f'File "{script}", line 5' in result.stderr and "SyntaxError" in result.stderr
        assert "Traceback" not in result.stderr
    elif "+1+1" in ending:
        assert summary["steps"] == 0, "a controller that does not compile does not run"
        assert "RecursionError" in result.stderr and "internal error" not in result.stderr
    else:
        assert summary["steps"] == 5
    if "giving up" in ending:
        assert "giving up" in result.stderr


def test_every_e_puck_device_answers(tmp_path: Path) -> None:
    result = webots_run("every_device.py", "--world", "arena", "--no-noise", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    lines = dict(line.split(" ", 1) for line in result.stdout.splitlines() if " " in line)
    assert float(lines["ls0"]) == pytest.approx(2047.5, abs=1.0)
    assert float(lines["gs1"]) == pytest.approx(PROFILE.ground_reading(1, 1.0), rel=0.01)
    assert float(lines["accelerometer"].split()[-1]) == pytest.approx(9.81, abs=0.01)
    spin = 2.0 * PROFILE.wheel_radius * 2.0 / PROFILE.axle_length
    # The E-puck PROTO's gyro table maps +-13.315805 rad/s to +-100000.
    assert float(lines["gyro"].split()[-1]) == pytest.approx(spin * 100000 / 13.315805, rel=0.02)
    assert lines["camera"] == "52 39 8112"
    assert lines["receiver"] == "queue 0"
    assert lines["led1"] == "1"
    assert lines["model"] == "GCtronic e-puck"  # the E-puck PROTO's model field
    assert lines["missing"] == "None"
    assert 'Device "lidar" was not found on robot "e-puck"' in result.stderr


WARNED_WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 1 1 }
SomeUnknownProto { translation 0.2 0.2 0 }
E-puck { translation 0 0 0 }
"""


def test_import_warnings_are_printed_and_strict_refuses_them(tmp_path: Path) -> None:
    world = tmp_path / "warned.wbt"
    world.write_text(WARNED_WORLD)
    warnings = import_wbt(world)[1]["warnings"]
    assert warnings, "the unknown PROTO is reported"
    result = webots_run(
        "multi_step_counter.py", "--world", str(world), "--seconds", "1", cwd=tmp_path
    )
    assert result.returncode == 0, result.stderr
    printed = [line for line in result.stderr.splitlines() if line.startswith("mazesim: warning: ")]
    assert printed == [f"mazesim: warning: {warning}" for warning in warnings]
    # One summary comes first: the robot recognised and how many things were not imported.
    first = next(line for line in result.stderr.splitlines() if line.startswith("mazesim: "))
    assert first == (
        "mazesim: warned.wbt: robot: E-puck, simulated as the e-puck; "
        f"{len(warnings)} thing(s) not imported as in Webots, listed below"
    )
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["import"]["not_imported"] == warnings
    assert summary["import"]["robot_model"] == "E-puck"
    strict = webots_run(
        "multi_step_counter.py", "--world", str(world), "--strict", "--out", "strict", cwd=tmp_path
    )
    assert strict.returncode == 2
    assert "--strict" in strict.stderr and "mazesim: error: " in strict.stderr
    assert not (tmp_path / "strict").exists(), "nothing runs under --strict"


def test_a_stand_in_is_named_in_the_summary_and_strict_refuses_it(tmp_path: Path) -> None:
    world = tmp_path / "circle.wbt"
    world.write_text(
        "#VRML_SIM R2023b utf8\n"
        'EXTERNPROTO "webots://projects/objects/floors/protos/CircleArena.proto"\n'
        "CircleArena { radius 0.4 }\nE-puck { }\n"
    )
    result = webots_run(
        "multi_step_counter.py", "--world", str(world), "--seconds", "1", cwd=tmp_path
    )
    assert result.returncode == 0, result.stderr
    assert "stood in for by mazesim's stand-ins: CircleArena" in result.stderr.splitlines()[0]
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert list(summary["import"]["stand_ins"]) == ["CircleArena"]
    strict = webots_run(
        "multi_step_counter.py", "--world", str(world), "--strict", "--out", "strict", cwd=tmp_path
    )
    assert strict.returncode == 2 and "stand-in" in strict.stderr


def test_help_documents_the_exit_codes(tmp_path: Path) -> None:
    result = mazesim_command("webots", "run", "--help", cwd=tmp_path)
    assert result.returncode == 0
    text = " ".join(result.stdout.split())
    phrases = ("exit status", "1 the controller raised", "2 a mazesim error", "--keys", "--strict")
    for phrase in phrases:
        assert phrase in text


def test_key_script_holds_each_key_until_the_next_line() -> None:
    script = KeyScript.parse("1 a\n2 UP 0.5\n3 CONTROL+RIGHT\n4 -\n")
    assert script.key_at(0.5) is None
    assert script.key_at(1.0) == ord("A") and script.key_at(1.99) == ord("A")
    assert script.key_at(2.2) == 315 and script.key_at(2.6) is None
    assert script.key_at(3.5) == 0x20000 + 316
    assert script.key_at(10.0) is None


OLD_STYLE = """
import os
import sys

sys.path.append(os.path.join(os.environ["WEBOTS_HOME"], "lib", "controller", "python"))
from controller import Robot  # noqa: E402

robot = Robot()
robot.keyboardEnable(32)
while robot.step(32) != -1:
    key = robot.keyboardGetKey()
    if key == ord("Q"):
        print("quit at", round(robot.getTime(), 2))
        break
"""


def test_an_old_style_controller_that_looks_for_webots_home(tmp_path: Path) -> None:
    script = tmp_path / "old_style.py"
    script.write_text(OLD_STYLE)
    keys = tmp_path / "keys.txt"
    keys.write_text("0.96 q\n")
    result = webots_run(script, "--world", "arena", "--keys", str(keys), cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "quit at 0.96" in result.stdout


PIONEER_WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 1 1 }
Pioneer3dx { translation 0.1 0 0 }
"""


def test_a_world_whose_robot_is_not_an_e_puck_is_warned_about(tmp_path: Path) -> None:
    world = tmp_path / "pioneer.wbt"
    world.write_text(PIONEER_WORLD)
    result = webots_run(
        "multi_step_counter.py", "--world", str(world), "--seconds", "1", cwd=tmp_path
    )
    assert result.returncode == 0, result.stderr
    warnings = [line for line in result.stderr.splitlines() if "mazesim: warning: " in line]
    assert any("Pioneer3dx" in line for line in warnings), result.stderr
    strict = webots_run("multi_step_counter.py", "--world", str(world), "--strict", cwd=tmp_path)
    assert strict.returncode == 2 and "Pioneer3dx" in strict.stderr


def test_the_worlds_controller_args_are_the_controllers_argv(tmp_path: Path) -> None:
    world = tmp_path / "args.wbt"
    robot = 'E-puck {\n  controllerArgs [ "--speed" "3" ]\n}\n'
    world.write_text("#VRML_SIM R2023b utf8\nRectangleArena { }\n" + robot)
    script = tmp_path / "argv.py"
    script.write_text("import sys\nfrom controller import Robot\nRobot()\nprint(sys.argv[1:])\n")
    result = webots_run(script, "--world", str(world), cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "['--speed', '3']" in result.stdout
