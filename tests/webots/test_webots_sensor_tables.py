"""A plain ``Robot`` e-puck saved expanded with its own ``DistanceSensor`` nodes reads each
sensor through that node's ``lookupTable``, as Webots does: a 10-bit table reads 0..1023, the
stock table reads exactly as the built-in e-puck, and a table the profile format refuses keeps
the built-in one with a warning."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np
import pytest

from mazesim import RobotProfile, robot_profile_names
from mazesim._toml import load_toml
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.devices import PROXIMITY_TABLE
from mazesim.webots.importer import import_wbt_text
from mazesim.webots.scene import read_scene

#: The 10-bit proximity table of some course worlds (the e-puck's values scaled to 0..1023).
TEN_BIT = ((0.0, 1023.0, 0.0), (0.005, 868.0, 0.0), (0.01, 539.0, 0.0), (0.02, 169.0, 0.0))
TEN_BIT += ((0.03, 59.0, 0.0), (0.07, 17.0, 0.0))
#: Distances not increasing: the profile format refuses it.
REFUSED = ((0.02, 500.0, 0.0), (0.01, 1000.0, 0.0), (0.07, 10.0, 0.0))
#: The e-puck's proximity sensors: name, x, y, yaw (Webots' E-puck PROTO, rounded).
SENSORS = (
    ("ps0", 0.03, -0.01, -0.3),
    ("ps1", 0.022, -0.025, -0.8),
    ("ps2", 0.0, -0.031, -1.5708),
    ("ps3", -0.03, -0.015, -2.644),
    ("ps4", -0.03, 0.015, 2.639),
    ("ps5", 0.0, 0.031, 1.5708),
    ("ps6", 0.022, 0.025, 0.8),
    ("ps7", 0.03, 0.01, 0.3),
)


def _table(rows: tuple[tuple[float, float, float], ...]) -> str:
    return ", ".join(" ".join(repr(v) for v in row) for row in rows)


def plain_robot_world(rows: tuple[tuple[float, float, float], ...]) -> str:
    """A plain ``Robot`` e-puck whose ps0..ps7 carry ``rows``, 2 cm from a wall ahead (+x)."""
    sensors = "".join(
        f'    DistanceSensor {{ translation {x} {y} 0.033 rotation 0 0 1 {yaw} name "{name}"'
        f" lookupTable [ {_table(rows)} ] }}\n"
        for name, x, y, yaw in SENSORS
    )
    return (
        "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\n"
        "RectangleArena { floorSize 0.5 0.5 }\n"
        "Robot {\n  translation 0.203 0 0\n  children [\n"
        f"{sensors}"
        '    HingeJoint { device [ RotationalMotor { name "left wheel motor" } ] '
        "endPoint Solid { translation 0 0.026 0.02 } }\n"
        '    HingeJoint { device [ RotationalMotor { name "right wheel motor" } ] '
        "endPoint Solid { translation 0 -0.026 0.02 } }\n"
        '  ]\n  name "e-puck"\n  controller "<extern>"\n}\n'
    )


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
    again = simulations._profile_with_tables(load_toml(text, name), {})
    assert again.to_toml() == text


def test_a_webots_6_differential_wheels_e_puck_s_tables_are_read() -> None:
    text = plain_robot_world(TEN_BIT).replace("Robot {", "DifferentialWheels {")
    text = text.replace("#VRML_SIM R2023b", "#VRML_SIM V6.4.0")
    _, report = import_wbt_text(text, "old.wbt")
    scene = read_scene(text, report.get("robot_model"), report.get("robot_line"))
    assert scene.robot_name == "e-puck"
    assert scene.sensor_tables["ps0"] == list(TEN_BIT)
    assert set(simulations.world_sensor_tables(report, scene)[0]) == {n for n, *_ in SENSORS}
