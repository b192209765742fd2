"""A road of visual-only slabs under the proximity rays (1.6 cm thick, lane marks on them, as a
camera lane follower's world builds it) is seen by the e-puck's camera and its ground sensors,
and the robot drives through it as in Webots (#32)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from supervised_world import drive, supervisor_in

#: A dark road 1.6 cm thick ahead of the e-puck, a yellow lane mark 1 cm wide lying on it.
ROAD = (
    "Pose { translation 0.7 0 0.008 children [ Shape { appearance PBRAppearance { "
    "baseColor 0.14 0.15 0.17 } geometry Box { size 1.2 0.5 0.016 } } ] }\n"
    "Pose { translation 0.7 0 0.017 children [ Shape { appearance PBRAppearance { "
    "baseColor 1 1 0 } geometry Box { size 1.2 0.01 0.002 } } ] }\n"
)


def _world(road: bool) -> str:
    return (
        "#VRML_SIM R2025a utf8\nWorldInfo { basicTimeStep 32 }\nRectangleArena { floorSize 3 3 }\n"
        + (ROAD if road else "")
        + 'E-puck { translation 0 0 0 controller "<extern>" supervisor TRUE groundSensorsSlot [ '
        + "E-puckGroundSensors { } ] }\n"
    )


def _pixel(camera: Any, x: int, y: int) -> tuple[int, int, int]:
    image: Any = camera.getImage()
    i = 4 * (y * camera.getWidth() + x)
    return (image[i + 2], image[i + 1], image[i])


@pytest.mark.parametrize("road", [False, True])
def test_the_camera_sees_a_raised_road_and_its_lane_mark(tmp_path: Path, road: bool) -> None:
    robot = supervisor_in(tmp_path, _world(road))
    camera = robot.getDevice("camera")
    camera.enable(32)
    robot.step(32)
    width, bottom = camera.getWidth(), camera.getHeight() - 1
    middle, aside = _pixel(camera, width // 2, bottom), _pixel(camera, width // 4, bottom)
    if road:
        assert middle == (255, 255, 0)  # the lane mark ahead
        assert max(aside) < 60  # the dark road beside it
    else:
        assert middle == aside == (255, 255, 255)  # the bare floor


def test_the_robot_drives_onto_the_road_and_its_ground_sensors_read_it(tmp_path: Path) -> None:
    robot = supervisor_in(tmp_path, _world(True))
    sensors = [robot.getDevice(f"gs{i}") for i in range(3)]
    for sensor in sensors:
        sensor.enable(32)
    robot.step(32)
    on_floor = [sensor.getValue() for sensor in sensors]
    drive(robot, 6.0, 40)  # 0.15 m: onto the road, nothing in the way
    on_road = [sensor.getValue() for sensor in sensors]
    assert robot.getSelf().getPosition()[0] > 0.14
    assert all(before > 700 for before in on_floor), on_floor
    assert on_road[1] > 700 > max(on_road[0], on_road[2]), on_road  # the lane under gs1
