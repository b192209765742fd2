"""Webots-style controllers on mazesim: the controller module's semantics, the runner, and the
example controller through ``mazesim webots run``."""

from __future__ import annotations

import json
import math
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

import mazesim
from mazesim.errors import InvalidArgumentError, MazesimIOError
from mazesim.webots import prepare, run_controller
from mazesim.webots import simulation as simulations
from mazesim.webots.controller import ControllerStopped, Robot
from mazesim.webots.devices import LED, DistanceSensor, Motor, PositionSensor
from mazesim.webots.termination import GRACE_SECONDS
from mazesim_process import mazesim_command

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "webots" / "avoid_collision.py"
CORPUS = ROOT / "tests" / "data" / "webots-worlds"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


@pytest.fixture
def robot() -> Iterator[Robot]:
    """A Robot in the arena with noise-free sensors and a 2 s run."""
    prepare(mazesim.load_world("arena"), seconds=2.0, noise=False)
    Robot.created = None
    yield Robot()
    Robot.created = None
    simulations.release()


def motor(robot: Robot, name: str) -> Motor:
    device = robot.getDevice(name)
    assert isinstance(device, Motor)
    return device


def sensor(robot: Robot, name: str) -> DistanceSensor:
    device = robot.getDevice(name)
    assert isinstance(device, DistanceSensor)
    return device


def test_robot_needs_a_prepared_simulation() -> None:
    simulations.release()
    with pytest.raises(InvalidArgumentError, match="mazesim webots run"):
        Robot()


def test_time_step_name_and_devices(robot: Robot, capsys: pytest.CaptureFixture[str]) -> None:
    assert robot.getBasicTimeStep() == 32.0
    assert robot.getName() == "e-puck"
    assert robot.getTime() == 0.0
    names = {robot.getDeviceByIndex(i).getName() for i in range(robot.getNumberOfDevices())}
    expected = {f"ps{i}" for i in range(8)} | {"gs0", "gs1", "gs2"} | {f"led{i}" for i in range(10)}
    expected |= {"left wheel motor", "right wheel motor", "left wheel sensor", "right wheel sensor"}
    expected |= {f"ls{i}" for i in range(8)}
    expected |= {"camera", "accelerometer", "gyro", "emitter", "receiver", "speaker"}
    assert names == expected
    assert robot.getDevice("lidar") is None
    assert 'Device "lidar" was not found on robot "e-puck"' in capsys.readouterr().err


def test_a_device_name_of_a_million_characters_is_quoted_shortened(
    robot: Robot, capsys: pytest.CaptureFixture[str]
) -> None:
    """Webots' "not found" line, and the closing line that lists the names asked for, quote a
    name by its start and end (mazesim.errors.MOST_QUOTED characters), not whole."""
    assert robot.getDevice("ps" + "0" * 10**6) is None
    err = capsys.readouterr().err
    assert err.startswith('Device "ps000') and "characters ...]" in err and len(err) < 1000
    line = robot._missing_devices_line()
    assert "characters ...]" in line and len(line) < 2000


def test_sensors_read_only_after_enable_and_one_period(
    robot: Robot, capsys: pytest.CaptureFixture[str]
) -> None:
    ps0 = sensor(robot, "ps0")
    assert math.isnan(ps0.getValue())
    assert "wb_distance_sensor_get_value() called for a disabled device" in capsys.readouterr().err
    ps0.enable(64)
    assert ps0.getSamplingPeriod() == 64
    robot.step(32)
    assert math.isnan(ps0.getValue()), "one basic step is not yet a sampling period"
    robot.step(32)
    first = ps0.getValue()
    assert 60.0 < first < 100.0, "nothing within 7 cm: about the table's last value"
    assert ps0.getLookupTable()[:3] == [0.0, 4095.0, 0.002]
    assert ps0.getMaxValue() == 4095.0
    ground = sensor(robot, "gs1")
    ground.enable(32)
    robot.step()
    assert 800.0 < ground.getValue() < 900.0, "white floor"
    assert robot.getTime() == pytest.approx(0.096)


