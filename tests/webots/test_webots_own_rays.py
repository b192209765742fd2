"""A robot's proximity rays as the world writes them, in a run of one robot and in a world run
alike (:func:`mazesim.webots.own_sensors.own_sensors`): an ``E-puck`` PROTO's rays rise by the
PROTO's stock 0.16 rad, an expanded e-puck's by its own DistanceSensor rotation, and a
DistanceSensor whose ``type`` is not ``infra-red`` reads the distance alone, whatever colour its
ray meets (Webots' reference manual, DistanceSensor; docs/webots.md)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mazesim import RobotProfile, Simulator, World
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.devices import PROXIMITY_TABLE
from mazesim.webots.own_sensors import own_sensors
from mazesim.webots.scene import EPUCK_IR_ELEVATION, read_scene
from proximity_probe import SENSORS, probe_world_run

#: Walls at x, y = +-0.25 m.
ARENA = (
    "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\nRectangleArena { floorSize 0.5 0.5 }\n"
)
STOCK_ROWS = ", ".join(" ".join(repr(v) for v in row) for row in PROXIMITY_TABLE)


def expanded_e_puck(
    *, tilt: float = 0.16, sensor_type: str | None = "infra-red", at: float = 0.203
) -> str:
    """A plain ``Robot`` e-puck saved expanded as Webots saves its E-puck: each DistanceSensor
    in a Solid at the sensor's place and heading, turned about the mount's y axis by ``-tilt``
    (which raises its ray by ``tilt``), with the stock table and ``type``; at x = ``at``."""
    kind = "" if sensor_type is None else f' type "{sensor_type}"'
    sensors = "".join(
        f"    Solid {{ translation {x} {y} 0.033 rotation 0 0 1 {yaw} children [ "
        f'DistanceSensor {{ rotation 0 1 0 {-tilt!r} name "{name}" lookupTable [ {STOCK_ROWS} ]'
        f"{kind} }} ] }}\n"
        for name, x, y, yaw in SENSORS
    )
    return (
        f"Robot {{\n  translation {at} 0 0\n  children [\n{sensors}"
        '    HingeJoint { device [ RotationalMotor { name "left wheel motor" } ] '
        "endPoint Solid { translation 0 0.026 0.02 } }\n"
        '    HingeJoint { device [ RotationalMotor { name "right wheel motor" } ] '
        "endPoint Solid { translation 0 -0.026 0.02 } }\n"
        '  ]\n  name "expanded"\n  controller "probe"\n}\n'
    )


def test_the_proto_s_stock_tilt_comes_from_the_one_function_as_its_own_rotation_does() -> None:
    proto = own_sensors("e-puck", read_scene(ARENA + "E-puck { }\n"))
    assert proto.elevations == {name: EPUCK_IR_ELEVATION for name, *_ in SENSORS}
    assert proto.profile == RobotProfile.builtin("e-puck").with_infrared_elevation(0.16)
    expanded = own_sensors("e-puck", read_scene(ARENA + expanded_e_puck()))
    assert expanded.elevations == pytest.approx(proto.elevations, abs=1e-12)
    assert expanded.tables == {} and expanded.poses == {} and expanded.types == {}
    assert expanded.profile is not None
    assert expanded.profile.distance_sensor_elevations() == pytest.approx([0.16] * 8, abs=1e-12)
    level = own_sensors("e-puck", read_scene(ARENA + expanded_e_puck(tilt=0.0)))
    assert level.profile is None and level.elevations == {}


def _box_ahead() -> World:
    """A wall whose face is 0.06 m ahead of the robot's centre."""
    return World.from_toml(
        'format = "mazesim-world"\nversion = 1\n[[walls]]\ncenter = [0.56, 0.0]\nsize = [1, 1]\n'
    )


def test_an_expanded_e_puck_reads_along_its_own_tilted_rays_as_the_proto_does() -> None:
    readings = []
    for text in (
        ARENA + "E-puck { }\n",
        ARENA + expanded_e_puck(),
        ARENA + expanded_e_puck(tilt=0),
    ):
        prepare(_box_ahead(), seconds=1.0, noise=False, scene=read_scene(text))
        readings.append(simulations.current().simulator.distance_sensors())
        simulations.release()
    proto, expanded, level = readings
    assert expanded == pytest.approx(proto, rel=1e-6)
    assert np.all(proto[[0, 7]] < level[[0, 7]])


def test_a_ray_tilted_down_onto_the_floor_within_its_range_is_named() -> None:
    # 0.7 rad down from 3.3 cm: the floor 0.051 m along the ray, within its 0.07 m.
    own = own_sensors("e-puck", read_scene(ARENA + expanded_e_puck(tilt=-0.7)))
    (warning,) = own.warnings
    assert warning.startswith("the ray of DistanceSensor 'ps0' (0.051 m), 'ps1' (0.051 m)")
    assert "where Webots reads the floor" in warning
    assert own.elevations == pytest.approx({name: 0.7 for name, *_ in SENSORS})
    # 0.16 rad down: the floor 0.207 m along the ray, beyond its reach; nothing to say.
    assert own_sensors("e-puck", read_scene(ARENA + expanded_e_puck(tilt=-0.16))).warnings == []


