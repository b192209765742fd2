"""A camera with a Recognition node recognises the world's Solids with recognitionColors: those
in its field of view and range, not hidden behind walls, with their model, colours, position
in the camera's frame and place on the image, as Webots' camera recognition gives them."""

from __future__ import annotations

import json
import math
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from mazesim import World
from mazesim.webots import controller, prepare, run_controller
from mazesim.webots import simulation as simulations
from mazesim.webots.importer import import_wbt
from mazesim.webots.lockstep import run_world
from mazesim.webots.rays import WallBoxes
from mazesim.webots.recognition import CameraPose, Recogniser, read_recognition
from mazesim.webots.scene import read_scene
from native_controllers import NEEDS_COMPILERS, write_source

HEADER = "#VRML_SIM R2023b utf8\n"
SWARM = Path(__file__).resolve().parent.parent / "data" / "webots-swarm"


def world_text(occlusion: str = "", max_objects: str = "") -> str:
    """An e-puck at the origin facing +x whose turret camera ``rec`` has a Recognition node;
    a red box 0.3 m ahead and a little left, a green one 0.6 m ahead and right behind a
    wall, a blue one beside the robot, out of the field of view."""
    return (
        HEADER
        + "WorldInfo { basicTimeStep 32 }\n"
        + 'E-puck {\n  controller "<extern>"\n  turretSlot [\n'
        # 3 cm ahead of the centre and 2.8 cm up: the turret slot is 9.5 mm back, 48.6 mm up.
        + '    Camera { translation 0.0395 0 -0.0206 name "rec" width 52 height 39 '
        + f"fieldOfView 0.84 recognition Recognition {{ {occlusion} {max_objects} }} }}\n"
        + "  ]\n}\n"
        + 'Solid { translation 0.3 0.05 0.025 name "red" model "red box" '
        + "recognitionColors [ 1 0 0 ] children [ Shape { geometry DEF R Box "
        + "{ size 0.05 0.05 0.05 } } ] boundingObject USE R }\n"
        + 'Solid { translation 0.6 -0.15 0.025 name "green" model "green box" '
        + "recognitionColors [ 0 1 0, 0 0.5 0 ] boundingObject Box { size 0.05 0.05 0.05 } }\n"
        + 'Solid { translation 0.45 -0.1 0.05 name "wall" '
        + "boundingObject Box { size 0.02 0.1 0.1 } }\n"
        + 'Solid { translation 0 0.4 0.025 name "blue" model "blue box" '
        + "recognitionColors [ 0 0 1 ] boundingObject Box { size 0.05 0.05 0.05 } }\n"
    )


#: The Recognition node of the robot on line 1's camera, without occlusion.
SETTINGS: Any = {
    "robot_line": 1,
    "camera": "camera",
    "max_range": 100.0,
    "max_objects": -1,
    "occlusion": 0,
    "frame_color": [1.0, 0.0, 0.0],
    "frame_thickness": 1,
    "segmentation": False,
}


@pytest.fixture(autouse=True)
def release() -> Iterator[None]:
    yield
    controller.Robot.created = None
    simulations.release()


def camera_of(tmp_path: Path, text: str, supervisor: bool = False) -> tuple[Any, Any]:
    """The robot (a ``Supervisor`` when asked) and its ``rec`` camera of a world file's
    ``text``."""
    world_file = tmp_path / "recognition.wbt"
    world_file.write_text(text)
    world, report = import_wbt(world_file)
    prepare(world, seconds=2.0, noise=False, report=report, scene=read_scene(text))
    controller.Robot.created = None
    robot = controller.Supervisor() if supervisor else controller.Robot()
    return robot, robot.getDevice("rec")


