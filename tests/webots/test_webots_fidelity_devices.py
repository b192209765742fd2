"""Twelve small Webots projects written as users write them, each calling devices in ways the
other suites do not, each run whole and checked against what Webots documents (its reference
manual, cyberbotics.com/doc/reference, and where the manual is silent, Webots' source): a
motor's PID gains, wheels released by ``setAvailableTorque(0)``, a lidar and a range finder on
the turret, a display saved to a file, a speaker's sound, the ``resolution`` of a GPS, a compass
and a sonar, an accelerometer's own table, a robot's battery, a C controller walking its devices
and a C++ odometry (#32)."""

from __future__ import annotations

import functools
import math
import shutil
import statistics
import wave
from pathlib import Path

import numpy as np
import pytest

from mazesim.webots.devices import discretize
from swarm_project import run_project

PROJECT = Path(__file__).resolve().parent.parent / "data" / "webots-fidelity-29"

run = functools.partial(run_project, PROJECT)


def copied_project(tmp_path: Path) -> Path:
    """The project copied under ``tmp_path``, for controllers that write beside themselves."""
    copy = tmp_path / "project"
    shutil.copytree(PROJECT, copy)
    return copy


def test_set_control_pid_sets_the_gain_of_position_control(tmp_path: Path) -> None:
    """Motor "controlPID" (reference manual, Motor): the velocity towards the target is P times
    the error, at most the velocity set (maxVelocity, 6.28 rad/s, by default); ``setControlPID``
    changes the gains (``WbMotor::computeCurrentDynamicVelocity``: P e + I sum(e dt) + D de/dt).
    The left wheel, P = 2, closes its 3 rad error by 2 * 0.032 = 6.4 % a 32 ms step from the
    first; the right, the E-puck's default P = 10, runs at 6.28 rad/s until the error is under
    0.628 rad, then closes 32 % a step."""
    _, logs = run("pid_gains", tmp_path, 2.0)
    angles = np.array(logs["pid_gains"]["angles"])
    steps = np.arange(1, len(angles) + 1)
    assert angles[:, 0] == pytest.approx(3.0 * (1.0 - 0.936**steps), abs=0.01)
    assert angles[:11, 1] == pytest.approx(6.28 * 0.032 * steps[:11], abs=0.01)
    assert angles[-1, 1] == pytest.approx(3.0, abs=0.01)


def webots_pid_angles(gains: tuple[float, float, float], steps: int) -> list[float]:
    """A wheel's angle after each 32 ms step towards 3 rad from 0, by Webots' PID position
    control at most 6.28 rad/s (``WbMotor::computeCurrentDynamicVelocity``; the previous error
    starts at 0)."""
    p, i, d = gains
    angle, integral, previous, angles = 0.0, 0.0, 0.0, []
    for _ in range(steps):
        error = 3.0 - angle
        integral += error * 0.032
        output = p * error + i * integral + d * (error - previous) / 0.032
        previous = error
        angle += max(-6.28, min(6.28, output)) * 0.032
        angles.append(angle)
    return angles


def test_a_c_controller_s_pid_gains_drive_its_wheel_as_webots_pid(
    tmp_path: Path, own_cache: Path
) -> None:
    """``wb_motor_set_control_pid(2, 0.5, 0.01)`` in C: the integral and the derivative terms
    too (the derivative's first kick clamped at maxVelocity); the right wheel keeps P = 10. Both
    read as Webots reads them: Webots' angles rounded to the E-puck PROTO's 0.00628 rad."""
    _, logs = run("pid_gains_c", tmp_path, 2.0)
    angles = np.array(logs["pid_gains_c"]["angles"])
    for side, gains in enumerate(((2.0, 0.5, 0.01), (10.0, 0.0, 0.0))):
        webots = [discretize(a, 0.00628) for a in webots_pid_angles(gains, 40)]
        assert angles[:, side] == pytest.approx(webots, abs=1e-9)


