"""A Solid without a ``boundingObject`` in the proximity sensors' rays (a goal object the robot
drives through) is seen by the e-puck's infra-red sensors and camera, as in Webots, and met by
nothing else; a flat floor marker stays floor paint."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

import mazesim
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.camera import WALL_SHADE
from mazesim.webots.importer import import_summary, import_wbt
from mazesim.webots.scene import read_scene

HEADER = "#VRML_SIM R2023b utf8\n"
#: A red 5 cm tall box, 15 to 25 cm ahead of an e-puck at the origin, that nothing collides with.
RED_GOAL = (
    "Solid { translation 0.2 0 0.025 children [ Shape { appearance PBRAppearance { baseColor "
    '1 0 0 roughness 1 } geometry Box { size 0.1 0.3 0.05 } } ] name "goal" }\n'
)
#: The same box 5 cm ahead, in the front sensors' range.
NEAR_GOAL = RED_GOAL.replace("translation 0.2 0", "translation 0.1 0")
#: A flat red disc on the floor 10 cm behind the e-puck.
FLOOR_MARKER = (
    "Solid { translation -0.1 0 0.0005 children [ Shape { appearance PBRAppearance { baseColor "
    '1 0 0 } geometry Cylinder { radius 0.03 height 0.001 } } ] name "marker" }\n'
)


@pytest.fixture(autouse=True)
def release() -> Iterator[None]:
    yield
    controller.Robot.created = None
    simulations.release()


def first_step(tmp_path: Path, text: str) -> controller.Robot:
    """A controller's robot after its first step in a world file's ``text``, its camera and
    proximity sensors enabled."""
    world_file = tmp_path / "goal.wbt"
    world_file.write_text(HEADER + text)
    world, report = import_wbt(world_file)
    prepare(world, seconds=1.0, noise=False, report=report, scene=read_scene(HEADER + text))
    controller.Robot.created = None
    robot = controller.Robot()
    robot.getDevice("camera").enable(32)
    for i in range(8):
        robot.getDevice(f"ps{i}").enable(32)
    robot.step(32)
    return robot


def test_the_import_keeps_it_sensed_only_and_says_so(tmp_path: Path) -> None:
    world_file = tmp_path / "goal.wbt"
    world_file.write_text(HEADER + "E-puck { }\n" + RED_GOAL + FLOOR_MARKER)
    world, report = import_wbt(world_file)
    assert report["obstacles"] == []
    (goal,) = report["sensed_only"]
    assert goal["kind"] == "box" and goal["center"] == [0.2, 0.0] and goal["size"] == [0.1, 0.3]
    assert report["warnings"] == []
    assert world.wall_boxes().shape == (0, 6)
    assert world.sensed_wall_boxes().shape == (1, 6)
    assert world.sensed_wall_colours().tolist() == [[1.0, 0.0, 0.0]]
    # The report says the reflectance the world's sensed-only wall has.
    assert goal["reflectance"] == pytest.approx(float(world.sensed_wall_boxes()[0, 5]))
    assert len(world.paint_regions()) == 1  # the floor marker
    again = mazesim.World.from_toml(world.to_toml())
    assert again == world and "sensed_only = true" in world.to_toml()
    summary = import_summary(str(world_file), report, [])
    assert summary["sensed_only"] == 1
    assert "1 visual-only object(s) seen by the infra-red sensors" in summary["sentence"]


def test_the_camera_sees_it_red(tmp_path: Path) -> None:
    robot = first_step(tmp_path, "E-puck { }\n" + RED_GOAL)
    camera = robot.getDevice("camera")
    image, width, height = camera.getImage(), camera.getWidth(), camera.getHeight()
    x, y = width // 2, height // 2
    seen = (
        controller.Camera.imageGetRed(image, width, x, y),
        controller.Camera.imageGetGreen(image, width, x, y),
        controller.Camera.imageGetBlue(image, width, x, y),
    )
    assert seen == (round(255 * WALL_SHADE), 0, 0)


def test_the_front_infrared_sensors_read_it_as_the_same_box_with_a_bounding_object(
    tmp_path: Path,
) -> None:
    def front(text: str) -> list[float]:
        robot = first_step(tmp_path, "E-puck { }\n" + text)
        readings = [robot.getDevice(f"ps{i}").getValue() for i in (0, 7)]
        controller.Robot.created = None
        simulations.release()
        return readings

    seen = front(NEAR_GOAL)
    walled = front(
        NEAR_GOAL.replace('name "goal"', 'name "goal" boundingObject Box { size 0.1 0.3 0.05 }')
    )
    free = front(FLOOR_MARKER)
    assert seen == walled
    assert all(s > 2 * f for s, f in zip(seen, free)), (seen, free)
    assert np.all(np.isfinite(seen))


def test_a_generic_range_sensor_passes_through_it_as_webots_bounding_object_rays_do(
    tmp_path: Path,
) -> None:
    # Webots' reference manual (DistanceSensor): generic, sonar and laser rays collide with the
    # bounding objects of Solid nodes, infra-red rays with the Solid nodes themselves.
    def time_of_flight(text: str) -> float:
        robot = first_step(tmp_path, 'E-puck { version "2" }\n' + text)
        sensor = robot.getDevice("tof")
        sensor.enable(32)
        robot.step(32)
        reading = float(sensor.getValue())
        controller.Robot.created = None
        simulations.release()
        return reading

    open_floor = time_of_flight("")
    walled = time_of_flight(
        NEAR_GOAL.replace('name "goal"', 'name "goal" boundingObject Box { size 0.1 0.3 0.05 }')
    )
    assert time_of_flight(NEAR_GOAL) == open_floor
    assert walled < open_floor


def test_a_turret_lidar_measures_it_as_webots_renders_it(tmp_path: Path) -> None:
    """Webots' lidar measures depth from a rendering of the scene (reference manual, Lidar), so
    it sees the box the infra-red sensors see: the point straight ahead of a lidar on the turret
    (9.5 mm behind the e-puck's centre) is at the box's near face, 0.15 m ahead of the centre;
    with the box gone, the lidar sees nothing there. ``step(time_step=...)``, Webots' keyword
    since R2023a, is taken."""
    lidar = (
        "E-puck { turretSlot [ Lidar { horizontalResolution 8 fieldOfView 6.28318 "
        "numberOfLayers 1 maxRange 3 } ] }\n"
    )

    def ahead(text: str) -> float:
        robot = first_step(tmp_path, lidar + text)
        device = robot.getDevice("lidar")
        device.enable(32)
        robot.step(time_step=32)
        reading = float(device.getRangeImage()[4])
        controller.Robot.created = None
        simulations.release()
        return reading

    assert ahead(RED_GOAL) == pytest.approx(0.15 + 0.0095, abs=0.002)
    assert ahead("") == float("inf")