def test_step_returns_minus_one_at_the_end_then_stops_the_controller(robot: Robot) -> None:
    steps = 0
    while robot.step(32) != -1:
        steps += 1
    assert steps == math.ceil(2000 / 32)
    assert robot.getTime() == pytest.approx(steps * 0.032)
    with pytest.raises(ControllerStopped):
        robot.step(32)


def test_motors_position_and_velocity_control(
    robot: Robot, capsys: pytest.CaptureFixture[str]
) -> None:
    left, right = motor(robot, "left wheel motor"), motor(robot, "right wheel motor")
    encoder = robot.getDevice("left wheel sensor")
    assert isinstance(encoder, PositionSensor) and left.getPositionSensor() is encoder
    encoder.enable(32)
    robot.step(320)
    assert encoder.getValue() == pytest.approx(0.0, abs=1e-9), "position control holds 0"
    left.setPosition(2.0)
    robot.step(640)
    assert encoder.getValue() == pytest.approx(2.0, abs=0.01)
    left.setPosition(float("inf"))
    right.setPosition(float("inf"))
    left.setVelocity(10.0)
    right.setVelocity(-10.0)
    err = capsys.readouterr().err
    assert "The requested velocity 10 exceeds 'maxVelocity' = 6.28." in err
    robot.step(32)
    simulation = simulations.current()
    assert simulation.simulator.wheel_speeds == pytest.approx((6.28, -6.28))
    assert left.getMaxVelocity() == 6.28 and left.getVelocity() == 10.0
    left.setPosition(1.0)
    left.setVelocity(-1.0)
    assert "negative 'velocity' argument in position control mode" in capsys.readouterr().err


def test_torque_feedback_keeps_its_period_and_reads_nan_while_disabled(robot: Robot) -> None:
    # Webots' motor.c keeps the period given and starts the feedback at NaN; no torque is
    # simulated, so an enabled feedback reads 0.
    motor = robot.getDevice("left wheel motor")
    assert motor.getTorqueFeedbackSamplingPeriod() == 0
    assert math.isnan(motor.getTorqueFeedback())
    motor.enableTorqueFeedback(16)
    assert motor.getTorqueFeedbackSamplingPeriod() == 16
    assert motor.getForceFeedbackSamplingPeriod() == 16 and motor.getTorqueFeedback() == 0.0
    motor.disableTorqueFeedback()
    assert motor.getTorqueFeedbackSamplingPeriod() == 0


def test_leds_keep_their_value(robot: Robot) -> None:
    led = robot.getDevice("led8")
    assert isinstance(led, LED) and led.get() == 0
    led.set(1)
    assert led.get() == 1
    # Webots' LED.set takes a bool too (Union[bool, int]): the usual led.set(ps > 80).
    led.set(False)
    assert led.get() == 0
    led.value = True
    assert led.get() == 1


def test_deprecated_getters_warn_like_webots(robot: Robot) -> None:
    with pytest.warns(DeprecationWarning, match=r"DEPRECATION: Robot.getMotor is deprecated"):
        assert isinstance(robot.getMotor("left wheel motor"), Motor)
    with pytest.warns(DeprecationWarning, match=r"Robot.getDistanceSensor is deprecated"):
        assert isinstance(robot.getDistanceSensor("gs0"), DistanceSensor)
    with pytest.warns(DeprecationWarning, match=r"Robot.getPositionSensor is deprecated"):
        assert isinstance(robot.getPositionSensor("right wheel sensor"), PositionSensor)
    with pytest.warns(DeprecationWarning, match=r"Robot.getLed is deprecated"):
        assert robot.getLED("led0") is not None


LISTING_3_1 = """
from controller import Robot

robot = Robot()
timeStep = int(robot.getBasicTimeStep())
left = robot.getMotor('left wheel motor')
right = robot.getMotor('right wheel motor')
ps = []
psNames = ['ps0', 'ps1', 'ps2', 'ps3', 'ps4', 'ps5', 'ps6', 'ps7', 'gs0', 'gs1', 'gs2']
for i in range(11):
    ps.append(robot.getDistanceSensor(psNames[i]))
    ps[i].enable(timeStep)
left.setPosition(float('inf'))
right.setPosition(float('inf'))
left.setVelocity(2.0)
right.setVelocity(2.0)
readings = []
while robot.step(timeStep) != -1:
    readings.append([ps[i].getValue() for i in range(11)])
assert len(readings) > 10 and all(v == v for v in readings[-1])
"""


