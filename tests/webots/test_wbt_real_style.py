"""Webots worlds in the styles real users write (issue #16): maze walls as Solids with physics,
line tracks drawn as a floor ImageTexture beside the world file, an e-puck2 with a GPS and a
Compass on its turret, a robot that is not an e-puck. Nothing is silently dropped."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import mazesim
from mazesim.webots import import_wbt

HEADER = "#VRML_SIM R2023b utf8\n\nWorldInfo {\n  basicTimeStep 16\n}\n"


def physics_wall(index: int, x: float, y: float, length: float, turned: bool) -> str:
    """A maze wall as students write them: a Solid with a Shape, a boundingObject and physics."""
    rotation = "rotation 0 0 1 1.5708\n  " if turned else ""
    return (
        f"DEF WALL_{index} Solid {{\n  translation {x} {y} 0.05\n  {rotation}"
        "children [\n    Shape {\n      appearance PBRAppearance { baseColor 0.8 0.2 0.2 }\n"
        f"      geometry Box {{ size {length} 0.01 0.1 }}\n    }}\n  ]\n"
        f'  name "wall({index})"\n  boundingObject Box {{ size {length} 0.01 0.1 }}\n'
        "  physics Physics {\n    density -1\n    mass 1\n  }\n}\n"
    )


def maze_walls() -> list[tuple[float, float, float, bool]]:
    """18 walls of a 3 x 3 maze of 0.2 m cells: (x, y, length, turned)."""
    walls = []
    for i in range(3):
        for j in (-0.3, 0.3):
            walls.append((-0.2 + 0.2 * i, j, 0.2, False))
            walls.append((j, -0.2 + 0.2 * i, 0.2, True))
    walls += [(-0.2, -0.1, 0.2, True), (0.0, 0.1, 0.2, True), (0.1, 0.0, 0.2, False)]
    walls += [(-0.1, 0.1, 0.2, False), (0.2, -0.1, 0.2, True), (-0.1, -0.2, 0.2, False)]
    return walls


def track_image() -> np.ndarray:
    """64 x 48 grey levels: white, a black vertical band (columns 20-27), a mid-grey square."""
    grey = np.full((48, 64), 255, dtype=np.uint8)
    grey[:, 20:28] = 0
    grey[30:40, 40:50] = 128
    return grey


def write_world(folder: Path, robot: str, url: str = "textures/track.png") -> Path:
    arena = (
        "RectangleArena {\n  floorSize 1.6 1.2\n  floorTileSize 1.6 1.2\n"
        "  floorAppearance PBRAppearance {\n    baseColorMap ImageTexture {\n"
        f'      url [\n        "{url}"\n      ]\n    }}\n'
        "    roughness 1\n    metalness 0\n  }\n}\n"
    )
    walls = "".join(physics_wall(i, *w) for i, w in enumerate(maze_walls()))
    path = folder / "maze.wbt"
    path.write_text(HEADER + arena + walls + robot)
    return path


EPUCK2 = (
    'E-puck {\n  translation 0.15 0.15 0\n  rotation 0 0 1 1.5708\n  controller "<extern>"\n'
    '  version "2"\n  turretSlot [\n    GPS {\n      translation 0 0 0.01\n    }\n'
    '    Compass {\n      translation 0.01 0 0.01\n      name "north"\n    }\n  ]\n'
    "  groundSensorsSlot [\n    DistanceSensor {\n      translation 0.02 0 0\n"
    '      rotation 0 0 1 -1.5708\n      name "extra"\n'
    "      lookupTable [ 0 1000 0, 0.1 0 0.05 ]\n    }\n"
    "    Shape { geometry Box { size 0.01 0.01 0.01 } }\n  ]\n}\n"
)


@pytest.fixture
def maze(tmp_path: Path) -> Path:
    (tmp_path / "textures").mkdir()
    Image.fromarray(track_image()).save(tmp_path / "textures" / "track.png")
    return write_world(tmp_path, EPUCK2)


def test_physics_walls_are_walls_and_each_is_reported(maze: Path) -> None:
    world, report = import_wbt(maze)
    boxes = [o for o in report["obstacles"] if o["kind"] == "box"]
    # 4 arena walls + the 18 maze walls: none is dropped.
    assert len(boxes) == 4 + 18
    for x, y, length, turned in maze_walls():
        size = [0.01, length] if turned else [length, 0.01]
        assert any(
            math.isclose(b["center"][0], x, abs_tol=1e-6)
            and math.isclose(b["center"][1], y, abs_tol=1e-6)
            and (
                np.allclose(b["size"], [length, 0.01], atol=1e-6)
                if not turned
                else np.allclose(sorted(b["size"]), sorted(size), atol=1e-6)
            )
            for b in boxes
        ), (x, y)
    # Every Solid of the file is a wall with a warning that says it is kept static.
    text = maze.read_text()
    for name in re.findall(r'name "(wall\(\d+\))"', text):
        assert any(
            f'Solid "{name}": an object with physics: imported as a static obstacle' in w
            for w in report["warnings"]
        ), name
    assert len(world.wall_boxes()) == 22


def test_a_wall_with_physics_stops_the_robot(maze: Path) -> None:
    world, _ = import_wbt(maze)
    sim = mazesim.Simulator(world, robot="e-puck2", noise=False)
    sim.set_start(0.15, 0.15, 0.0)
    sim.reset()
    for _ in range(200):
        sim.step(4.0, 4.0)
    # The wall at x = 0.3 (turned, 0.01 thick) stops the body 0.037 m before its face.
    assert sim.pose[0] == pytest.approx(0.295 - 0.037, abs=0.002)
    assert sim.collisions >= 1


def test_the_floor_texture_is_paint_of_its_grey_levels_and_roughness(maze: Path) -> None:
    world, report = import_wbt(maze)
    assert report["floor_paint"] > 0
    assert not [w for w in report["warnings"] if "texture" in w]
    grey = track_image() / 255.0
    rows, cols = grey.shape
    # The image covers the 1.6 x 1.2 floor once: pixel (r, c) centres at these points.
    for r, c in [(0, 0), (5, 22), (47, 27), (35, 45), (30, 40), (20, 63), (10, 19), (10, 28)]:
        x = -0.8 + (c + 0.5) * 1.6 / cols
        y = 0.6 - (r + 0.5) * 1.2 / rows
        # The floor's appearance is of roughness 1, as users write it: Webots' factor is
        # 0.2 + 0.8 red (1 - 0.5 roughness), white 0.6.
        expected = 0.2 + 0.8 * grey[r, c] * 0.5
        assert world.floor_reflectance(x, y) == pytest.approx(expected, abs=1e-9), (r, c)


def test_ground_sensors_see_the_track(maze: Path) -> None:
    world, _ = import_wbt(maze)
    sim = mazesim.Simulator(world, robot="e-puck", noise=False)
    # The band is columns 20-27: x in [-0.3, -0.1]; gs1 is 0.03 m ahead of the centre.
    sim.set_start(-0.2 - 0.03, 0.15, 0.0)
    sim.reset()
    sim.step(0.0, 0.0)
    black = sim.ground_sensors()[1]
    sim.set_start(0.05, -0.15, 0.0)
    sim.reset()
    sim.step(0.0, 0.0)
    white = sim.ground_sensors()[1]
    # The floor is of roughness 1: white reflects 0.6 (759 through the table; 856 at 1).
    assert black == pytest.approx(300.0, abs=5.0)
    assert white == pytest.approx(759.0, abs=5.0)


def test_the_e_puck2_and_its_turret_devices_are_reported(maze: Path) -> None:
    _, report = import_wbt(maze)
    assert report["robot_model"] == "e-puck2"
    assert report["robot_profile"] == "e-puck2"
    assert report["robot"] == pytest.approx({"x": 0.15, "y": 0.15, "yaw": 1.5708})
    devices = {d["name"]: d for d in report["extension_devices"]}
    assert set(devices) == {"gps", "north", "extra"}
    assert (devices["gps"]["type"], devices["gps"]["slot"]) == ("GPS", "turretSlot")
    # Measured from the robot's origin: the turret slot is 9.5 mm back and 48.6 mm up.
    assert devices["gps"]["translation"] == pytest.approx([-0.0095, 0.0, 0.0586])
    assert devices["north"]["type"] == "Compass"
    assert devices["north"]["translation"] == pytest.approx([0.0005, 0.0, 0.0586])
    extra = devices["extra"]
    assert (extra["type"], extra["slot"]) == ("DistanceSensor", "groundSensorsSlot")
    assert extra["yaw"] == pytest.approx(-1.5708)
    assert extra["fields"]["lookupTable"] == [[0.0, 1000.0, 0.0], [0.1, 0.0, 0.05]]
    # The Shape beside it is not a device: a warning, not silence.
    assert any("groundSensorsSlot: a visual node" in w for w in report["warnings"])


def test_a_missing_texture_is_a_warning_naming_the_files(tmp_path: Path) -> None:
    path = write_world(tmp_path, EPUCK2, url="lines.png")
    world, report = import_wbt(path)
    warning = next(w for w in report["warnings"] if "floor texture" in w)
    assert "not found" in warning
    assert str(tmp_path / "lines.png") in warning
    assert str(tmp_path / "textures" / "lines.png") in warning
    assert report["floor_paint"] == 0
    assert world.paint_regions() == []


def test_an_empty_texture_url_is_no_texture_and_no_warning(tmp_path: Path) -> None:
    # Webots' scene tree leaves url [""] when a texture is cleared: it loads no image and says
    # nothing, and the floor is drawn in its appearance's own colour.
    world, report = import_wbt(write_world(tmp_path, EPUCK2, url=""))
    assert not [w for w in report["warnings"] if "floor texture" in w]
    assert report["floor_paint"] == 0
    assert world.paint_regions() == []


def test_a_jpeg_in_textures_beside_the_world_is_found(tmp_path: Path) -> None:
    (tmp_path / "textures").mkdir()
    jpeg = tmp_path / "textures" / "track.jpg"
    Image.fromarray(track_image()).save(jpeg, quality=95)
    # A url as Webots' own worlds write them: a web address whose file name is beside the world.
    path = write_world(tmp_path, EPUCK2, url="https://example.org/worlds/textures/track.jpg")
    world, report = import_wbt(path)
    assert report["floor_paint"] > 0
    decoded = np.asarray(Image.open(jpeg).convert("L"), dtype=float) / 255.0
    for r, c in [(5, 5), (24, 23), (35, 45)]:
        x = -0.8 + (c + 0.5) * 0.025
        y = 0.6 - (r + 0.5) * 0.025
        # Of roughness 1: 0.2 + 0.8 grey (1 - 0.5).
        assert world.floor_reflectance(x, y) == pytest.approx(0.2 + 0.4 * decoded[r, c])


def test_an_image_that_cannot_be_decoded_is_a_warning(tmp_path: Path) -> None:
    (tmp_path / "textures").mkdir()
    (tmp_path / "textures" / "track.png").write_bytes(b"not a png")
    _, report = import_wbt(write_world(tmp_path, EPUCK2))
    assert any("cannot decode it" in w for w in report["warnings"])


def test_a_robot_that_is_not_an_e_puck_is_replaced_with_a_warning(tmp_path: Path) -> None:
    thymio = 'Thymio2 {\n  translation 0.1 -0.1 0\n  rotation 0 0 1 3.14159\n  controller "x"\n}\n'
    world, report = import_wbt(write_world(tmp_path, thymio))
    assert report["robot_model"] == "Thymio2"
    assert report["robot_profile"] == "e-puck"
    assert report["robot"] == pytest.approx({"x": 0.1, "y": -0.1, "yaw": 3.14159})
    warning = next(w for w in report["warnings"] if "Thymio2" in w and "not an e-puck" in w)
    assert "e-puck in its place" in warning
    # The footprint a library robot stands as in a whole-world run is not a wall of the run of
    # one controller: the e-puck in its place does not start inside it.
    (tmp_path / "epuck").mkdir()
    epuck = 'E-puck {\n  translation 0.1 -0.1 0\n  rotation 0 0 1 3.14159\n  controller "x"\n}\n'
    walls_of_an_e_puck_world, _ = import_wbt(write_world(tmp_path / "epuck", epuck))
    assert np.array_equal(world.wall_boxes(), walls_of_an_e_puck_world.wall_boxes())


def test_a_floor_proto_tiles_its_texture(tmp_path: Path) -> None:
    Image.fromarray(np.array([[0, 255]], dtype=np.uint8)).save(tmp_path / "bars.png")
    floor = (
        "Floor {\n  size 1 1\n  tileSize 0.5 0.5\n  appearance PBRAppearance {\n"
        '    baseColorMap ImageTexture { url [ "bars.png" ] }\n'
        "    textureTransform TextureTransform { scale 2 1 }\n  }\n}\n"
    )
    path = tmp_path / "floor.wbt"
    path.write_text(HEADER + floor)
    world, report = import_wbt(path)
    # Tiles of 0.25 x 0.5 m (0.5 / scale 2), each black then white: bars 0.125 m wide.
    for k in range(8):
        x = -0.5 + (k + 0.5) * 0.125
        assert world.floor_reflectance(x, 0.3) == pytest.approx(0.2 if k % 2 == 0 else 1.0)
    assert report["robot"] is None and report["robot_model"] is None
    assert report["robot_profile"] == "e-puck"


def test_a_textured_plane_on_the_floor_is_paint(tmp_path: Path) -> None:
    # Line-follower worlds often draw the track on a Plane of their own, turned on the floor.
    grey = np.full((10, 20), 255, dtype=np.uint8)
    grey[:, 10:] = 0
    Image.fromarray(grey).save(tmp_path / "line.png")
    plane = (
        "Solid {\n  translation 0.5 0.2 0.0005\n  rotation 0 0 1 1.5708\n  children [\n"
        "    Shape {\n      appearance Appearance {\n"
        '        texture ImageTexture { url [ "line.png" ] }\n      }\n'
        "      geometry Plane { size 0.4 0.2 }\n    }\n  ]\n}\n"
    )
    path = tmp_path / "plane.wbt"
    path.write_text(HEADER + plane)
    world, report = import_wbt(path)
    assert report["floor_textures"][0]["size"] == pytest.approx([0.4, 0.2])
    # Turned a quarter: the image's right (black) half lies towards +y, its top towards -x.
    assert world.floor_reflectance(0.5, 0.3) == pytest.approx(0.2)
    assert world.floor_reflectance(0.5, 0.1) == pytest.approx(1.0)
    assert world.floor_reflectance(0.5, 0.45) == pytest.approx(world.floor_background)
