"""The camera sees colours: a Webots world's solids, walls and floor marks in the colours of
their appearances, and other e-pucks in the E-puck PROTO's; mazesim's own grey worlds render as
before."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import mazesim
from mazesim.errors import WorldFormatError
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.camera import WALL_SHADE, CameraView, RobotBody, render
from mazesim.webots.importer import import_wbt, import_wbt_text
from mazesim.webots.rays import FloorPaint, WallBoxes
from mazesim.webots.scene import read_scene
from mazesim.webots.shared_world import RobotView, shared_simulator

HEADER = "#VRML_SIM R2023b utf8\n"
#: A wall 0.25 m ahead of an e-puck at the origin: a Solid whose Shape has a green Material,
#: its bounding object that Shape.
GREEN_WALL = (
    "Solid { translation 0.25 0 0.05 children [ Shape { appearance Appearance { material "
    "Material { diffuseColor 0.1 0.9 0.2 } } geometry DEF W Box { size 0.02 0.5 0.1 } } ] "
    "boundingObject USE W }\n"
)
#: A blue 4 cm square on the floor, 5.5 to 9.5 cm ahead of an e-puck at the origin.
BLUE_PATCH = (
    "Pose { translation 0.075 0 0.0005 children [ Shape { appearance PBRAppearance { baseColor "
    "0 0 1 } geometry Box { size 0.04 0.04 0.001 } } ] }\n"
)


@pytest.fixture(autouse=True)
def release() -> Iterator[None]:
    yield
    controller.Robot.created = None
    simulations.release()


def camera_image(tmp_path: Path, text: str) -> tuple[Any, int, int]:
    """The first image of the camera of the e-puck of a world file's ``text``."""
    world_file = tmp_path / "colours.wbt"
    world_file.write_text(HEADER + text)
    world, report = import_wbt(world_file)
    prepare(world, seconds=1.0, noise=False, report=report, scene=read_scene(HEADER + text))
    controller.Robot.created = None
    robot = controller.Robot()
    camera = robot.getDevice("camera")
    camera.enable(32)
    robot.step(32)
    return camera.getImage(), camera.getWidth(), camera.getHeight()


def rgb(image: bytes, width: int, x: int, y: int) -> tuple[int, int, int]:
    return (
        controller.Camera.imageGetRed(image, width, x, y),
        controller.Camera.imageGetGreen(image, width, x, y),
        controller.Camera.imageGetBlue(image, width, x, y),
    )


def middle(tmp_path: Path, text: str) -> tuple[int, int, int]:
    """The colour of the middle of the first image of the world file's e-puck."""
    image, width, height = camera_image(tmp_path, text)
    return rgb(image, width, width // 2, height // 2)


def test_a_red_box_ahead_is_red_in_the_middle_of_the_image(tmp_path: Path) -> None:
    box = "SolidBox { translation 0.2 0 0.05 size 0.1 0.3 0.1 appearance PBRAppearance "
    seen = middle(tmp_path, "E-puck { }\n" + box + "{ baseColor 1 0 0 roughness 1 } }\n")
    assert seen == (round(255 * WALL_SHADE), 0, 0)


def test_a_green_wall_of_a_solid_is_green(tmp_path: Path) -> None:
    red, green, blue = middle(tmp_path, "E-puck { }\n" + GREEN_WALL)
    assert green > 4 * red and green > 4 * blue
    assert green == round(0.9 * 255 * WALL_SHADE)


def test_a_coloured_floor_patch_is_seen_looking_down(tmp_path: Path) -> None:
    image, width, height = camera_image(
        tmp_path, "E-puck { camera_rotation 0 1 0 0.6 }\n" + BLUE_PATCH
    )
    # Tilted 0.6 rad down, the middle ray meets the floor 7.1 cm ahead of the axle, on the
    # patch; the top row's meet it 12.7 cm ahead, on the bare white floor.
    assert rgb(image, width, width // 2, height // 2) == (0, 0, 255)
    assert rgb(image, width, width // 2, 0) == (255, 255, 255)


def test_a_wall_without_a_colour_renders_as_before(tmp_path: Path) -> None:
    wall = "Solid { translation 0.2 0 0.05 boundingObject Box { size 0.02 0.5 0.1 } }\n"
    grey = round(255 * WALL_SHADE)
    assert middle(tmp_path, "E-puck { }\n" + wall) == (grey, grey, grey)


def test_a_second_e_puck_ahead_has_the_e_puck_colours() -> None:
    text = HEADER + (
        'DEF A E-puck { name "a" }\n'
        'DEF B E-puck { translation 0.15 0 0 name "b" controller "other" }\n'
    )
    world, report = import_wbt_text(text, "two.wbt")
    simulator, why = shared_simulator(world, report["robots"], [0, 1], seed=1, noise=False)
    assert simulator is not None, why
    first = RobotView(simulator, 0)
    others = first.other_robots()
    assert [(round(x, 3), round(y, 3)) for x, y, _ in others] == [(0.15, 0.0)]
    robots = [RobotBody(*body) for body in others]
    view = CameraView()
    walls, floor = WallBoxes(world), FloorPaint(world)
    seen = render(view, walls, floor, first.pose, robots)
    alone = render(view, walls, floor, first.pose)
    body = round(0.5 * 255 * WALL_SHADE)
    middle = seen[view.height // 2, view.width // 2]
    assert tuple(middle[:3]) == (body, body, body)
    assert not np.array_equal(middle, alone[view.height // 2, view.width // 2])
    # The edge of its top plate (3.7 cm up, above the lens) is the PROTO's green print.
    column = seen[:, view.width // 2, :3].astype(int)
    green = [row for row in column if row[1] > 2 * row[0] and row[1] > 2 * row[2]]
    assert green, "the plate's green edge shows above the body"


def test_a_toml_world_gives_wall_and_paint_colours() -> None:
    text = (
        'format = "mazesim-world"\nversion = 1\n[start]\nx = 0.0\ny = 0.0\nyaw = 0.0\n'
        "[[walls]]\ncenter = [0.3, 0.0]\nsize = [0.02, 0.4]\ncolour = [1.0, 0.5, 0.0]\n"
        "[[walls]]\ncenter = [-0.3, 0.0]\nsize = [0.02, 0.4]\n"
        '[[paint]]\nshape = "circle"\ncenter = [0.1, 0.0]\nradius = 0.05\nreflectance = 0.3\n'
        "colour = [0.0, 1.0, 0.0]\n"
    )
    world = mazesim.World.from_toml(text, "coloured")
    colours = world.wall_colours()
    assert colours[0].tolist() == [1.0, 0.5, 0.0]
    assert np.isnan(colours[1]).all()
    assert world.paint_regions()[0]["colour"] == (0.0, 1.0, 0.0)
    again = mazesim.World.from_toml(world.to_toml(), "again")
    assert again == world and again.wall_colours()[0].tolist() == [1.0, 0.5, 0.0]
    with pytest.raises(WorldFormatError, match="colour level in"):
        mazesim.World.from_toml(text.replace("[1.0, 0.5, 0.0]", "[2.0, 0.5, 0.0]"), "bad")
