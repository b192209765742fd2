"""A LightSensor, Accelerometer or Gyro the world adds without a ``lookupTable`` reads through
its node's default table (Webots' reference manual: a LightSensor's ``[0 0 0, 1 1000 0]``, an
Accelerometer's and a Gyro's empty table, the raw value without noise), not through the E-puck
PROTO's tables for its own ls0-ls7, accelerometer and gyro (``[1 4095 0.01, 2 0 0.01]``,
``[-100 -100 0.003, 100 100 0.003]``, ``[-13.3 -100000 0.003, 13.3 100000 0.003]``), which made
a turret light sensor read 4095 in the dark and fall as the light grew. An empty ``lookupTable []``
is no table, not the default one.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from supervised_world import supervisor_in


def _world(devices: str, light: str = "") -> str:
    return (
        "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 16 }\n"
        f"{light}"
        f'E-puck {{ supervisor TRUE controller "<extern>" turretSlot [ {devices} ] }}\n'
    )


@pytest.mark.usefixtures("fresh_robot")
@pytest.mark.parametrize(("intensity", "reads"), [(0.0, 0.0), (0.25, 250.0), (0.5, 500.0)])
def test_a_light_sensor_without_a_table_reads_through_the_node_s_default_one(
    tmp_path: Path, intensity: float, reads: float
) -> None:
    # A point light 0.4 m ahead of the sensor, level with it, no attenuation: the irradiance
    # is its intensity, which the default table reads times 1000.
    light = f"PointLight {{ location 0.4 0 0.05 intensity {intensity} attenuation 1 0 0 }}\n"
    robot = supervisor_in(tmp_path, _world('LightSensor { name "eye" }', light), noise=True)
    eye = robot.getDevice("eye")
    eye.enable(16)
    robot.step(16)
    assert eye.getLookupTable() == [0.0, 0.0, 0.0, 1.0, 1000.0, 0.0]
    assert eye.getValue() == pytest.approx(reads, abs=30.0)


@pytest.mark.usefixtures("fresh_robot")
def test_an_accelerometer_and_a_gyro_without_a_table_read_raw_values(tmp_path: Path) -> None:
    devices = 'Accelerometer { name "acc" } Gyro { name "turret gyro" }'
    robot = supervisor_in(tmp_path, _world(devices), noise=True)
    accelerometer, gyro = robot.getDevice("acc"), robot.getDevice("turret gyro")
    accelerometer.enable(16)
    gyro.enable(16)
    robot.step(16)
    assert accelerometer.getLookupTable() == [] and gyro.getLookupTable() == []
    x, y, z = accelerometer.getValues()
    # At rest on the floor: gravity alone, without the 0.3 % noise of the PROTO's table.
    assert (x, y) == pytest.approx((0.0, 0.0), abs=1e-9)
    assert z == pytest.approx(9.81, abs=1e-6)
    assert gyro.getValues() == pytest.approx([0.0, 0.0, 0.0], abs=1e-9)


@pytest.mark.usefixtures("fresh_robot")
def test_an_empty_table_is_no_table_not_the_default_one(tmp_path: Path) -> None:
    # Webots' lookup of an empty table gives its input back (WbLookupTable::lookup): a
    # LightSensor with `lookupTable []` reads the raw irradiance; a DistanceSensor with one
    # reads 0 (WbDistanceSensor::computeValue), where one without the field reads through
    # the node default [0 0 0, 0.1 1000 0] (1000 with nothing ahead).
    light = "PointLight { location 0.4 0 0.05 intensity 0.25 attenuation 1 0 0 }\n"
    devices = (
        'LightSensor { name "raw eye" lookupTable [] } '
        'DistanceSensor { name "no table" lookupTable [] } '
        'DistanceSensor { name "default table" }'
    )
    robot = supervisor_in(tmp_path, _world(devices, light), noise=True)
    eye, empty, plain = (robot.getDevice(n) for n in ("raw eye", "no table", "default table"))
    for device in (eye, empty, plain):
        device.enable(16)
    robot.step(16)
    assert eye.getLookupTable() == [] and empty.getLookupTable() == []
    assert eye.getValue() == pytest.approx(0.25, abs=0.01)
    assert empty.getValue() == 0.0 and empty.getMaxValue() == 0.0
    assert plain.getValue() == pytest.approx(1000.0)
