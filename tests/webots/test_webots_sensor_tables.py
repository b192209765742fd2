"""A plain ``Robot`` e-puck saved expanded with its own ``DistanceSensor`` nodes reads each
sensor through that node's ``lookupTable``, as Webots does: a 10-bit table reads 0..1023, the
stock table reads exactly as the built-in e-puck, and a table the profile format refuses keeps
the built-in one with a warning."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from mazesim import RobotProfile, robot_profile_names
from mazesim._toml import load_toml
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.devices import PROXIMITY_TABLE
from mazesim.webots.importer import import_wbt_text
from mazesim.webots.own_sensors import _profile_with, own_sensors
from mazesim.webots.scene import DEFAULT_LOOKUP_TABLE, read_scene
from proximity_probe import SENSORS, plain_robot, probe_world_run, table_text

#: The 10-bit proximity table of some course worlds (the e-puck's values scaled to 0..1023).
TEN_BIT = ((0.0, 1023.0, 0.0), (0.005, 868.0, 0.0), (0.01, 539.0, 0.0), (0.02, 169.0, 0.0))
TEN_BIT += ((0.03, 59.0, 0.0), (0.07, 17.0, 0.0))
#: The e-puck2's time-of-flight table (E-puck.proto, version "2", DistanceSensor "tof"):
#: distance (m), reading (mm), relative noise.
TOF_TABLE = ((0.0, 19.8, 0.126), (0.05, 58.5, 0.032), (0.1, 111.0, 0.019), (0.2, 218.9, 0.009))
TOF_TABLE += ((0.5, 531.9, 0.007), (1.0, 1052.0, 0.01), (1.7, 1780.5, 0.013), (2.0, 2000.0, 0.0))
#: Distances not increasing: the profile format refuses it.
REFUSED = ((0.02, 500.0, 0.0), (0.01, 1000.0, 0.0), (0.07, 10.0, 0.0))


ARENA = (
    "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\nRectangleArena { floorSize 0.5 0.5 }\n"
)


def plain_robot_world(rows: tuple[tuple[float, float, float], ...] | None) -> str:
    """A plain ``Robot`` e-puck whose ps0..ps7 carry ``rows``, 2 cm from a wall ahead (+x)."""
    return ARENA + plain_robot(rows)


@pytest.fixture(autouse=True)
def _released() -> Iterator[None]:
    controller.Robot.created = None
    yield
    controller.Robot.created = None
    simulations.release()


def front_readings(text: str, *, with_scene: bool = True) -> tuple[list[float], controller.Robot]:
    """ps0..ps7 after one step of a controller in the world ``text`` (no noise)."""
    world, report = import_wbt_text(text, "tables.wbt")
    assert report["robot_profile"] == "e-puck"
    scene = read_scene(text, report.get("robot_model"), report.get("robot_line"))
    prepare(world, seconds=1.0, noise=False, report=report, scene=scene if with_scene else None)
    robot = controller.Robot()
    sensors = [robot.getDevice(name) for name, *_ in SENSORS]
    for sensor in sensors:
        sensor.enable(32)
    robot.step(32)
    return [sensor.getValue() for sensor in sensors], robot


def test_the_scene_reads_the_robot_s_own_tables() -> None:
    scene = read_scene(plain_robot_world(TEN_BIT))
    assert set(scene.sensor_tables) == {name for name, *_ in SENSORS}
    assert scene.sensor_tables["ps3"] == list(TEN_BIT)


def test_a_10_bit_table_reads_as_the_world_says() -> None:
    stock, _ = front_readings(plain_robot_world(PROXIMITY_TABLE))
    controller.Robot.created = None
    simulations.release()
    readings, robot = front_readings(plain_robot_world(TEN_BIT))
    # Each sensor's distance, from its stock reading (the stock table falls all the way).
    distances = [
        np.interp(-r, [-row[1] for row in PROXIMITY_TABLE], [row[0] for row in PROXIMITY_TABLE])
        for r in stock
    ]
    expected = [
        np.interp(d, [row[0] for row in TEN_BIT], [row[1] for row in TEN_BIT]) for d in distances
    ]
    # The front sensors see the wall 2 cm ahead; all readings are on the 10-bit scale.
    assert stock[0] > 300.0 and stock[7] > 300.0
    assert max(readings) <= 1023.0
    assert readings == pytest.approx(expected, rel=2e-3, abs=0.05)
    ps0 = robot.getDevice("ps0")
    assert ps0.getLookupTable() == [v for row in TEN_BIT for v in row]
    assert ps0.getMaxValue() == 1023.0 and ps0.getMinValue() == 17.0


def test_the_stock_table_reads_as_the_built_in_profile_bit_for_bit() -> None:
    text = plain_robot_world(PROXIMITY_TABLE)
    stock, _ = front_readings(text)
    assert simulations.current().sensor_tables == {}
    controller.Robot.created = None
    simulations.release()
    built_in, _ = front_readings(text, with_scene=False)
    assert stock == built_in


def test_a_refused_table_warns_and_runs(capsys: pytest.CaptureFixture[str]) -> None:
    readings, robot = front_readings(plain_robot_world(REFUSED))
    warnings = [line for line in capsys.readouterr().err.splitlines() if "lookupTable" in line]
    # One line names every sensor whose table was not used, and why.
    (warning,) = warnings
    assert warning.startswith("mazesim: warning: ")
    assert all(f"'{name}'" in warning for name, *_ in SENSORS)
    assert warning.endswith("row 1 (0.01) is not above row 0 (0.02)")
    assert robot.getDevice("ps0").getMaxValue() == 4095.0
    assert readings[0] > 300.0


@pytest.mark.parametrize("name", robot_profile_names())
def test_the_profile_text_is_written_back_as_it_was_read(name: str) -> None:
    text = RobotProfile.builtin(name).to_toml()
    again = _profile_with(load_toml(text, name), {})
    assert again.to_toml() == text


def test_a_webots_6_differential_wheels_e_puck_s_tables_are_read() -> None:
    text = plain_robot_world(TEN_BIT).replace("Robot {", "DifferentialWheels {")
    text = text.replace("#VRML_SIM R2023b", "#VRML_SIM V6.4.0")
    _, report = import_wbt_text(text, "old.wbt")
    scene = read_scene(text, report.get("robot_model"), report.get("robot_line"))
    assert scene.robot_name == "e-puck"
    assert scene.sensor_tables["ps0"] == list(TEN_BIT)
    assert set(own_sensors("e-puck", scene).tables) == {n for n, *_ in SENSORS}


def test_a_sensor_without_a_lookup_table_reads_through_webots_default() -> None:
    """Webots' DistanceSensor ``lookupTable`` defaults to ``[0 0 0, 0.1 1000 0]``: 0 touching,
    rising to 1000 at 0.1 m and beyond, which the profile format takes as it is."""
    stock, _ = front_readings(plain_robot_world(PROXIMITY_TABLE))
    controller.Robot.created = None
    simulations.release()
    readings, robot = front_readings(plain_robot_world(None))
    assert read_scene(plain_robot_world(None)).sensor_tables["ps0"] == DEFAULT_LOOKUP_TABLE
    inputs = [-row[1] for row in PROXIMITY_TABLE]
    for index, (value, seen) in enumerate(zip(readings, stock)):
        if seen > PROXIMITY_TABLE[-1][1] + 0.01:
            # Within the stock table's 7 cm: the same distance on the rising table.
            distance = np.interp(-seen, inputs, [row[0] for row in PROXIMITY_TABLE])
            assert value == pytest.approx(distance * 10_000.0, rel=2e-3, abs=0.05), index
        else:
            assert value > 700.0, index
    # The front sees the wall 2 cm ahead (reading about 200); the rear sees nothing near.
    assert readings[0] < 300.0 and readings[3] == 1000.0
    ps0 = robot.getDevice("ps0")
    assert ps0.getLookupTable() == [0.0, 0.0, 0.0, 0.1, 1000.0, 0.0]
    assert (ps0.getMinValue(), ps0.getMaxValue()) == (0.0, 1000.0)


def test_an_e_puck_proto_keeps_its_proto_stable_text() -> None:
    text = ARENA + 'E-puck { translation 0.2 0 0 name "e-puck" controller "<extern>" }\n'
    scene = read_scene(text)
    assert scene.sensor_tables == {} and scene.malformed_tables == {}
    own = own_sensors("e-puck", scene)
    assert own.tables == {} and own.poses == {} and own.types == {}
    assert own.profile == RobotProfile.builtin("e-puck").with_infrared_elevation(0.16)


def test_an_empty_lookup_table_reads_0_as_webots_reads_through_no_table(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # WbDistanceSensor::computeValue: an empty table gives 0, whatever the ray meets (ps0 and
    # ps7 face the wall 2 cm ahead); not a refused table read through the profile's.
    text = plain_robot_world(PROXIMITY_TABLE)
    for name in ("ps0", "ps7"):
        text = text.replace(
            f'name "{name}" lookupTable [ {table_text(PROXIMITY_TABLE)} ]',
            f'name "{name}" lookupTable [ ]',
        )
    capsys.readouterr()
    readings, robot = front_readings(text)
    assert "lookupTable" not in capsys.readouterr().err
    assert readings[0] == readings[7] == 0.0
    assert 100.0 < readings[1] < 4095.0  # ps1 keeps its own table: the wall at 45 degrees
    ps0 = robot.getDevice("ps0")
    assert ps0.getLookupTable() == [] and ps0.getMaxValue() == 0.0
    assert robot.getDevice("ps1").getLookupTable() == [v for row in PROXIMITY_TABLE for v in row]


def test_an_empty_lookup_table_of_a_ground_sensor_reads_0() -> None:
    """The ground sensors of an expanded e-puck go through the same tables as its proximity
    sensors: gs1 with ``lookupTable []`` reads 0 over the arena's floor, gs0 and gs2 without one
    read through the node's default."""
    ground = "".join(
        f'    DistanceSensor {{ translation 0.03 {y} -0.011 rotation 0 1 0 1.5708 name "{name}"'
        f"{table} }}\n"
        for name, y, table in (
            ("gs0", 0.01, ""),
            ("gs1", 0.0, " lookupTable [ ]"),
            ("gs2", -0.01, ""),
        )
    )
    text = plain_robot_world(PROXIMITY_TABLE).replace(
        "  children [\n", "  children [\n" + ground, 1
    )
    _, robot = front_readings(text)
    sensors = [robot.getDevice(name) for name in ("gs0", "gs1", "gs2")]
    for sensor in sensors:
        sensor.enable(32)
    robot.step(32)
    assert sensors[1].getLookupTable() == [] and sensors[1].getValue() == 0.0
    assert sensors[0].getLookupTable() == [v for row in DEFAULT_LOOKUP_TABLE for v in row]
    assert sensors[0].getValue() > 0.0 and sensors[2].getValue() > 0.0