def test_the_import_keeps_the_recognition_node_and_the_objects_with_colours(
    tmp_path: Path,
) -> None:
    world_file = tmp_path / "recognition.wbt"
    world_file.write_text(world_text("maxRange 2 occlusion 0", "maxObjects 3"))
    _, report = import_wbt(world_file)
    (camera,) = report["recognition"]["cameras"]
    assert (camera["camera"], camera["robot_line"]) == ("rec", 3)
    assert (camera["max_range"], camera["max_objects"], camera["occlusion"]) == (2.0, 3, 0)
    assert not camera["segmentation"]
    objects = report["recognition"]["objects"]
    assert [o["model"] for o in objects] == ["red box", "green box", "blue box"]
    assert objects[1]["colors"] == [0.0, 1.0, 0.0, 0.0, 0.5, 0.0]
    assert objects[0]["origin"] == pytest.approx([0.3, 0.05, 0.025])
    assert objects[0]["box_size"] == pytest.approx([0.05, 0.05, 0.05])
    # Their ids are their places among the file's top-level nodes, as a supervisor's.
    assert [o["id"] for o in objects] == [3, 4, 6]


def test_the_camera_recognises_the_box_in_view_not_the_hidden_or_the_outside_one(
    tmp_path: Path,
) -> None:
    robot, camera = camera_of(tmp_path, world_text())
    assert camera.hasRecognition()
    assert not robot.getDevice("camera").hasRecognition()  # the e-puck's own camera has none
    camera.recognitionEnable(64)
    assert camera.getRecognitionSamplingPeriod() == 64
    robot.step(32)
    assert camera.getRecognitionNumberOfObjects() == 0  # the first period has not ended
    robot.step(32)
    assert camera.getRecognitionNumberOfObjects() == 1
    (red,) = camera.getRecognitionObjects()
    assert red.getModel() == "red box"
    assert red.getColors() == [1.0, 0.0, 0.0] and red.getNumberOfColors() == 1
    assert red.getId() == 3
    # x forward, y left, z up (Webots' camera frame since R2022a): ahead, left, a little down.
    x, y, z = red.getPosition()
    assert x == pytest.approx(0.27, abs=0.01)
    assert y == pytest.approx(0.05, abs=0.01)
    assert z < 0.0
    assert red.getSize() == pytest.approx([0.05, 0.05], abs=0.01)
    u, v = red.getPositionOnImage()
    width, height = red.getSizeOnImage()
    # Left of the image's centre, by the planar projection of its centre.
    focal = 51 * 0.5 / math.tan(0.42)
    assert u == pytest.approx(25.5 - focal * 0.05 / 0.27, abs=2.0)
    assert u < 25 and 17 <= v <= 22
    assert 8 <= width <= 12 and 8 <= height <= 12


def test_a_recognised_object_answers_the_spelling_of_webots_before_r2023a(
    tmp_path: Path,
) -> None:
    # Webots' SWIG-made Python module (up to R2022b) spells the getters get_position_on_image,
    # get_colors...: a controller of that time reads the box with them. Its get_model gives
    # bytes and its get_size ints (resources/languages/python/controller.i).
    robot, camera = camera_of(tmp_path, world_text())
    camera.recognitionEnable(32)
    robot.step(32)
    (red,) = camera.getRecognitionObjects()
    assert red.get_colors() == [1.0, 0.0, 0.0] and red.get_number_of_colors() == 1
    assert red.get_model() == b"red box" and red.get_id() == red.getId() == 3
    assert red.get_position() == red.getPosition()
    assert red.get_orientation() == red.getOrientation()
    assert red.get_size() == [int(v) for v in red.getSize()] == [0, 0]
    assert red.get_position_on_image() == red.getPositionOnImage()
    assert red.get_size_on_image() == red.getSizeOnImage()


def test_without_occlusion_the_box_behind_the_wall_is_recognised_too(tmp_path: Path) -> None:
    robot, camera = camera_of(tmp_path, world_text("occlusion 0"))
    camera.recognitionEnable(32)
    robot.step(32)
    objects = camera.getRecognitionObjects()
    assert [o.getModel() for o in objects] == ["red box", "green box"]
    green = objects[1]
    assert green.getPosition()[1] < 0.0  # to the right
    assert green.getPositionOnImage()[0] > 26
    assert green.getNumberOfColors() == 2