def test_wheels_without_available_torque_do_not_turn(tmp_path: Path) -> None:
    """``wb_motor_set_available_torque(0)``: a motor with no torque has no control
    (``WbMotor::computeCurrentDynamicVelocity``: "no control", speed 0), whatever velocity is
    asked; ``getAvailableTorque`` gives what was set, ``getMaxTorque`` the node's maxTorque
    (10, Motor's default, which the E-puck PROTO keeps). With the torque back, the wheels run
    at the 5 rad/s asked: the 11 steps of 32 ms left (the loop steps once more before its
    count stops it) turn them 1.76 rad."""
    _, logs = run("free_wheels", tmp_path, 2.0)
    log = logs["free_wheels"]
    assert log["available_released"] == 0.0 and log["max"] == 10.0
    assert log["released"] == [0.0, 0.0]
    assert log["available_given"] == 10.0
    assert log["driven"] == pytest.approx([1.76, 1.76], abs=0.02)


def test_a_turret_lidar_measures_the_arena_around_it(tmp_path: Path) -> None:
    """Lidar (reference manual): ``horizontalResolution`` points a layer over ``fieldOfView``,
    the range image's distances in metres. On the turret, 9.5 mm behind the centre of an e-puck
    in the middle of a 0.6 m arena: 72 points 5 degrees apart, the nearest 0.3 - 0.0095 m (the
    wall behind), the farthest 0.3 / cos(45 deg) (the point at 45 degrees to a side wall)."""
    _, logs = run("lidar_turret", tmp_path, 1.0)
    log = logs["lidar_turret"]
    assert (log["resolution"], log["layers"], log["count"]) == (72, 1, 72)
    assert log["max_range"] == 1.0 and log["fov"] == pytest.approx(6.2832)
    assert log["nearest"] == pytest.approx(0.2905, abs=0.002)
    # Whether Webots' first point looks at +fov/2 or half a step inside it, the farthest is
    # within 5 mm of the ray at 45 degrees.
    assert log["farthest"] == pytest.approx(0.3 * math.sqrt(2.0), abs=0.006)
    # Read between enable and the first step (a public project's Gymnasium env does, in its
    # reset): Webots hands the image memory over at the start, so zeros, not None.
    assert log["before"] == [72, [0.0]]


def test_a_turret_range_finder_gives_the_depth_of_the_wall_ahead(tmp_path: Path) -> None:
    """RangeFinder (reference manual): a ``width`` x ``height`` image of depths in metres, read
    with ``rangeImageGetDepth``; its default name is "range-finder". The wall ahead is 0.3 m
    from the centre, 0.3095 m from the turret."""
    _, logs = run("rangefinder_turret", tmp_path, 1.0)
    log = logs["rangefinder_turret"]
    assert (log["width"], log["height"], log["max_range"]) == (16, 1, 1.0)
    assert log["middle"] == pytest.approx(0.3095, abs=0.002)


@pytest.mark.xfail(strict=True, reason="mazesim's displays are not drawn")
def test_a_display_saves_what_it_was_drawn(tmp_path: Path) -> None:
    """Display (reference manual): ``fillRectangle`` and ``drawLine`` in the colour of
    ``setColor`` (0xRRGGBB); ``imageSave(None, file)`` saves the display's content as PNG."""
    project = copied_project(tmp_path)
    _, logs = run_project(project, "display_draw", tmp_path / "logs", 1.0)
    log = logs["display_draw"]
    assert (log["width"], log["height"], log["saved"]) == (32, 16, True)
    from PIL import Image

    image = np.asarray(Image.open(project / "controllers" / "display_draw" / "screen.png"))
    assert image.shape[:2] == (16, 32)
    assert tuple(image[3, 3, :3]) == (255, 0, 0)
    assert tuple(image[8, 15, :3]) == (0, 0, 255)
    assert tuple(image[0, 0, :3]) == (0, 0, 0)


def write_beep(path: Path, seconds: float) -> None:
    """A silent mono WAV of ``seconds``."""
    with wave.open(str(path), "wb") as sound:
        sound.setnchannels(1)
        sound.setsampwidth(1)
        sound.setframerate(8000)
        sound.writeframes(b"\x80" * int(8000 * seconds))