def test_a_report_style_controller_runs_unmodified(tmp_path: Path) -> None:
    script = tmp_path / "e_puck_maze.py"
    script.write_text(LISTING_3_1)
    before = sys.modules.get("controller")
    with pytest.warns(DeprecationWarning):
        run = run_controller(script, mazesim.load_world("seed-maze"), seconds=2.0)
    assert run.reached_end and run.steps == math.ceil(2000 / 32)
    assert run.distance_m > 0.05
    assert sys.modules.get("controller") is before


def test_controller_errors_are_reported_and_state_is_restored(tmp_path: Path) -> None:
    script = tmp_path / "broken.py"
    script.write_text("from controller import Robot\nrobot = Robot()\nraise ValueError('mine')\n")
    path_before = list(sys.path)
    run = run_controller(script, mazesim.load_world("arena"), seconds=1.0)
    assert run.exit_status == 1
    assert f'File "{script}", line 3, in <module>' in run.error
    assert run.error.rstrip().endswith("ValueError: mine")
    assert "runner.py" not in run.error, "the traceback starts in the controller's file"
    assert sys.path == path_before and "controller" not in sys.modules
    with pytest.raises(MazesimIOError):
        run_controller(tmp_path / "missing.py", mazesim.load_world("arena"))


def test_a_controller_ignoring_minus_one_is_stopped(tmp_path: Path) -> None:
    script = tmp_path / "forever.py"
    script.write_text(
        "from controller import Robot\nrobot = Robot()\n"
        "while True:\n    try:\n        robot.step(32)\n    except Exception:\n        pass\n"
    )
    run = run_controller(script, mazesim.load_world("arena"), seconds=1.0)
    assert run.reached_end and run.simulated_seconds == pytest.approx(1.024)


@pytest.mark.parametrize(
    "body",
    [
        # Catches everything, ControllerStopped too, and goes on stepping.
        "while True:\n    try:\n        robot.step(32)\n    except:\n        pass\n",
        # The same, one function call deeper, its loop inside another bare except.
        "def spin():\n    while True:\n        try:\n            robot.step(32)\n"
        "        except BaseException:\n            continue\n"
        "while True:\n    try:\n        spin()\n    except:\n        pass\n",
    ],
    ids=["bare-except", "nested"],
)
def test_a_runaway_controller_is_stopped_after_the_grace_as_webots_does(
    tmp_path: Path, body: str
) -> None:
    script = tmp_path / "runaway.py"
    script.write_text(f"from controller import Robot\nrobot = Robot()\n{body}")
    tracing = sys.gettrace()
    started = time.monotonic()
    run = run_controller(script, mazesim.load_world("arena"), seconds=0.5)
    took = time.monotonic() - started
    assert run.reached_end and run.stopped
    assert GRACE_SECONDS <= took < GRACE_SECONDS + CEILING_S  # stopped: not left running
    assert run.exit_status == 0 and sys.gettrace() is tracing
    # The process goes on normally: code run afterwards is not unwound.
    assert [n * 2 for n in range(3)] == [0, 2, 4]


#: What a watchdog's stop may take at most on a loaded machine: a ceiling that tells "stopped"
#: from "left running", never a pace.
CEILING_S = 120.0

#: Runs a controller file (its first argument) in a child process under a time limit, with the
#: stall watchdog its second argument says, and prints its run's outcome, so that a controller
#: the watchdog fails to end fails the test instead of hanging it.
RUN_IN_CHILD = """
import json, sys, time
import mazesim
from mazesim.webots import run_controller
started = time.monotonic()
run = run_controller(sys.argv[1], mazesim.load_world("arena"), seconds=0.5,
                     stall_seconds=float(sys.argv[2]))
print(json.dumps({"reached_end": run.reached_end, "stopped": run.stopped,
                  "stalled": run.stalled, "exit_status": run.exit_status, "error": run.error,
                  "took": time.monotonic() - started, "tracing": sys.gettrace() is not None,
                  "after": [n * 2 for n in range(3)]}))
"""