def _one_robot_readings(text: str) -> list[float]:
    """ps0..ps7 of the world's first robot after one step of a run of it alone."""
    from mazesim.webots.importer import import_wbt_text

    world, report = import_wbt_text(text, "one.wbt")
    scene = read_scene(text, report.get("robot_model"), report.get("robot_line"))
    prepare(world, seconds=1.0, noise=False, report=report, scene=scene)
    try:
        robot = controller.Robot()
        sensors = [robot.getDevice(name) for name, *_ in SENSORS]
        for sensor in sensors:
            sensor.enable(32)
        robot.step(32)
        return [sensor.getValue() for sensor in sensors]
    finally:
        controller.Robot.created = None
        simulations.release()


def test_a_world_run_tilts_each_robot_s_rays_as_a_run_of_one_robot_does(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    proto = 'E-puck { translation 0.2 0 0 name "proto" controller "probe" }\n'
    far = 'E-puck { translation -0.15 0.1 0 rotation 0 0 1 3.1416 name "far" controller "probe" }\n'
    readings = probe_world_run(tmp_path, monkeypatch, ARENA + proto + far)
    alone = _one_robot_readings(ARENA + proto)
    assert readings["proto"]["values"] == alone
    level = Simulator(_box_ahead(), noise=False).distance_sensors()
    tilted = Simulator(
        _box_ahead(),
        robot=RobotProfile.builtin("e-puck").with_infrared_elevation(0.16),
        noise=False,
    ).distance_sensors()
    assert not np.array_equal(level, tilted)
    expanded = probe_world_run(
        tmp_path / "expanded", monkeypatch, ARENA + expanded_e_puck(at=0.2) + far
    )
    assert expanded["expanded"]["values"] == pytest.approx(readings["proto"]["values"], rel=1e-6)


def _dark_wall_readings(sensor_type: str | None) -> tuple[np.ndarray, list[int]]:
    """ps0..ps7 and their types for an expanded e-puck of ``sensor_type`` sensors facing a wall
    of reflectance 0.5 whose face is 0.06 m ahead of its centre."""
    text = ARENA + expanded_e_puck(tilt=0.0, sensor_type=sensor_type)
    dark = World.from_toml(
        'format = "mazesim-world"\nversion = 1\n[[walls]]\ncenter = [0.56, 0.0]\nsize = [1, 1]\n'
        "reflectance = 0.5\n"
    )
    prepare(dark, seconds=1.0, noise=False, scene=read_scene(text))
    try:
        robot = controller.Robot()
        types = [robot.getDevice(name).getType() for name, *_ in SENSORS]
        return simulations.current().simulator.distance_sensors(), types
    finally:
        controller.Robot.created = None
        simulations.release()


def test_only_an_infra_red_distance_sensor_reads_the_colour_its_ray_meets() -> None:
    infra_red, ir_types = _dark_wall_readings("infra-red")
    generic, generic_types = _dark_wall_readings(None)
    sonar, _ = _dark_wall_readings("sonar")
    assert ir_types == [controller.DistanceSensor.INFRA_RED] * 8
    assert generic_types == [controller.DistanceSensor.GENERIC] * 8
    # The stock infra-red sensor reads bit for bit as the built-in profile.
    dark = World.from_toml(
        'format = "mazesim-world"\nversion = 1\n[[walls]]\ncenter = [0.56, 0.0]\nsize = [1, 1]\n'
        "reflectance = 0.5\n"
    )
    assert np.array_equal(infra_red, Simulator(dark, noise=False).distance_sensors())
    # ps7 meets the wall 0.03 / cos(0.3) m along its ray: the generic one reads that distance
    # through the table, the infra-red one that distance over the reflectance 0.5.
    distance = 0.03 / np.cos(0.3)
    rows = np.array(PROXIMITY_TABLE)
    assert float(generic[7]) == pytest.approx(np.interp(distance, rows[:, 0], rows[:, 1]), rel=2e-3)
    assert float(infra_red[7]) == pytest.approx(
        np.interp(distance / 0.5, rows[:, 0], rows[:, 1]), rel=2e-3
    )
    assert generic[7] > infra_red[7]
    assert np.array_equal(sonar, generic)


def test_what_the_2d_model_leaves_out_of_a_sensor_type_is_said() -> None:
    for sensor_type, said in (
        ("sonar", "22.5 degrees"),
        ("laser", "red spot"),
        ("ultrasonic", "expected one of 'generic', 'sonar', 'laser', 'infra-red'"),
    ):
        own = own_sensors(
            "e-puck", read_scene(ARENA + expanded_e_puck(tilt=0.0, sensor_type=sensor_type))
        )
        (warning,) = own.warnings
        assert warning.startswith("DistanceSensor 'ps0', 'ps1'") and said in warning
        assert f"(type {sensor_type!r})" in warning
    assert (
        own_sensors("e-puck", read_scene(ARENA + expanded_e_puck(sensor_type=None))).warnings == []
    )


def test_a_type_written_in_another_case_reads_as_webots_reads_it() -> None:
    # Webots compares the field without case and takes "infrared" too: such a sensor reads the
    # colour its ray meets as "infra-red" does, and nothing is said of it; "Sonar" is a sonar.
    infra_red, _ = _dark_wall_readings("infra-red")
    for written in ("Infra-Red", "infrared"):
        readings, types = _dark_wall_readings(written)
        assert types == [controller.DistanceSensor.INFRA_RED] * 8
        assert np.array_equal(readings, infra_red)
        scene = read_scene(ARENA + expanded_e_puck(tilt=0.0, sensor_type=written))
        assert own_sensors("e-puck", scene).warnings == []
    (warning,) = own_sensors(
        "e-puck", read_scene(ARENA + expanded_e_puck(tilt=0.0, sensor_type="Sonar"))
    ).warnings
    assert "22.5 degrees" in warning and "expected one of" not in warning


def test_a_sensor_of_the_world_reads_its_far_value_in_a_world_without_walls() -> None:
    # A Floor and no wall: the extension sensor's rays meet nothing (the cast took a wall's
    # reflectance from an empty table and stopped the first step with IndexError).
    from mazesim.webots.importer import import_wbt_text

    text = (
        "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\nFloor { }\n"
        'E-puck { turretSlot [ DistanceSensor { translation 0.03 0 0 name "front" '
        "lookupTable [ 0 0 0, 0.2 200 0 ] } ] }\n"
    )
    world, report = import_wbt_text(text, "bare.wbt")
    assert len(world.wall_boxes()) == 0
    scene = read_scene(text, report.get("robot_model"), report.get("robot_line"))
    prepare(world, seconds=1.0, noise=False, report=report, scene=scene)
    try:
        robot = controller.Robot()
        front = robot.getDevice("front")
        front.enable(32)
        assert robot.step(32) != -1
        assert front.getValue() == 200.0
    finally:
        controller.Robot.created = None
        simulations.release()


def test_a_device_size_beyond_what_mazesim_simulates_is_cut_with_a_warning(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # A camera 2^31 pixels wide asked for 16 GiB at its first image (the run was killed);
    # each size field beyond MAX_DEVICE_SIDE is cut to it, saying so.
    from mazesim.webots.devices import MAX_DEVICE_SIDE
    from mazesim.webots.importer import import_wbt_text

    text = (
        "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\nFloor { }\n"
        "E-puck { camera_width 1e9 turretSlot [\n"
        '  Camera { name "big" width 2147483648 height 2 }\n'
        '  Lidar { name "lidar" horizontalResolution 1e12 numberOfLayers 1 }\n'
        '  RangeFinder { name "depth" width 3 height 100000000 }\n'
        '  Display { name "screen" width 1e15 height 4 }\n] }\n'
    )
    world, report = import_wbt_text(text, "huge.wbt")
    scene = read_scene(text, report.get("robot_model"), report.get("robot_line"))
    prepare(world, seconds=1.0, noise=False, report=report, scene=scene)
    try:
        robot = controller.Robot()
        big, lidar, depth = (robot.getDevice(n) for n in ("big", "lidar", "depth"))
        assert (big.getWidth(), big.getHeight()) == (MAX_DEVICE_SIDE, 2)
        assert robot.getDevice("camera").getWidth() == MAX_DEVICE_SIDE
        assert lidar.getHorizontalResolution() == MAX_DEVICE_SIDE
        assert (depth.getWidth(), depth.getHeight()) == (3, MAX_DEVICE_SIDE)
        assert robot.getDevice("screen").getWidth() == MAX_DEVICE_SIDE
        for device in (big, lidar, depth):
            device.enable(32)
        assert robot.step(32) != -1
        assert len(big.getImage()) == MAX_DEVICE_SIDE * 2 * 4
        assert len(lidar.getRangeImage()) == MAX_DEVICE_SIDE
        warned = capsys.readouterr().err
        for what in ("Camera 'big' width 2147483648", "camera_width 1000000000",
                     "Lidar 'lidar' horizontalResolution", "RangeFinder 'depth' height",
                     "Display 'screen' width"):  # fmt: skip
            assert f"{what}" in warned and f"taken as {MAX_DEVICE_SIDE}" in warned, what
    finally:
        controller.Robot.created = None
        simulations.release()