def test_a_speaker_plays_its_sound_for_the_sound_s_duration(tmp_path: Path) -> None:
    """``wb_speaker_is_sound_playing`` (reference manual, Speaker): true while the sound
    played by ``wb_speaker_play_sound`` (without loop) plays: a 0.5 s sound for the steps
    ending at 0.032 ... 0.48 s, no longer at 0.512 s."""
    project = copied_project(tmp_path)
    write_beep(project / "controllers" / "speaker_sounds" / "beep.wav", 0.5)
    _, logs = run_project(project, "speaker_sounds", tmp_path / "logs", 1.5)
    playing = logs["speaker_sounds"]["playing"]
    assert playing == [True] * 15 + [False] * 15


def test_a_gps_and_a_compass_read_to_their_resolution(tmp_path: Path) -> None:
    """GPS and Compass ``resolution`` (reference manual: "the resolution of the sensor"; Webots
    rounds each value v to int(v / r + 0.5) * r, ``WbMathsUtilities::discretize``). The GPS
    on the turret of an e-puck at (0.123, -0.072) turned 0.3 rad stands at (0.1139, -0.0748):
    0.1 and 0.0 (-0.748 + 0.5 truncates to 0); north in the compass frame (sin 0.3, cos 0.3, 0)
    reads (0.5, 1.0, 0.0) at a resolution of 0.5."""
    _, logs = run("gps_resolution", tmp_path, 1.0)
    log = logs["gps_resolution"]
    assert log["gps"][:2] == pytest.approx([0.1, 0.0], abs=1e-12)
    assert log["compass"] == pytest.approx([0.5, 1.0, 0.0], abs=1e-12)


def test_a_turret_accelerometer_reads_through_its_own_table(tmp_path: Path) -> None:
    """Accelerometer ``lookupTable`` (reference manual): m/s^2 mapped linearly, here times 100;
    at rest it reads 9.81 up, 981 through the table, 0 on x and y."""
    _, logs = run("accelerometer_table", tmp_path, 1.0)
    log = logs["accelerometer_table"]
    assert log["table"] == [-20.0, -2000.0, 0.0, 20.0, 2000.0, 0.0]
    assert log["values"] == pytest.approx([0.0, 0.0, 981.0], abs=0.5)


def test_a_robot_s_battery_is_drained_by_its_cpu(tmp_path: Path) -> None:
    """Robot ``battery`` [energy J, max J, recharge W] and ``cpuConsumption`` (10 W by default;
    reference manual, Robot): after each basic step the energy drops by the consumption times
    the step (``WbRobot::postPhysicsStep``), 0.32 J a 32 ms step for a robot whose motors do no
    work; ``batterySensorGetValue`` reads it."""
    _, logs = run("battery_robot", tmp_path, 1.0)
    log = logs["battery_robot"]
    assert log["period"] == 32
    assert log["levels"] == pytest.approx([50.0 - 0.32 * k for k in range(1, 6)], abs=1e-9)


def test_an_empty_battery_stops_the_motors(tmp_path: Path) -> None:
    """Robot ``battery`` (reference manual: "when the current energy value reaches zero ... the
    simulated robot stops all motion"; ``WbMotor::powerOn(false)`` leaves the motors no
    torque): 1 J at 10 W lasts three 32 ms steps and part of a fourth, after which the wheel
    turning at 5 rad/s stops."""
    _, logs = run("battery_drive", tmp_path, 1.0)
    levels, angles = zip(*logs["battery_drive"]["rows"], strict=True)
    assert levels == pytest.approx([0.68, 0.36, 0.04, 0.0, 0.0, 0.0], abs=1e-9)
    assert angles == pytest.approx([0.16, 0.32, 0.48, 0.64, 0.64, 0.64], abs=0.004)


def test_a_battery_that_starts_empty_leaves_the_motors_on(tmp_path: Path) -> None:
    """Robot ``battery`` [0, 100, 0], as a world saved after its robot ran out: Webots drains and
    powers a robot off only while its energy is above 0 (``WbRobot::postPhysicsStep`` steps the
    energy down when it is > 0 and calls ``setCurrentEnergy``, which calls ``powerOn(false)``
    when it reaches 0; a robot starts powered on). So a robot whose battery starts at 0 drives
    on, its battery reading 0."""
    _, logs = run("battery_empty", tmp_path, 1.0)
    levels, angles = zip(*logs["battery_empty"]["rows"], strict=True)
    assert levels == pytest.approx([0.0] * 6, abs=1e-12)
    assert angles == pytest.approx([0.16 * k for k in range(1, 7)], abs=0.004)


