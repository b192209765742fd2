"""Fields of an E-puck node that mount devices besides its ``turretSlot``: the slots a
project's own E-puck PROTO adds and numbers (``extensionSlot1``), whose devices the controller
finds as a slot's, and the PROTO's ``camera_recognition``, which gives the e-puck's own camera
a Recognition node."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.importer import import_wbt
from mazesim.webots.scene import read_scene

HEADER = "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\n"
RED_BOX = (
    'Solid { translation 0.3 0 0.025 name "red" model "red box" recognitionColors [ 1 0 0 ] '
    "children [ Shape { geometry DEF R Box { size 0.05 0.05 0.05 } } ] boundingObject USE R }\n"
)


@pytest.fixture(autouse=True)
def release() -> Iterator[None]:
    yield
    controller.Robot.created = None
    simulations.release()


def robot_of(tmp_path: Path, text: str) -> tuple[Any, dict[str, Any]]:
    """The robot of a world file's ``text`` and the world's import report."""
    world_file = tmp_path / "fields.wbt"
    world_file.write_text(text)
    world, report = import_wbt(world_file)
    prepare(world, seconds=2.0, noise=False, report=report, scene=read_scene(text))
    controller.Robot.created = None
    return controller.Robot(), report


def test_a_numbered_slot_of_a_projects_proto_mounts_its_gps(tmp_path: Path) -> None:
    text = (
        HEADER + 'E-puck { translation 0.1 0.2 0 controller "<extern>"\n'
        '  extensionSlot1 [ GPS { name "walker_gps" } ]\n'
        '  extensionSlot2 [ InertialUnit { name "walker_imu" } ]\n}\n'
    )
    robot, report = robot_of(tmp_path, text)
    slots = [(d["name"], d["slot"]) for d in report["extension_devices"]]
    assert slots == [("walker_gps", "extensionSlot1"), ("walker_imu", "extensionSlot2")]
    gps = robot.getDevice("walker_gps")
    assert gps is not None and robot.getDevice("walker_imu") is not None
    gps.enable(32)
    robot.step(32)
    x, y, _ = gps.getValues()
    assert (x, y) == pytest.approx((0.1, 0.2), abs=1e-3)


def test_a_field_not_named_as_a_slot_mounts_nothing(tmp_path: Path) -> None:
    text = HEADER + 'E-puck { controller "<extern>" spareNodes [ GPS { name "kept" } ] }\n'
    robot, report = robot_of(tmp_path, text)
    assert [d["name"] for d in report["extension_devices"]] == []
    assert robot.getDevice("kept") is None


def test_camera_recognition_gives_the_epucks_own_camera_a_recognition_node(
    tmp_path: Path,
) -> None:
    text = (
        HEADER + 'E-puck { controller "<extern>"\n'
        "  camera_recognition Recognition { maxRange 2 }\n}\n" + RED_BOX
    )
    robot, report = robot_of(tmp_path, text)
    (settings,) = report["recognition"]["cameras"]
    assert (settings["camera"], settings["max_range"]) == ("camera", 2.0)
    camera = robot.getDevice("camera")
    assert camera.hasRecognition()
    camera.enable(32)
    camera.recognitionEnable(32)
    robot.step(32)
    robot.step(32)
    (red,) = camera.getRecognitionObjects()
    assert red.getModel() == "red box"


def test_without_camera_recognition_the_epucks_camera_has_none(tmp_path: Path) -> None:
    robot, report = robot_of(tmp_path, HEADER + 'E-puck { controller "<extern>" }\n' + RED_BOX)
    assert report["recognition"]["cameras"] == []
    assert not robot.getDevice("camera").hasRecognition()
