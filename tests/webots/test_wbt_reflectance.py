"""An imported wall reflects infra-red by its appearance, as in Webots: its proximity readings are
``LUT(d / f)`` with ``f = 0.2 + 0.8 * red * (1 - 0.5 * roughness)`` (red times ``1 - transparency``;
Webots' reference manual, DistanceSensor; docs/webots.md), and the import's report and world file
carry that ``f``."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import mazesim
from mazesim.webots import import_wbt_text
from mazesim.webots.devices import PROXIMITY_TABLE
from mazesim.webots.rays import WallBoxes
from mazesim.webots.sensors import DeviceMount, LookupTable

PROFILE = mazesim.RobotProfile.builtin("e-puck")


def wall_ahead(appearance: str) -> str:
    """An e-puck at the origin facing +x, a 2 cm thick wall whose face is 5 cm ahead."""
    return (
        "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\nE-puck { }\n"
        "Solid { translation 0.06 0 0.05 children [ Shape { "
        f"appearance {appearance} geometry Box {{ size 0.02 0.3 0.1 }} }} ] "
        "boundingObject Box { size 0.02 0.3 0.1 } }\n"
    )


def front_readings(world: mazesim.World, reflectance: float) -> tuple[np.ndarray, np.ndarray]:
    """ps0 and ps7 as the core reads them, and as the E-puck's table reads each ray's distance
    to the wall over ``reflectance``."""
    simulator = mazesim.Simulator(world, robot="e-puck", noise=False)
    readings = simulator.distance_sensors()[[0, 7]]
    table, walls = LookupTable(PROXIMITY_TABLE), WallBoxes(world)
    expected = []
    for index in (0, 7):
        x, y, heading = PROFILE.distance_sensor_poses()[index]
        sx, sy, direction = DeviceMount((x, y, 0.0), heading).world_pose(simulator.pose)
        ray = np.array([[math.cos(direction), math.sin(direction)]])
        distance, _ = walls.cast((sx, sy), ray)
        expected.append(table(min(float(distance[0]) / reflectance, 0.07), None))
    return readings, np.array(expected)


def test_a_grey_rough_wall_reads_as_webots_reads_it_farther_than_a_white_one() -> None:
    # red 0.5, roughness 1: f = 0.2 + 0.8 * 0.5 * 0.5 = 0.4.
    world, report = import_wbt_text(
        wall_ahead("PBRAppearance { baseColor 0.5 0.5 0.5 roughness 1 }")
    )
    assert [o["reflectance"] for o in report["obstacles"]] == [pytest.approx(0.4)]
    readings, expected = front_readings(world, 0.4)
    assert readings == pytest.approx(expected, rel=0.02, abs=1.0)
    _, white = front_readings(world, 1.0)
    assert np.all(readings < white - 100.0), (readings, white)


def test_a_red_smooth_wall_reads_as_a_white_one() -> None:
    world, report = import_wbt_text(wall_ahead("PBRAppearance { baseColor 1 0 0 }"))
    assert [o["reflectance"] for o in report["obstacles"]] == [1.0]
    readings, expected = front_readings(world, 1.0)
    assert readings == pytest.approx(expected, rel=0.02, abs=1.0)


def test_the_world_file_keeps_the_reflectance_and_the_colour(tmp_path: Path) -> None:
    world, _ = import_wbt_text(
        wall_ahead("Appearance { material Material { diffuseColor 0.5 0 0 transparency 0.5 } }")
    )
    path = tmp_path / "grey.toml"
    world.save(path)
    again = mazesim.load_world(path)
    assert "reflectance = 0.4" in path.read_text()
    assert np.array_equal(again.wall_colours(), [[0.5, 0.0, 0.0]])
    first, _ = front_readings(world, 0.4)
    second, _ = front_readings(again, 0.4)
    assert np.array_equal(first, second)