@pytest.mark.parametrize(
    ("body", "after_end"),
    [
        # Spins after the end without calling the API, inside a bare except.
        (
            "while robot.step(32) != -1:\n    pass\n"
            "while True:\n    try:\n        while True:\n            pass\n"
            "    except:\n        pass\n",
            True,
        ),
        # Spins before its first step, one function deeper, catching everything.
        (
            "def spin():\n    while True:\n        try:\n            pass\n"
            "        except BaseException:\n            continue\n"
            "while True:\n    try:\n        spin()\n    except:\n        pass\n",
            False,
        ),
    ],
    ids=["after-the-end", "before-the-first-step"],
)
def test_a_controller_looping_without_the_api_is_stopped(
    tmp_path: Path, body: str, after_end: bool
) -> None:
    script = tmp_path / "spin.py"
    script.write_text(f"from controller import Robot\nrobot = Robot()\n{body}")
    done = subprocess.run(
        # A controller that steps until the end is not a stalled one however slow its steps on a
        # loaded machine: the stall watchdog waits its default there, 0.5 s where none comes.
        [sys.executable, "-c", RUN_IN_CHILD, str(script), "60" if after_end else "0.5"],
        capture_output=True,
        text=True,
        timeout=3 * CEILING_S,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    run = json.loads(done.stdout.splitlines()[-1])
    assert run["after"] == [0, 2, 4] and not run["tracing"]
    if after_end:
        assert run["reached_end"] and run["stopped"] and not run["stalled"]
        assert run["exit_status"] == 0
        assert GRACE_SECONDS <= run["took"] < GRACE_SECONDS + CEILING_S
    else:
        assert not run["reached_end"] and run["stalled"] and not run["stopped"]
        assert run["exit_status"] == 1 and "took no step for 0.5 s" in run["error"]
        assert 0.5 <= run["took"] < CEILING_S
    with pytest.raises(InvalidArgumentError, match="stall_seconds"):
        run_controller(script, mazesim.load_world("arena"), stall_seconds=math.nan)


def test_example_controller_avoids_collisions_in_the_arena(tmp_path: Path) -> None:
    result = mazesim_command(
        "webots",
        "run",
        str(EXAMPLE),
        "--world",
        "arena",
        "--seconds",
        "60",
        "--out",
        "out",
        cwd=tmp_path,
    )
    assert result.returncode == 0, result.stderr
    assert "robot.step returned -1" in result.stdout
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["reached_end"] is True
    assert summary["simulated_seconds"] == pytest.approx(60.0)
    assert summary["distance_m"] > 1.0
    # Alg. 1 on the e-puck as Webots simulates it grazes a wall now and then: 0 or 1 bumps a
    # minute over seeds 0-7 (issue #16); never a stall.
    assert summary["collisions"] <= 1
    assert summary["longest_stop_s"] < 1.0, "the robot never stalls"
    assert (tmp_path / "out" / "trajectory.png").read_bytes()[:8] == PNG_MAGIC


def test_example_controller_runs_on_an_imported_webots_world(tmp_path: Path) -> None:
    world = CORPUS / "e-puck.R2023b.wbt"
    result = mazesim_command(
        "webots", "run", str(EXAMPLE), "--world", str(world), "--seconds", "30", cwd=tmp_path
    )
    assert result.returncode == 0, result.stderr
    summary = json.loads((tmp_path / "mazesim-webots" / "summary.json").read_text())
    assert summary["world"] == "e-puck.R2023b"
    assert summary["collisions"] == 0 and summary["distance_m"] > 1.0


def test_webots_run_help_and_errors(tmp_path: Path) -> None:
    help_text = mazesim_command("webots", "run", "--help", cwd=tmp_path)
    assert help_text.returncode == 0
    for option in ("--world", "--seconds", "--seed", "--out"):
        assert option in help_text.stdout
    missing = mazesim_command("webots", "run", "nothing.py", cwd=tmp_path)
    assert missing.returncode == 2
    assert missing.stderr.startswith("mazesim: error: ") and "nothing.py" in missing.stderr
