"""The camera on worlds of every kind: a robot's own Camera node gives its size and field of
view (a robot that is no e-puck, an e-puck saved expanded); boxes and cylinders with physics
are drawn as balls are; what a supervisor imports or removes is drawn, or no longer; and a
camera of a world saved in Webots' old NUE frame sees what the same camera of an ENU world
sees (#32, #33)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
import pytest

from mazesim import World
from mazesim.webots import controller, prepare
from mazesim.webots.camera import WALL_SHADE, Block, CameraView, render
from mazesim.webots.importer import import_wbt
from mazesim.webots.rays import FloorPaint, WallBoxes
from mazesim.webots.scene import read_scene

pytestmark = pytest.mark.usefixtures("fresh_robot")

HEADER = "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\n"
#: The red of a Solid of ``baseColor 1 0 0`` as the camera lights it.
RED = (round(255 * WALL_SHADE), 0, 0)


def robot_of(tmp_path: Path, text: str, robot_line: int | None = None) -> controller.Supervisor:
    """The supervisor of a world file's ``text`` (the robot on ``robot_line``, else the
    first e-puck), its camera ``camera`` enabled, after one step."""
    path = tmp_path / "camera.wbt"
    path.write_text(text)
    world, imported = import_wbt(str(path), robot_line=robot_line)
    report = dict(imported, path=str(path))
    scene = read_scene(text, report["robot_model"], report["robot_line"])
    prepare(world, seconds=10.0, noise=False, report=report, scene=scene)
    controller.Robot.created = None
    supervisor = controller.Supervisor()
    supervisor.getDevice("camera").enable(32)
    supervisor.step(32)
    return supervisor


def pixels(camera: Any) -> npt.NDArray[np.uint8]:
    """The camera's last image as (height, width, 3) red, green, blue."""
    data = camera.getImage()
    assert data is not None
    image = np.frombuffer(data, dtype=np.uint8)
    return image.reshape(camera.getHeight(), camera.getWidth(), 4)[:, :, 2::-1]


def red_share(camera: Any) -> float:
    """The share of the camera's last image in the red of a Solid of ``baseColor 1 0 0``."""
    return float((pixels(camera) == RED).all(axis=2).mean())


def test_a_robot_that_is_no_e_puck_has_its_own_cameras_size(tmp_path: Path) -> None:
    text = (
        HEADER + 'Robot {\n  name "watcher"\n  controller "<extern>"\n  supervisor TRUE\n'
        "  children [ Camera { translation 0.02 0 0.05 width 256 height 128 "
        "fieldOfView 1.2 } ]\n}\n"
    )
    camera = robot_of(tmp_path, text, robot_line=3).getDevice("camera")
    assert (camera.getWidth(), camera.getHeight()) == (256, 128)
    assert camera.getFov() == pytest.approx(1.2)
    assert len(camera.getImage()) == 256 * 128 * 4
    image = camera.getImageArray()
    assert len(image) == 256 and len(image[255]) == 128


def test_an_e_puck_saved_expanded_keeps_its_camera_nodes_fields(tmp_path: Path) -> None:
    text = (
        HEADER + 'Robot {\n  name "e-puck"\n  controller "<extern>"\n  supervisor TRUE\n'
        "  children [ Camera { translation 0.03 0 0.028 width 160 height 120 "
        "fieldOfView 0.9 } ]\n}\n"
    )
    camera = robot_of(tmp_path, text).getDevice("camera")
    assert (camera.getWidth(), camera.getHeight()) == (160, 120)
    assert camera.getFov() == pytest.approx(0.9)


#: A red box with physics 0.15 m ahead of an e-puck facing +x, 4 cm a side.
RED_BOX = (
    "DEF BOX Solid { translation 0.15 0 0.02 children [ Shape { appearance PBRAppearance { "
    "baseColor 1 0 0 } geometry DEF B Box { size 0.04 0.04 0.04 } } ] boundingObject USE B "
    "physics Physics { mass 0.05 } }\n"
)
E_PUCK = 'E-puck { controller "<extern>" supervisor TRUE }\n'