def test_max_objects_keeps_the_biggest_on_the_image_and_max_range_the_near_ones(
    tmp_path: Path,
) -> None:
    robot, camera = camera_of(tmp_path, world_text("occlusion 0", "maxObjects 1"))
    camera.recognitionEnable(32)
    robot.step(32)
    assert [o.getModel() for o in camera.getRecognitionObjects()] == ["red box"]
    controller.Robot.created = None
    simulations.release()
    robot, camera = camera_of(tmp_path, world_text("occlusion 0 maxRange 0.4"))
    camera.recognitionEnable(32)
    robot.step(32)
    assert [o.getModel() for o in camera.getRecognitionObjects()] == ["red box"]


def test_recognition_functions_say_webots_errors_when_disabled_or_missing(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    robot, camera = camera_of(tmp_path, world_text())
    assert camera.getRecognitionNumberOfObjects() == 0
    assert "wb_camera_recognition_get_number_of_objects() called for a disabled device" in (
        capsys.readouterr().err
    )
    camera.recognitionEnable(32)
    robot.step(32)
    camera.recognitionDisable()
    assert camera.getRecognitionSamplingPeriod() == 0
    robot.getDevice("camera").recognitionEnable(32)
    assert "called on a Camera without Recognition node" in capsys.readouterr().err


def green_target(line: int, node_id: int, origin: list[float], size: list[float]) -> Any:
    """A recognisable green object "cible" on ``line``, its box of ``size`` at ``origin``."""
    return {
        "line": line,
        "id": node_id,
        "model": "cible",
        "colors": [0.0, 1.0, 0.0],
        "origin": origin,
        "yaw": 0.0,
        "box_center": [0.0, 0.0, 0.0],
        "box_size": size,
        "round": False,
    }


def test_a_recognised_robot_follows_its_live_pose() -> None:
    target = green_target(9, 2, [5.0, 5.0, 0.0], [0.1, 0.2, 0.1])
    report = {"robots": [{"line": 1}, {"line": 9}]}
    recogniser = Recogniser(SETTINGS, [target], report)
    assert recogniser.follows_robots
    camera = CameraPose(0.0, 0.0, 0.028, 0.0, 0.0, 52, 39, 0.84)
    assert recogniser.recognise(camera, None) == []  # where the import put it: behind
    (seen,) = recogniser.recognise(camera, None, [(0.0, 0.0, 0.0), (0.5, -0.05, math.pi / 2)])
    assert seen.position == pytest.approx((0.5, -0.05, -0.028))
    # Turned a quarter: its 0.2 m side across the camera's x axis, its 0.1 m side across y.
    assert seen.size == pytest.approx((0.1, 0.1))
    assert seen.orientation == pytest.approx((0.0, 0.0, 1.0, math.pi / 2))
    # Before R2022a: x right, y up, z backward.
    old = Recogniser(SETTINGS, [target], report, old_frame=True)
    (seen,) = old.recognise(camera, None, [(0.0, 0.0, 0.0), (0.5, -0.05, 0.0)])
    assert seen.position == pytest.approx((0.05, -0.028, -0.5))


RECOGNITION_BODY = """
  WbDeviceTag camera = wb_robot_get_device("rec");
  wb_camera_recognition_enable(camera, 32);
  wb_robot_step(32);
  const WbCameraRecognitionObject *o = wb_camera_recognition_get_objects(camera);
  printf("has %d objects %d model %s left %d colours %d\\n", wb_camera_has_recognition(camera),
         wb_camera_recognition_get_number_of_objects(camera), o[0].model,
         o[0].position[1] > 0.0, o[0].number_of_colors);
"""


@NEEDS_COMPILERS
@pytest.mark.usefixtures("own_cache")
def test_a_c_controller_reads_what_the_camera_recognises(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    source = write_source(
        tmp_path,
        "recogniser",
        "#include <stdio.h>\n#include <webots/robot.h>\n#include <webots/camera.h>\n"
        "#include <webots/camera_recognition_object.h>\n"
        f"int main(void) {{\n  wb_robot_init();\n{RECOGNITION_BODY}\n  wb_robot_cleanup();\n"
        "  return 0;\n}\n",
    )
    text = world_text()
    world_file = tmp_path / "recognition.wbt"
    world_file.write_text(text)
    world, report = import_wbt(world_file)
    run = run_controller(
        source, world, seconds=0.5, noise=False, report=dict(report), scene=read_scene(text)
    )
    assert (run.exit_status, run.error) == (0, "")
    assert (
        capfd.readouterr().out.splitlines()[-1] == "has 1 objects 1 model red box left 1 colours 1"
    )


def test_an_object_across_the_edge_of_the_view_is_recognised_clipped_to_it() -> None:
    # Its centre 5 cm left of the field of view at 0.3 m ahead, its near half inside it.
    edge = 0.3 * math.tan(0.42)
    wide: Any = {
        "line": 5,
        "id": 4,
        "model": "wide",
        "colors": [1.0, 1.0, 0.0],
        "origin": [0.3, edge + 0.05, 0.0],
        "yaw": 0.0,
        "box_center": [0.0, 0.0, 0.0],
        "box_size": [0.02, 0.2, 0.02],
        "round": False,
    }
    camera = CameraPose(0.0, 0.0, 0.0, 0.0, 0.0, 52, 39, 0.84)
    (seen,) = Recogniser(SETTINGS, [wide], {}).recognise(camera, None)
    left = seen.position[1] + seen.size[0] / 2.0
    assert left == pytest.approx(0.31 * math.tan(0.42), abs=1e-9)  # clipped at the edge
    assert seen.size[0] < 0.2
    assert seen.position_on_image[0] < 26 and seen.size_on_image[0] < 26
    wide["origin"] = [0.3, edge + 0.15, 0.0]  # wholly outside
    assert Recogniser(SETTINGS, [wide], {}).recognise(camera, None) == []


def tall_cylinder(x: float, y: float, rounded: bool = True) -> Any:
    """A 0.3 m tall cylinder of radius 0.05 standing at (x, y) (its box 0.1 x 0.1 x 0.3, its
    centre 0.15 m up), or (``rounded`` False) a box of that size."""
    return {
        "line": 5,
        "id": 4,
        "model": "pillar",
        "colors": [1.0, 0.0, 1.0],
        "origin": [x, y, 0.0],
        "yaw": 0.0,
        "box_center": [0.0, 0.0, 0.15],
        "box_size": [0.1, 0.1, 0.3],
        "round": rounded,
    }


def test_a_round_object_partly_out_of_view_is_measured_from_its_centre_as_webots_does() -> None:
    # Webots (WbObjectDetection::isWithinBounds, its Sphere/Cylinder/Capsule branch): the
    # centre's distance d to each side of the field of view against half the width or height;
    # the part beyond, half - d, comes off the size and half of it off the position.
    camera = CameraPose(0.0, 0.0, 0.028, 0.0, 0.0, 52, 39, 0.84)
    up = math.tan(0.42) * 39 / 52
    # 0.131 m ahead its centre is 0.122 m above the camera: d = (up * 0.131 - 0.122) /
    # sqrt(1 + up^2) = -0.0741 from the top side, 0.1573 (more than 0.15) from the bottom one.
    (seen,) = Recogniser(SETTINGS, [tall_cylinder(0.131, 0.0)], {}).recognise(camera, None)
    top = 0.15 - (up * 0.131 - 0.122) / math.sqrt(1.0 + up * up)
    assert seen.position == pytest.approx((0.131, 0.0, 0.122 - top / 2.0), abs=1e-12)
    assert seen.position[2] == pytest.approx(0.00996, abs=1e-5)  # the course lab's stop, 0.01
    assert seen.size == pytest.approx((0.1, 0.3 - top), abs=1e-12)
    # A box of that size is clipped at its corners instead: higher, as mazesim had the cylinder.
    (boxed,) = Recogniser(SETTINGS, [tall_cylinder(0.131, 0.0, False)], {}).recognise(camera, None)
    assert boxed.position[2] == pytest.approx(0.01631, abs=1e-5)
    # Its centre beyond the left side by more than half its width: out of view, where a box's
    # near corners still lie across the view.
    across = math.tan(0.42)
    beyond = (across * 0.131 - 0.12) / math.sqrt(1.0 + across * across)
    assert beyond < -0.05
    assert Recogniser(SETTINGS, [tall_cylinder(0.131, 0.12)], {}).recognise(camera, None) == []
    assert Recogniser(SETTINGS, [tall_cylinder(0.131, 0.12, False)], {}).recognise(camera, None)


def test_a_world_before_r2022a_gives_positions_in_the_old_camera_frame(tmp_path: Path) -> None:
    # y up, the e-puck facing -z: a box 0.3 m ahead, another 0.3 m to its right (out of view).
    text = (
        "#VRML_SIM R2021a utf8\nWorldInfo { basicTimeStep 32 }\n"
        'E-puck { controller "<extern>" turretSlot [ Camera { name "rec" width 52 height 39 '
        "fieldOfView 0.84 recognition Recognition { occlusion TRUE } } ] }\n"
        'Solid { translation 0 0.025 -0.3 model "ahead" recognitionColors [ 1 0 0 ] '
        "boundingObject Box { size 0.05 0.05 0.05 } }\n"
        'Solid { translation 0.3 0.025 0 model "right" recognitionColors [ 1 0 0 ] '
        "boundingObject Box { size 0.05 0.05 0.05 } }\n"
    )
    robot, camera = camera_of(tmp_path, text)
    camera.recognitionEnable(32)
    robot.step(32)
    (ahead,) = camera.getRecognitionObjects()
    assert ahead.getModel() == "ahead"
    # x right, y up, z backward: straight ahead is a negative z. The camera sits where the
    # turret slot is, 9.5 mm behind the centre and 48.6 mm up.
    assert ahead.getPosition() == pytest.approx([0.0, 0.025 - 0.0486, -0.3095])
    assert ahead.getOrientation()[3] == pytest.approx(0.0)  # turned as the robot is
    assert ahead.getPositionOnImage()[0] in (25, 26)


def test_the_camera_does_not_recognise_a_part_of_its_own_robot(tmp_path: Path) -> None:
    # A flag with recognitionColors on the e-puck's turret, 10 cm ahead of its camera.
    flag = (
        'Solid { translation 0.13 0 0.03 name "flag" model "own flag" recognitionColors '
        "[ 1 1 0 ] boundingObject Box { size 0.02 0.02 0.02 } }\n"
    )
    text = world_text().replace("  ]\n}\n", f"    {flag}  ]\n}}\n", 1)
    robot, camera = camera_of(tmp_path, text)
    camera.recognitionEnable(32)
    robot.step(32)
    assert [o.getModel() for o in camera.getRecognitionObjects()] == ["red box"]


@pytest.mark.parametrize(
    ("written", "objects", "thickness"),
    [("1e999", -1, 1), ("-1e999", -1, 1), ("99999999999999999999", 2**31 - 1, 2**31 - 1)],
)
def test_a_recognition_count_out_of_range_keeps_a_whole_number(
    written: str, objects: int, thickness: int
) -> None:
    text = (
        "#VRML_SIM R2023b utf8\nRobot { children [ Camera { recognition Recognition { "
        f"maxObjects {written} frameThickness {written} }} }} ] }}\n"
    )
    camera = read_recognition(text)["cameras"][0]
    assert (camera["max_objects"], camera["frame_thickness"]) == (objects, thickness)


def supervised_camera(tmp_path: Path) -> tuple[Any, Any]:
    """The supervisor and ``rec`` camera of :func:`world_text`'s e-puck, the red box ``RED``
    and the wall ``WALL``."""
    text = (
        world_text()
        .replace("E-puck {\n  controller", "E-puck {\n  supervisor TRUE controller")
        .replace("Solid { translation 0.3 0.05", "DEF RED Solid { translation 0.3 0.05")
        .replace("Solid { translation 0.45 -0.1", "DEF WALL Solid { translation 0.45 -0.1")
    )
    return camera_of(tmp_path, text, supervisor=True)


def test_a_solid_a_supervisor_moves_is_recognised_where_it_is_now(tmp_path: Path) -> None:
    supervisor, camera = supervised_camera(tmp_path)
    camera.recognitionEnable(32)
    supervisor.getFromDef("RED").getField("translation").setSFVec3f([0.35, -0.04, 0.025])
    supervisor.step(32)
    (red,) = camera.getRecognitionObjects()
    x, y, _ = red.getPosition()
    assert x == pytest.approx(0.32, abs=0.01) and y == pytest.approx(-0.04, abs=0.01)
    # The wall that hid the green box moved away: the camera sees it now.
    supervisor.getFromDef("WALL").getField("translation").setSFVec3f([0.45, 0.5, 0.05])
    supervisor.step(32)
    assert [o.getModel() for o in camera.getRecognitionObjects()] == ["red box", "green box"]
    # The world's reset puts both back: the red box where the file has it, the green one hidden.
    supervisor.simulationReset()
    supervisor.step(32)
    supervisor.step(32)
    (red,) = camera.getRecognitionObjects()
    assert red.getPosition()[1] == pytest.approx(0.05, abs=0.01)


def test_another_robots_body_hides_what_is_behind_it() -> None:
    target = green_target(20, 3, [0.6, 0.0, 0.025], [0.05, 0.05, 0.05])
    report = {"robots": [{"line": 1, "profile": "e-puck"}, {"line": 9, "profile": "e-puck"}]}
    camera = CameraPose(0.0, 0.0, 0.028, 0.0, 0.0, 52, 39, 0.84)
    occluding = Recogniser({**SETTINGS, "occlusion": 1}, [target], report)
    assert occluding.needs_robot_poses
    no_walls = WallBoxes(World.from_toml('format = "mazesim-world"\nversion = 1\n'))
    ahead = [(0.0, 0.0, 0.0), (0.3, 0.0, 0.0)]
    aside = [(0.0, 0.0, 0.0), (0.3, 0.2, 0.0)]
    assert occluding.recognise(camera, no_walls, ahead) == []
    assert [o.model for o in occluding.recognise(camera, no_walls, aside)] == ["cible"]
    # The camera's own robot hides nothing; without occlusion, nothing hides.
    assert len(occluding.recognise(camera, no_walls, [(0.0, 0.0, 0.0), (0.3, 0.2, 0.0)])) == 1
    seeing = Recogniser(SETTINGS, [target], report)
    assert not seeing.needs_robot_poses
    assert len(seeing.recognise(camera, no_walls, ahead)) == 1


def test_a_robot_a_supervisor_removed_is_not_recognised_and_hides_nothing() -> None:
    robot = green_target(9, 2, [5.0, 5.0, 0.0], [0.07, 0.07, 0.05])
    box = green_target(20, 3, [0.6, 0.0, 0.025], [0.05, 0.05, 0.05])
    report = {"robots": [{"line": 1, "profile": "e-puck"}, {"line": 9, "profile": "e-puck"}]}
    camera = CameraPose(0.0, 0.0, 0.028, 0.0, 0.0, 52, 39, 0.84)
    recogniser = Recogniser({**SETTINGS, "occlusion": 1}, [robot, box], report)
    no_walls = WallBoxes(World.from_toml('format = "mazesim-world"\nversion = 1\n'))
    here = recogniser.recognise(camera, no_walls, [(0.0, 0.0, 0.0), (0.3, 0.0, 0.0)])
    assert [o.id for o in here] == [2], "the robot ahead, the box behind it hidden"
    gone = recogniser.recognise(camera, no_walls, [(0.0, 0.0, 0.0), None])
    assert [o.id for o in gone] == [3], "the removed robot is not there to see or to hide"


def test_in_a_world_run_a_robot_crossing_the_line_of_sight_hides_the_box(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    run = run_world(str(SWARM / "worlds" / "hidden_box.wbt"), seconds=2.0)
    assert [r.exit_status for r in run.robots] == [0, 0]
    counts = json.loads((tmp_path / "watcher.json").read_text())
    assert counts[0] == 0, "the screen e-puck stands between the camera and the box"
    assert counts[-1] == 1, "it drove out of the way"


def test_an_object_a_robot_carries_moves_with_it_and_its_body_hides_it_not() -> None:
    """A public follower project's leader e-puck carries a Can in its turret slot: the object
    stayed where the import put it, hidden by its own carrier's body, and the follower found
    nothing to follow (its ``getRecognitionObjects()[0]`` raised)."""
    carried = {**green_target(12, 3, [0.3, 0.0, 0.06], [0.06, 0.06, 0.12]), "robot_line": 9}
    report = {
        "robots": [
            {"line": 1, "profile": "e-puck", "pose": [0.0, 0.0, 0.0]},
            {"line": 9, "profile": "e-puck", "pose": [0.3, 0.0, math.pi]},
        ]
    }
    camera = CameraPose(0.0, 0.0, 0.028, 0.0, 0.0, 52, 39, 0.84)
    no_walls = WallBoxes(World.from_toml('format = "mazesim-world"\nversion = 1\n'))
    recogniser = Recogniser({**SETTINGS, "occlusion": 1}, [carried], report)
    assert recogniser.follows_robots
    (seen,) = recogniser.recognise(camera, no_walls, [(0.0, 0.0, 0.0), (0.3, 0.0, math.pi)])
    assert seen.position[0] == pytest.approx(0.3)
    # The carrier drove 0.2 m on and turned: the object went with it.
    (seen,) = recogniser.recognise(camera, no_walls, [(0.0, 0.0, 0.0), (0.5, 0.05, 0.0)])
    assert seen.position[:2] == pytest.approx((0.5, 0.05))
    # Removed with its carrier.
    assert recogniser.recognise(camera, no_walls, [(0.0, 0.0, 0.0), None]) == []


#: A follower e-puck whose turret camera recognises, and a leader carrying a red Solid in its
#: turret slot, 0.3 m ahead; the leader drives away.
CARRIED_WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 3 3 }
E-puck {
  name "follower"
  controller "follower"
  turretSlot [
    Camera { translation 0.0395 0 -0.0206 name "rec" width 52 height 39 fieldOfView 0.84
      recognition Recognition { } }
  ]
}
E-puck {
  translation 0.3 0 0
  name "leader"
  controller "leader"
  turretSlot [
    Solid { translation 0 0 0.03 name "flag" model "flag" recognitionColors [ 0.666667 0 0 ]
      children [ Shape { geometry DEF FLAG Cylinder { height 0.06 radius 0.015 } } ] }
  ]
}
"""
FOLLOWER = """import json, os
from controller import Robot
robot = Robot()
camera = robot.getDevice("rec")
camera.enable(32)
camera.recognitionEnable(32)
seen = []
while robot.step(32) != -1:
    objects = camera.getRecognitionObjects()
    seen.append([list(o.getPosition()) for o in objects])
with open(os.path.join(os.environ["SWARM_LOG"], "seen.json"), "w") as out:
    json.dump(seen, out)
"""
LEADER = """from controller import Robot
robot = Robot()
for name in ("left wheel motor", "right wheel motor"):
    motor = robot.getDevice(name)
    motor.setPosition(float("inf"))
    motor.setVelocity(4.0)
while robot.step(32) != -1:
    pass
"""


@pytest.mark.usefixtures("own_cache")
def test_in_a_world_run_the_follower_sees_the_object_its_leader_carries_go_away(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "w.wbt").write_text(CARRIED_WORLD)
    for name, text in (("follower", FOLLOWER), ("leader", LEADER)):
        (tmp_path / "controllers" / name).mkdir(parents=True)
        (tmp_path / "controllers" / name / f"{name}.py").write_text(text)
    monkeypatch.setenv("SWARM_LOG", str(tmp_path))
    run = run_world(str(tmp_path / "worlds" / "w.wbt"), seconds=2.0, seed=1)
    assert all(r.exit_status == 0 for r in run.robots), [r.error for r in run.robots]
    seen = json.loads((tmp_path / "seen.json").read_text())
    assert len(seen[0]) == 1 and len(seen[-1]) == 1
    # 0.27 m ahead of the camera (3 cm ahead of the follower's centre) after the leader's
    # first step, then as far as the leader drove: 4 rad/s on wheels of 2 cm for 2 s.
    assert seen[0][0][0] == pytest.approx(0.27 + 4.0 * 0.02 * 0.032, abs=0.003)
    assert seen[-1][0][0] == pytest.approx(0.27 + 4.0 * 0.02 * 2.0, abs=0.01)