def test_a_c_controller_walks_the_e_puck_s_devices_by_index(
    tmp_path: Path, own_cache: Path
) -> None:
    """``wb_robot_get_number_of_devices``, ``wb_robot_get_device_by_index``,
    ``wb_device_get_node_type`` (reference manual, Robot and Device): every device found by
    index is the one its name gives; the E-puck has 8 + 3 distance sensors (with its ground
    sensors), two wheel motors and their sensors, 10 LEDs and a camera."""
    _, logs = run("device_walk_c", tmp_path, 1.0)
    log = logs["device_walk_c"]
    assert log["same"] == log["count"] and log["count"] >= 24
    assert (log["motors"], log["encoders"], log["leds"], log["cameras"]) == (2, 2, 10, 1)
    assert log["distance"] >= 8 and log["time_step"] == 32


def test_a_cpp_controller_integrates_its_odometry(tmp_path: Path, own_cache: Path) -> None:
    """C++ ``Robot``, ``Motor::getPositionSensor``, ``PositionSensor::getValue`` (reference
    manual): 30 steps of 32 ms at 3 rad/s turn each wheel 2.88 rad; the odometry of equal
    wheels goes straight, 0.0205 m a radian after the first reading."""
    _, logs = run("cpp_odometry", tmp_path, 2.0)
    log = logs["cpp_odometry"]
    assert log["left"] == pytest.approx(2.88, abs=0.01)
    assert log["right"] == pytest.approx(2.88, abs=0.01)
    assert log["x"] == pytest.approx(0.0205 * 2.88 * 29 / 30, abs=0.001)
    assert log["theta"] == pytest.approx(0.0, abs=1e-6)
    # The loop steps a 31st time before its count stops it.
    assert log["time"] == pytest.approx(0.992) and log["sampling"] == 32


def test_a_sonar_s_noise_column_and_resolution(tmp_path: Path) -> None:
    """DistanceSensor ``lookupTable`` third column: the standard deviation of the Gaussian noise
    relative to the value; ``resolution`` 1 rounds each reading to a whole number (reference
    manual, DistanceSensor). The sonar 7 cm from the wall reads 70 on average, about 3.5 apart,
    always whole."""
    _, logs = run("ds_noise_column", tmp_path, 7.0)
    values = logs["ds_noise_column"]["values"]
    assert len(values) == 200
    assert all(v == int(v) for v in values)
    assert statistics.mean(values) == pytest.approx(70.0, abs=1.0)
    assert 2.5 < statistics.stdev(values) < 4.5


def test_the_e_puck_s_wheel_sensors_read_the_true_angle_to_the_proto_s_resolution() -> None:
    """Position control closes on the wheel's true angle (``WbMotor``: the joint's position)
    and the wheel sensors round it to the E-puck PROTO's ``resolution 0.00628`` as Webots
    rounds (``WbPositionSensor::position``, ``discretize``: ``int(v / r + 0.5) * r``). A wheel
    sent to 8.25 rad settles within a micro-radian of it and reads 1314 steps, 8.25192 rad, at
    least its target (a controller waiting for that, as MTRN4110's phase D does, goes on); one
    sent to -1 rad reads -158 steps (the cast truncates towards 0), not -159."""
    import mazesim
    from mazesim.webots import controller, prepare
    from mazesim.webots import simulation as simulations

    prepare(mazesim.load_world("arena"), seconds=5.0, noise=False)
    try:
        controller.Robot.created = None
        robot = controller.Robot()
        motors = [robot.getDevice(f"{side} wheel motor") for side in ("left", "right")]
        sensors = [robot.getDevice(f"{side} wheel sensor") for side in ("left", "right")]
        for motor, target, sensor in zip(motors, (8.25, -1.0), sensors):
            motor.setPosition(target)
            sensor.enable(32)
        for _ in range(125):
            robot.step(32)
        true = simulations.current().wheel_angles()
        assert true == pytest.approx((8.25, -1.0), abs=1e-6)
        readings = [sensor.getValue() for sensor in sensors]
        assert readings == [1314 * 0.00628, -158 * 0.00628]
        assert readings[0] >= 8.25
    finally:
        controller.Robot.created = None
        simulations.release()
