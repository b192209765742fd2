"""Small Webots projects written as users write them, each checked against what Webots
documents (its reference manual, cyberbotics.com/doc/reference, and its controller library,
src/controller/c): sensors read before the first step and their units, a wheel's position
sensor read before it is enabled, a supervisor's quit ending every controller's step, broadcast
radio on channel -1 with the signal strength, a camera's saved image, a supervisor moving and
resetting a robot through its fields, and the GPS's speed, in Python and in C (#32). The
readings before the first step that docs/webots.md lists are these tests'."""

from __future__ import annotations

import functools
import math
from pathlib import Path

import pytest

from swarm_project import run_project

PROJECT = Path(__file__).resolve().parent.parent / "data" / "webots-fidelity-32"
#: Where the E-puck PROTO puts its ``turretSlot`` in the robot's frame (m): 9.5 mm behind the
#: centre, 48.6 mm up.
TURRET = (-0.0095, 0.0, 0.0486)
#: The E-puck PROTO's wheel radius (m) and its encoders' ``resolution`` (rad).
WHEEL_RADIUS = 0.02
ENCODER_RESOLUTION = 0.00628

run = functools.partial(run_project, PROJECT)


def _turret(x: float, y: float, yaw: float) -> tuple[float, float, float]:
    """Where the turret slot of an e-puck at ``x``, ``y`` heading ``yaw`` is."""
    c, s = math.cos(yaw), math.sin(yaw)
    return x + c * TURRET[0] - s * TURRET[1], y + s * TURRET[0] + c * TURRET[1], TURRET[2]


def test_sensors_read_nan_before_the_first_step_then_in_their_units(tmp_path: Path) -> None:
    """Before the first sampling period every reading is NaN, each component of it: Webots'
    controller library creates each sensor's values as NaN (src/controller/c/gps.c,
    compass.c, gyro.c, accelerometer.c, touch_sensor.c ``values[i] = NAN``), the inertial unit's
    quaternion as much as its angles, and a force-3d touch sensor's three values as much as its
    one. After one step: the GPS gives metres in the world frame (the turret slot of the e-puck
    at 0.1, 0.05, heading 0.5 rad) and its speed 0 m/s at rest; the inertial unit its roll,
    pitch and yaw in radians and the same orientation as a quaternion [x, y, z, w]; the compass
    the north direction (world y) in its own frame, [sin 0.5, cos 0.5, 0]; the accelerometer
    about 9.81 m/s^2 up; the touch sensor no force (GPS, InertialUnit, Compass, Accelerometer,
    TouchSensor pages of the reference manual)."""
    _, logs = run("sensors_unset", tmp_path, 0.5)
    log = logs["sensors_unset"]
    for name, values in log["before"].items():
        assert values == "nan" if name == "speed" else values == ["nan"] * len(values), name
    after = log["after"]
    assert after["gps"] == pytest.approx(_turret(0.1, 0.05, 0.5), abs=1e-6)
    assert after["speed"] == 0.0
    assert after["roll_pitch_yaw"] == pytest.approx([0.0, 0.0, 0.5], abs=1e-6)
    assert after["quaternion"] == pytest.approx([0.0, 0.0, math.sin(0.25), math.cos(0.25)])
    assert after["compass"] == pytest.approx([math.sin(0.5), math.cos(0.5), 0.0], abs=1e-6)
    assert after["accelerometer"][2] == pytest.approx(9.81, rel=0.02)
    assert after["touch"] == [0.0, 0.0, 0.0]
    assert log["periods"] == [32] * 6


def test_a_c_position_sensor_read_before_enable_is_nan(tmp_path: Path, own_cache: Path) -> None:
    """PositionSensor (reference manual; src/controller/c/position_sensor.c creates its value
    as NaN): read before ``wb_position_sensor_enable`` it is NaN and its sampling period 0;
    enabled, it is still NaN until a step has passed, then the joint's angle in radians (0 at
    the start), WB_ROTATIONAL for a wheel, and the sensor and its motor name each other. Ten
    steps of 32 ms at 2 rad/s turn the wheel 0.64 rad, read to the encoder's resolution."""
    _, logs = run("position_sensor_c", tmp_path, 1.0)
    log = logs["position_sensor_c"]
    assert (log["unset"], log["period_unset"], log["enabled"]) == ("nan", 0, "nan")
    assert log["first"] == 0.0
    assert log["turned"] == pytest.approx(10 * 0.032 * 2.0, abs=ENCODER_RESOLUTION)
    assert log["period"] == 32
    assert log["type"] == log["rotational"]
    assert log["motor_matches"] == log["sensor_matches"] == 1


