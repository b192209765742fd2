"""The camera from its full pose and the other robots' visual shapes: a camera robot raised and
tilted to look down at the arena sees it from there, its image turned as its node is; another
robot's visual shapes (outside its boundingObject) are drawn where that robot stands, and an
e-puck's body is seen from above (#32, #33)."""

from __future__ import annotations

import json
import textwrap
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
import pytest
from PIL import Image

from mazesim import World
from mazesim.webots.camera import (
    PLATE_COLOUR,
    ROBOT_COLOUR,
    WALL_SHADE,
    CameraView,
    RobotBody,
    placed_shape,
    render,
)
from mazesim.webots.lockstep import run_world
from mazesim.webots.rays import FloorPaint, WallBoxes
from mazesim.webots.robot_frames import RobotShape, robot_shapes
from mazesim.webots.scene import read_scene
from supervised_world import supervisor_in

pytestmark = pytest.mark.usefixtures("fresh_robot")

HEADER = "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\n"
#: A Solid of ``baseColor`` (r g b) with physics: a box 5 cm wide standing at (x, y).
BOX = """Solid {{
  translation {x} {y} 0.025
  children [ Shape {{
    appearance PBRAppearance {{ baseColor {colour} }} geometry DEF B Box {{ size 0.05 0.05 0.05 }}
  }} ]
  boundingObject USE B
  physics Physics {{ }}
}}
"""
#: A camera robot 0.5 m above (0.1, 0), turned a quarter turn about y: its camera, looking
#: along the robot's x axis, looks straight down, the top of its image towards +x, its left
#: towards +y.
WATCHER = """Robot {
  translation 0.1 0 0.5
  rotation 0 1 0 1.5708
  name "watcher"
  controller "<extern>"
  supervisor TRUE
  children [ Camera { width 64 height 64 fieldOfView 1.0 } ]
}
"""


def colours(camera: Any) -> npt.NDArray[np.uint8]:
    """The camera's last image as (height, width, 3) red, green, blue."""
    data = camera.getImage()
    assert data is not None
    image = np.frombuffer(data, dtype=np.uint8)
    return image.reshape(camera.getHeight(), camera.getWidth(), 4)[:, :, 2::-1]


def shade(*rgb: float) -> tuple[int, ...]:
    """A colour as the camera lights a body of it."""
    return tuple(round(255 * WALL_SHADE * c) for c in rgb)


def watching_camera(tmp_path: Path) -> Any:
    """The camera of the watcher robot above a red box, a green box 15 cm along +x and a blue
    one 15 cm along +y, after one step."""
    boxes = (
        BOX.format(x=0.1, y=0.0, colour="1 0 0")
        + BOX.format(x=0.25, y=0.0, colour="0 1 0")
        + BOX.format(x=0.1, y=0.15, colour="0 0 1")
    )
    robot = supervisor_in(tmp_path, HEADER + boxes + WATCHER, robot="Robot {")
    camera = robot.getDevice("camera")
    camera.enable(32)
    robot.step(32)
    return camera


def test_a_camera_robot_raised_and_tilted_looks_down_from_its_pose(
    tmp_path: Path,
) -> None:
    image = colours(watching_camera(tmp_path))
    middle = image[30:34, 30:34]
    assert (middle == shade(1, 0, 0)).all(), "straight below the lens: the red box's top"
    green = np.argwhere((image == shade(0, 1, 0)).all(axis=2))
    blue = np.argwhere((image == shade(0, 0, 1)).all(axis=2))
    assert len(green) and len(blue)
    assert green[:, 0].max() < 20, "the box ahead along +x lies at the image's top"
    assert abs(green[:, 1].mean() - 31.5) < 2.0
    assert blue[:, 1].max() < 20, "the box along +y lies at the image's left"
    assert abs(blue[:, 0].mean() - 31.5) < 2.0


def test_a_jpeg_of_quality_100_keeps_a_small_coloured_patch_as_webots_does(
    tmp_path: Path,
) -> None:
    """Webots writes a JPEG of quality above 90 with its colours at full resolution: the red
    box's top, 6 pixels wide, keeps red above 200 and green and blue below 100 (an OpenCV
    threshold a controller applies to the saved file)."""
    camera = watching_camera(tmp_path)
    red = (colours(camera) == shade(1, 0, 0)).all(axis=2)
    assert camera.saveImage(str(tmp_path / "best.jpg"), 100) == 0
    assert camera.saveImage(str(tmp_path / "rough.jpg"), 30) == 0
    saved = np.asarray(Image.open(tmp_path / "best.jpg").convert("RGB")).astype(int)
    kept = (saved[:, :, 0] > 200) & (saved[:, :, 1] < 100) & (saved[:, :, 2] < 100)
    assert kept[red].all()
    rough = (tmp_path / "rough.jpg").stat().st_size
    assert rough < (tmp_path / "best.jpg").stat().st_size, "a lower quality, a smaller file"