def test_a_lookup_table_not_of_rows_of_three_warns_naming_the_sensor(
    capsys: pytest.CaptureFixture[str],
) -> None:
    stock, _ = front_readings(plain_robot_world(PROXIMITY_TABLE))
    controller.Robot.created = None
    simulations.release()
    text = plain_robot_world(TEN_BIT)
    # ps3's and ps4's fields lose their last number.
    rows, field = table_text(TEN_BIT), "0 4095 0.002, 0.07 67"
    for name in ("ps3", "ps4"):
        text = text.replace(
            f'name "{name}" lookupTable [ {rows} ]', f'name "{name}" lookupTable [ {field} ]'
        )
    capsys.readouterr()
    readings, robot = front_readings(text)
    warnings = [line for line in capsys.readouterr().err.splitlines() if "lookupTable" in line]
    assert len(warnings) == 1
    (warning,) = warnings
    assert warning.startswith(
        "mazesim: warning: the world's lookupTable of DistanceSensor 'ps3', 'ps4' was not used"
    )
    assert warning.endswith(
        "read through the e-puck profile's table instead): expected rows of 3 numbers "
        "(distance, value, noise), found [0 4095 0.002, 0.07 67] (5 values)"
    )
    # Those two keep the built-in table; the others read through the world's.
    assert readings[3:5] == stock[3:5]
    assert robot.getDevice("ps3").getLookupTable() == [v for row in PROXIMITY_TABLE for v in row]
    assert robot.getDevice("ps0").getLookupTable() == [v for row in TEN_BIT for v in row]