def test_a_c_supervisor_s_quit_ends_every_controller_s_step(
    tmp_path: Path, own_cache: Path
) -> None:
    """Supervisor (reference manual, ``wb_supervisor_simulation_quit``): Webots quits with the
    status given, and ``wb_robot_step`` returns -1 to every controller (Robot,
    ``wb_robot_step``: -1 when Webots terminates the controller), the supervisor's own next
    step included; the steps before returned 0. The other robot saw the same three steps."""
    done, logs = run("quit_c", tmp_path, 5.0)
    assert logs["quit_c"]["returned"] == [0, 0, 0, -1]
    assert logs["quit_c"]["time"] == pytest.approx(0.096)
    assert logs["watcher"] == {"steps": 3, "time": pytest.approx(0.096)}
    assert done.exit_status == 3


def test_broadcast_channel_and_signal_strength(tmp_path: Path) -> None:
    """Emitter and Receiver (reference manual): an emitter on channel -1
    (``Emitter.CHANNEL_BROADCAST``) reaches receivers of every channel, and a receiver on
    channel -1 hears every channel; a receiver on channel 7 does not hear an emitter on
    channel 3. The signal strength is the inverse of the squared distance between emitter and
    receiver (1 / 0.5^2 = 4, 1 / 0.2^2 = 25, 1 / (0.3^2 + 0.2^2))."""
    _, logs = run("broadcast", tmp_path, 0.5)
    assert logs["seven"] == {"channel": 7, "heard": {"to everyone": pytest.approx(4.0)}}
    assert logs["all"]["channel"] == -1
    assert logs["all"]["heard"] == {
        "to everyone": pytest.approx(25.0),
        "on three": pytest.approx(1 / 0.13),
    }


def test_camera_save_image_writes_png_or_jpeg_by_extension(tmp_path: Path) -> None:
    """Camera (reference manual, ``wb_camera_save_image``): the image is saved as PNG or JPEG
    by the file name's extension, and the call returns 0 on success, -1 on failure: before
    the camera has an image (before the first step) and for another extension nothing is
    written. The PNG's header gives the camera's width and height (the e-puck's 52 x 39)."""
    _, logs = run("camera_save", tmp_path, 0.2)
    log = logs["camera_save"]
    assert log["returned"] == {"early": -1, "shot.png": 0, "shot.jpg": 0, "shot.bmp": -1}
    heads = log["heads"]
    assert heads["early.png"] is None and heads["shot.bmp"] is None
    png = bytes.fromhex(heads["shot.png"])
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    width, height = int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")
    assert [width, height] == log["size"] == [52, 39]
    assert bytes.fromhex(heads["shot.jpg"])[:3] == b"\xff\xd8\xff"