DISC_ROBOT = """DEF TARGET Robot {
  translation 0.2 0 0
  name "target"
  children [
    Solid {
      translation 0 0 0.05
      scale 0.05 0.05 0.05
      children [ Shape {
        appearance PBRAppearance { baseColor 1 0 0 roughness 1 metalness 0 }
        geometry Cylinder { height 0.01 radius 0.66 }
      } ]
    }
  ]
  controller "<none>"
}
"""


def others_shapes(text: str) -> list[RobotShape]:
    """The visual shapes of the first robot of a world file's ``text``, seen from the watcher
    robot added after it."""
    text += WATCHER
    line = text.count("\n", 0, text.index("Robot {\n  translation 0.1 0 0.5")) + 1
    shapes = robot_shapes(read_scene(text, None, line))
    assert len(shapes) == 1
    return next(iter(shapes.values()))


def test_another_robots_visual_shapes_are_listed_in_its_frame() -> None:
    text = HEADER + DISC_ROBOT.replace(
        "translation 0.2 0 0", "translation 0.2 0 0\n  rotation 0 0 1 1.5708"
    )
    text = text.replace("translation 0 0 0.05\n", "translation 0.01 0 0.05\n")
    (disc,) = others_shapes(text)
    assert disc.size is None and not disc.sphere
    assert disc.radius == pytest.approx(0.033)
    assert (disc.bottom, disc.top) == pytest.approx((0.04975, 0.05025))
    assert (disc.x, disc.y) == pytest.approx((0.01, 0.0), abs=1e-9), "in the robot's own frame"
    assert disc.colour == (1.0, 0.0, 0.0)
    drawn = placed_shape(disc, (0.2, 0.1, 1.5708))
    assert (drawn.x, drawn.y) == pytest.approx((0.2, 0.11), abs=1e-4)


def test_an_e_pucks_body_and_its_shapes_are_seen_from_above() -> None:
    empty = World.from_toml('format = "mazesim-world"\nversion = 1\n')
    view = CameraView(width=32, height=32, fov=0.6, x=0.0, z=0.5, pitch=np.pi / 2)
    robot = [RobotBody(0.0, 0.0, 0.037)]
    image = render(view, WallBoxes(empty), FloorPaint(empty), (0.0, 0.0, 0.0), robot)
    grey = shade(*ROBOT_COLOUR)
    assert tuple(image[16, 16, 2::-1]) == grey, "the body's top, seen from above"
    assert tuple(image[0, 0, 2::-1]) != grey
    (disc,) = others_shapes(HEADER + DISC_ROBOT)
    with_disc = render(
        view,
        WallBoxes(empty),
        FloorPaint(empty),
        (0.0, 0.0, 0.0),
        robot,
        blocks=[placed_shape(disc, (0.0, 0.0, 0.0))],  # type: ignore[list-item]
    )
    assert tuple(with_disc[16, 16, 2::-1]) == shade(1, 0, 0), "the disc on top of the body"
    assert tuple(with_disc[0, 0, 2::-1]) == tuple(image[0, 0, 2::-1])
    assert PLATE_COLOUR != (1.0, 0.0, 0.0)


WATCHER_CONTROLLER = textwrap.dedent(
    """
    import json, os
    from controller import Robot

    robot = Robot()
    camera = robot.getDevice("camera")
    camera.enable(32)
    robot.step(64)
    image = camera.getImageArray()
    red = sum(1 for column in image for (r, g, b) in column if r > 200 and g < 100 and b < 100)
    with open(os.environ["WATCH_LOG"], "w") as out:
        json.dump(red, out)
    """
)


def test_in_a_world_run_a_camera_robot_sees_another_robots_disc(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    log = tmp_path / "red.json"
    monkeypatch.setenv("WATCH_LOG", str(log))
    (tmp_path / "worlds").mkdir()
    (tmp_path / "controllers" / "watch").mkdir(parents=True)
    (tmp_path / "controllers" / "watch" / "watch.py").write_text(WATCHER_CONTROLLER)
    watcher = WATCHER.replace('"<extern>"', '"watch"').replace("0.1 0 0.5", "0.2 0 0.5")
    world = tmp_path / "worlds" / "w.wbt"
    world.write_text(HEADER + DISC_ROBOT + watcher)
    run = run_world(str(world), seconds=0.2, noise=False)
    assert [r.exit_status for r in run.robots if r.controller] == [0]
    red = json.loads(log.read_text())
    # The disc's radius of 3.3 cm from 0.45 m above it, 64 pixels over 1 rad: about 60 pixels.
    assert 30 < red < 120