def world_run_readings(
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    ten_bit: tuple[tuple[float, float, float], ...] | None,
    default: tuple[tuple[float, float, float], ...] | None,
) -> dict[str, dict[str, list[Any]]]:
    """Each robot's readings and tables in a world of three run in lockstep: plain ``Robot``
    e-pucks "ten" (its ps0..ps7 carrying ``ten_bit``) 2 cm from a wall and "default" (carrying
    ``default``) 4 cm from one, and a stock E-puck PROTO "proto" near the "default" one."""
    readings = probe_world_run(
        tmp_path,
        monkeypatch,
        ARENA
        + plain_robot(ten_bit, name="ten", controller_name="probe")
        + plain_robot(default, name="default", at=(-0.18, 0.1), controller_name="probe")
        + 'E-puck { translation -0.05 0.1 0 rotation 0 0 1 3.1416 name "proto" '
        'controller "probe" }\n',
    )
    return {name: readings[name] for name in RUN_ROBOTS}


RUN_ROBOTS = ("ten", "default", "proto")


def test_each_robot_of_a_world_run_reads_through_its_own_tables(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    stock = world_run_readings(tmp_path / "stock", monkeypatch, PROXIMITY_TABLE, PROXIMITY_TABLE)
    assert "lookupTable" not in capsys.readouterr().err
    own = world_run_readings(tmp_path / "own", monkeypatch, TEN_BIT, None)
    stock_rows = [v for row in PROXIMITY_TABLE for v in row]
    # The E-puck PROTO reads bit for bit as beside stock neighbours, through its PROTO's table.
    assert own["proto"] == stock["proto"]
    assert own["proto"]["tables"] == [stock_rows] * 8
    assert own["ten"]["tables"] == [[v for row in TEN_BIT for v in row]] * 8
    assert own["default"]["tables"] == [[0.0, 0.0, 0.0, 0.1, 1000.0, 0.0]] * 8
    inputs = [-row[1] for row in PROXIMITY_TABLE]
    for name, rows in (("ten", TEN_BIT), ("default", DEFAULT_LOOKUP_TABLE)):
        seen = [v for v in stock[name]["values"] if v > PROXIMITY_TABLE[-1][1] + 0.01]
        assert len(seen) >= 2, f"{name} sees a wall or a robot"
        for value, reading in zip(own[name]["values"], stock[name]["values"]):
            if reading > PROXIMITY_TABLE[-1][1] + 0.01:
                # Within the stock table's 7 cm: the same distance (over the reflectance of
                # what the ray meets) on the robot's own table.
                distance = np.interp(-reading, inputs, [row[0] for row in PROXIMITY_TABLE])
                expected = np.interp(distance, [r[0] for r in rows], [r[1] for r in rows])
                assert value == pytest.approx(expected, rel=2e-3, abs=0.05), name
    assert max(own["ten"]["values"]) <= 1023.0
    assert min(own["default"]["values"]) < 500.0 and max(own["default"]["values"]) == 1000.0


def test_a_world_run_warns_of_a_robot_s_table_it_does_not_use(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    readings = world_run_readings(tmp_path, monkeypatch, REFUSED, PROXIMITY_TABLE)
    warnings = [line for line in capsys.readouterr().err.splitlines() if "lookupTable" in line]
    (warning,) = warnings
    assert warning.startswith("mazesim: warning: robot 'ten': the world's lookupTable of ")
    assert warning.endswith("row 1 (0.01) is not above row 0 (0.02)")
    assert readings["ten"]["tables"] == [[v for row in PROXIMITY_TABLE for v in row]] * 8


def test_a_sensor_placed_elsewhere_casts_its_ray_from_where_the_world_puts_it() -> None:
    stock, _ = front_readings(plain_robot_world(PROXIMITY_TABLE))
    controller.Robot.created = None
    simulations.release()
    # ps2, on the right side, moved to ps7's place at the front, facing where ps7 faces.
    text = plain_robot_world(PROXIMITY_TABLE).replace(
        "translation 0.0 -0.031 0.033 rotation 0 0 1 -1.5708",
        "translation 0.03 0.01 0.033 rotation 0 0 1 0.2992",
    )
    moved, _ = front_readings(text)
    assert stock[2] < 100.0 < stock[7], "the side sensor saw no wall, the front one did"
    assert moved[2] == moved[7] == stock[7]
    assert [v for i, v in enumerate(moved) if i != 2] == [v for i, v in enumerate(stock) if i != 2]
    own = simulations.current().simulator.robot
    assert own.distance_sensor_poses()[2] == pytest.approx((0.03, 0.01, 0.2992))


def nue_sensors(moved: str | None = None) -> str:
    """ps0..ps7 of a Webots 6 e-puck (y up, forward -z), at the built-in poses rounded, or with
    sensor ``moved`` at ps7's."""
    lines = []
    for name, x, y, yaw in SENSORS:
        if name == moved:
            _, x, y, yaw = SENSORS[7]
        # Robot frame x forward, y left -> NUE: x right (-y), y up, z back (-x); a turn about
        # +z (up) becomes one about +y, the ray's x axis pointing forward needing a quarter turn.
        lines.append(
            f"    DistanceSensor {{ translation {-y} 0.033 {-x} rotation 0 1 0 "
            f'{yaw + 1.5707963267948966} name "{name}" }}\n'
        )
    return "".join(lines)


def test_a_webots_6_e_puck_s_sensor_poses_are_read_in_its_own_frame() -> None:
    def scene_of(sensors: str) -> Any:
        text = (
            "#VRML_SIM V6.4.0 utf8\nWorldInfo { basicTimeStep 32 }\n"
            "DifferentialWheels {\n  translation 0 0 0\n  children [\n"
            f'{sensors}  ]\n  name "e-puck"\n  controller "void"\n}}\n'
        )
        return read_scene(text, "DifferentialWheels", None)

    stock = own_sensors("e-puck", scene_of(nue_sensors()))
    assert stock.poses == {}
    moved = own_sensors("e-puck", scene_of(nue_sensors("ps2")))
    assert list(moved.poses) == ["ps2"]
    assert moved.poses["ps2"] == pytest.approx((0.03, 0.01, 0.3), abs=1e-9)
    assert moved.profile is not None
    assert moved.profile.distance_sensor_poses()[2] == pytest.approx((0.03, 0.01, 0.3))


def expanded_e_puck(turn_ps1: float = 0.0) -> str:
    """A plain ``Robot`` e-puck saved expanded as Webots' E-puck is: each DistanceSensor in a
    Solid at the sensor's place and heading, itself turned about the mount's z axis by 0.16
    (what raises its ray); ps1's Solid turned ``turn_ps1`` more. ps2 sits in a HingeJoint's
    end point, turned, whose pose is not composed."""
    sensors = []
    for name, x, y, yaw in SENSORS:
        heading = yaw + (turn_ps1 if name == "ps1" else 0.0)
        solid = f"Solid {{ translation {x} {y} 0.033 rotation 0 0 1 {heading}"
        sensor = (
            f'DistanceSensor {{ rotation 0 1 0 -0.16 name "{name}" '
            f"lookupTable [ {table_text(PROXIMITY_TABLE)} ] }}"
        )
        if name == "ps2":
            sensors.append(
                f"    HingeJoint {{ endPoint {solid} rotation 0 0 1 1 children [ {sensor} ] }} }}\n"
            )
        else:
            sensors.append(f"    {solid} children [ {sensor} ] }}\n")
    return ARENA + f'Robot {{\n  children [\n{"".join(sensors)}  ]\n  name "e-puck"\n}}\n'


def test_an_expanded_e_puck_s_sensor_poses_are_composed_through_its_solids() -> None:
    stock = read_scene(expanded_e_puck())
    assert "ps2" not in stock.sensor_poses
    assert stock.sensor_poses["ps0"] == pytest.approx((0.03, -0.01, -0.3, 0.16))
    # Where the E-puck's sensors sit: no pose of the world's own, only its rays' tilt.
    own = own_sensors("e-puck", stock)
    assert own.poses == {} and own.tables == {}
    assert own.elevations == pytest.approx({n: 0.16 for n, *_ in SENSORS if n != "ps2"})
    turned = own_sensors("e-puck", read_scene(expanded_e_puck(turn_ps1=0.5)))
    assert list(turned.poses) == ["ps1"]
    assert turned.poses["ps1"] == pytest.approx((0.022, -0.025, -0.3))


def test_the_e_puck2_tof_answers_with_the_table_it_reads_through() -> None:
    """The e-puck2's time-of-flight sensor reads through its own table (millimetres, up to
    2 m), and its lookup-table API answers with that table, not the proximity sensors'."""
    text = ARENA + 'E-puck { version "2" controller "void" }\n'
    world, report = import_wbt_text(text, "tof.wbt")
    assert report["robot_profile"] == "e-puck2"
    scene = read_scene(text, report.get("robot_model"), report.get("robot_line"))
    prepare(world, seconds=1.0, noise=False, report=report, scene=scene)
    robot = controller.Robot()
    tof, ps0 = robot.getDevice("tof"), robot.getDevice("ps0")
    assert tof.getLookupTable() == [v for row in TOF_TABLE for v in row]
    assert (tof.getMinValue(), tof.getMaxValue()) == (19.8, 2000.0)
    assert (tof.getMinRange(), tof.getMaxRange()) == (0.0, 2.0)
    assert tof.getType() == tof.GENERIC
    tof.enable(32)
    robot.step(32)
    # The wall ahead is 0.25 m from the centre, the sensor 0.034 m ahead of it: about 230 mm.
    assert 200.0 < tof.getValue() < 260.0
    assert ps0.getLookupTable() == [v for row in PROXIMITY_TABLE for v in row]
    assert ps0.getType() == ps0.INFRA_RED and ps0.getMaxValue() == 4095.0