def test_a_c_supervisor_moves_and_resets_a_robot_by_its_fields(
    tmp_path: Path, own_cache: Path
) -> None:
    """Supervisor (reference manual): ``wb_supervisor_field_get_sf_vec3f`` of the DEF RUNNER
    node's ``translation`` gives the file's value; ``wb_supervisor_node_get_velocity`` the
    linear and angular velocities (the runner drives at 4 rad/s: 4 x 0.02 = 0.08 m/s along its
    heading, x); ``wb_supervisor_field_set_sf_vec3f`` moves it (the field and
    ``wb_supervisor_node_get_position`` read the new place a step later, give or take the one
    step it drove, 2.56 mm); ``wb_supervisor_node_reset_physics`` zeroes the body's velocities
    (ODE's ``dBodySetLinearVel``), which its wheels, at 4 rad/s with no acceleration limit in
    the E-puck PROTO, give back within the step; ``wb_supervisor_simulation_reset`` resets the
    simulation time and the Solid's ``translation`` to the file's (the Reset/Reload matrix)."""
    _, logs = run("supervisor_fields_c", tmp_path, 1.0)
    log = logs["supervisor_fields_c"]
    assert log["start"] == pytest.approx([-0.4, 0.1, 0.0])
    assert log["driving"] == pytest.approx([4.0 * WHEEL_RADIUS, 0, 0, 0, 0, 0], abs=1e-4)
    assert log["moved"] == pytest.approx([0.25, -0.3, 0.0], abs=0.003)
    assert log["position"] == pytest.approx(log["moved"], abs=1e-6)
    assert log["stopped"] == pytest.approx(log["driving"], abs=1e-3)
    assert log["before_reset"] == pytest.approx(0.192)
    assert log["reset"] == pytest.approx([-0.4, 0.1, 0.0], abs=1e-6)
    assert log["after_reset"] == 0.0


def test_a_c_gps_speed_in_metres_a_second(tmp_path: Path, own_cache: Path) -> None:
    """GPS (reference manual): ``wb_gps_get_speed`` is m/s and ``wb_gps_get_speed_vector``
    the velocity in the world frame: an e-puck heading north (yaw pi/2, which the inertial unit
    reads in radians) with both wheels at 4 rad/s goes 0.08 m/s along y, and after 20 steps of
    32 ms its turret slot is 0.0512 m further north. Before the first step the GPS's values,
    its speed and the inertial unit's angles and quaternion are NaN, in C as in Python."""
    _, logs = run("gps_speed_c", tmp_path, 1.0)
    log = logs["gps_speed_c"]
    assert log["early_nan"] == 1
    assert log["quaternion_nan"] == 4
    assert log["speed"] == pytest.approx(4.0 * WHEEL_RADIUS, rel=1e-3)
    assert log["vector"] == pytest.approx([0.0, 4.0 * WHEEL_RADIUS, 0.0], abs=1e-4)
    assert log["yaw"] == pytest.approx(math.pi / 2, abs=1e-4)
    x, y, z = _turret(0.0, 0.0, math.pi / 2)
    assert log["where"] == pytest.approx([x, y + 20 * 0.032 * 4.0 * WHEEL_RADIUS, z], abs=2e-4)


def test_no_reading_is_partly_nan_before_the_first_step(tmp_path: Path) -> None:
    """The class behind the first test, over every device an e-puck can carry: before the
    first sampling period each list a getter answers is NaN in every component or in none
    (Webots creates each kept reading NaN whole; a list of zeros is an image Webots keeps
    zero-filled, a lidar's and a range finder's). The readings the reference manual gives
    per sensor are NaN throughout. A getter of one number answers NaN only for a reading
    (``getValue``, the GPS's ``getSpeed``, the signal strength of an empty receiver queue, a
    motor's torque feedback never enabled, NaN in Webots' motor.c),
    never for what the node's fields give: a Lidar's ``getMinFrequency`` and
    ``getMaxFrequency`` are its ``minFrequency`` and ``maxFrequency`` (1 Hz by default,
    reference manual, Lidar; the world sets 20 Hz)."""
    _, logs = run("every_reading", tmp_path, 0.1)
    lists = logs["every_reading"]["lists"]
    partly = {name: nans for name, nans in lists.items() if any(nans) and not all(nans)}
    assert partly == {}
    for name in [
        "gps.getValues",
        "gps.getSpeedVector",
        "inertial unit.getRollPitchYaw",
        "inertial unit.getQuaternion",
        "compass.getValues",
        "touch sensor.getValues",
        "accelerometer.getValues",
        "gyro.getValues",
    ]:
        assert lists[name] and all(lists[name]), name
    readings = ("getValue", "getSpeed", "getSignalStrength", "Feedback")
    assert [n for n in logs["every_reading"]["nan_numbers"] if not n.endswith(readings)] == []
    assert "gps.getSpeed" in logs["every_reading"]["nan_numbers"]
    assert logs["every_reading"]["lidar_frequencies"] == [1.0, 20.0]