@pytest.mark.parametrize(
    "geometry",
    ["Box { size 0.04 0.04 0.04 }", "Cylinder { radius 0.02 height 0.04 }"],
    ids=["box", "cylinder"],
)
def test_a_box_or_cylinder_with_physics_is_drawn_in_its_colour(
    tmp_path: Path, geometry: str
) -> None:
    text = HEADER + E_PUCK + RED_BOX.replace("Box { size 0.04 0.04 0.04 }", geometry)
    camera = robot_of(tmp_path, text).getDevice("camera")
    image = pixels(camera)
    middle = camera.getWidth() // 2
    # Its front face, 0.1 m from the lens, spans 0.4 rad: about 23 of the 52 columns, from
    # the floor to 1.2 cm above the lens (its top, 4 cm up).
    red_columns = np.nonzero((image == RED).all(axis=2).any(axis=0))[0]
    assert middle in red_columns and 20 <= len(red_columns) <= 26, red_columns
    assert tuple(image[camera.getHeight() // 2, middle]) == RED


def test_a_low_box_below_the_lens_shows_its_top_and_a_wall_hides_a_box_behind_it() -> None:
    world = World.from_toml(
        'format = "mazesim-world"\nversion = 1\n[start]\nx = 0.0\ny = 0.0\nyaw = 0.0\n'
        "[[walls]]\ncenter = [0.3, 0.0]\nsize = [0.01, 0.4]\n",
        "screen",
    )
    view = CameraView()
    walls, floor = WallBoxes(world), FloorPaint(world)
    green = (0.0, 1.0, 0.0)
    # 1 cm high, 6 cm a side, its near face 4 cm from the level lens (2.8 cm up): the face lies
    # 0.42 rad or more below the horizon, out of the view (0.32 rad each side of it); its top,
    # 0.18 to 0.42 rad below, fills the bottom rows.
    low = Block(0.1, 0.0, 0.0, (0.06, 0.06), 0.0, 0.01, green, 1.0)
    image = render(view, walls, floor, (0.0, 0.0, 0.0), blocks=[low])
    seen = (image[:, :, 2::-1] == (0, round(255 * WALL_SHADE), 0)).all(axis=2)
    rows = np.nonzero(seen.any(axis=1))[0]
    assert list(rows) == list(range(rows.min(), view.height)) and 28 <= rows.min() <= 32, rows
    behind = Block(0.4, 0.0, 0.0, None, 0.03, 0.05, green, 1.0)
    hidden = render(view, walls, floor, (0.0, 0.0, 0.0), blocks=[behind])
    assert np.array_equal(hidden, render(view, walls, floor, (0.0, 0.0, 0.0)))


def test_what_a_supervisor_imports_or_removes_is_drawn_from_the_next_step(
    tmp_path: Path,
) -> None:
    supervisor = robot_of(tmp_path, HEADER + E_PUCK)
    camera = supervisor.getDevice("camera")
    assert red_share(camera) == 0.0
    children = supervisor.getRoot().getField("children")
    children.importMFNodeFromString(-1, RED_BOX)
    supervisor.step(32)
    assert red_share(camera) > 0.05
    supervisor.getFromDef("BOX").remove()
    supervisor.step(32)
    assert red_share(camera) == 0.0
    ball = RED_BOX.replace("Box { size 0.04 0.04 0.04 }", "Sphere { radius 0.02 }")
    children.importMFNodeFromString(-1, ball)
    supervisor.step(32)
    assert red_share(camera) > 0.05


#: One scene in the two frames: a red wall 0.2 m ahead and 5 cm left of an e-puck whose camera
#: is tilted 0.3 rad down, and a turret camera turned 0.5 rad left.
ENU_SCENE = (
    HEADER + 'E-puck {\n  controller "<extern>"\n  camera_rotation 0 1 0 0.3\n'
    '  turretSlot [ Camera { translation 0.01 0.02 0.03 rotation 0 0 1 0.5 name "side" '
    "width 40 height 30 } ]\n}\n"
    "Solid { translation 0.2 0.05 0.05 children [ Shape { appearance PBRAppearance { "
    "baseColor 1 0 0 } geometry DEF W Box { size 0.02 0.1 0.1 } } ] boundingObject USE W }\n"
)
#: NUE: x north, y up, z east; the e-puck faces -z, its devices' frame x right, y up, z back.
NUE_SCENE = (
    "#VRML_SIM R2021a utf8\nWorldInfo { basicTimeStep 32 }\n"
    'E-puck {\n  controller "<extern>"\n  camera_rotation 1 0 0 -0.3\n'
    '  turretSlot [ Camera { translation -0.02 0.03 -0.01 rotation 0 1 0 0.5 name "side" '
    "width 40 height 30 } ]\n}\n"
    "Solid { translation -0.05 0.05 -0.2 children [ Shape { appearance PBRAppearance { "
    "baseColor 1 0 0 } geometry DEF W Box { size 0.1 0.1 0.02 } } ] boundingObject USE W }\n"
)


@pytest.mark.parametrize("name", ["camera", "side"])
def test_a_camera_of_an_nue_world_sees_what_the_enu_one_sees(tmp_path: Path, name: str) -> None:
    images = []
    for number, text in enumerate((ENU_SCENE, NUE_SCENE)):
        folder = tmp_path / str(number)
        folder.mkdir()
        robot = robot_of(folder, text)
        camera = robot.getDevice(name)
        camera.enable(32)
        robot.step(32)
        images.append(pixels(camera))
        controller.Robot.created = None
    enu, nue = images
    assert (enu == RED).all(axis=2).any()
    assert np.array_equal(enu, nue)


@pytest.mark.parametrize("name", ["seed-maze", "line-follow", "arena"])
def test_a_tilted_camera_draws_what_it_would_casting_every_pixel_s_ray(
    name: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    # A tilted camera's pixels that meet the floor nearer than the nearest wall cast no ray
    # (WallBoxes.nearest_distance); the image is the one every pixel's own cast gives, at every
    # pose, close to a wall too.
    world = World.builtin(name)
    walls, floor = WallBoxes(world, sensed=True), FloorPaint(world)
    rng = np.random.default_rng(7)
    views = [
        CameraView(width=96, height=72, pitch=0.35),
        CameraView(width=64, height=48, pitch=-0.2),
    ]
    poses = [(float(x), float(y), float(a)) for x, y, a in rng.uniform(-0.5, 0.5, (6, 3)) * 2]
    for index in range(0, len(walls.center), max(1, len(walls.center) // 6)):
        # 2 cm off a wall's face, looking along it or at it.
        gap = walls.half[index, 0] + 0.02
        x = walls.center[index, 0] + walls.cos[index] * gap
        y = walls.center[index, 1] + walls.sin[index] * gap
        poses.append((float(x), float(y), float(rng.uniform(-3.1, 3.1))))
    assert any(0.0 < walls.nearest_distance(pose[:2]) < 0.03 for pose in poses)
    culled = [render(view, walls, floor, pose) for view in views for pose in poses]
    monkeypatch.setattr(WallBoxes, "nearest_distance", lambda self, point: 0.0)
    every = [render(view, walls, floor, pose) for view in views for pose in poses]
    assert all(np.array_equal(a, b) for a, b in zip(culled, every))
