"""An imported wall reflects infra-red by its appearance, as in Webots: its proximity readings are
``LUT(d / f)`` with ``f = 0.2 + 0.8 * red * (1 - 0.5 * roughness)`` (red times ``1 - transparency``;
Webots' reference manual, DistanceSensor; docs/webots.md), and the import's report and world file
carry that ``f``. A textured wall reflects by its image's mean red times the appearance's own, as
Webots picks the texture's colour (#32)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import mazesim
from mazesim.webots import import_wbt, import_wbt_text
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


def textured_wall(tmp_path: Path, appearance: str, image: np.ndarray | None) -> Path:
    """A world file in ``tmp_path`` with ``wall_ahead(appearance)``, and ``image`` (an (H, W, 3)
    uint8 array) as ``textures/wall.png`` beside it unless None."""
    from PIL import Image

    if image is not None:
        (tmp_path / "textures").mkdir()
        Image.fromarray(image).save(tmp_path / "textures" / "wall.png")
    path = tmp_path / "textured.wbt"
    path.write_text(wall_ahead(appearance))
    return path


#: A PBRAppearance and an Appearance whose texture is the image ``wall.png``.
PBR_TEXTURE = 'PBRAppearance { baseColorMap ImageTexture { url [ "textures/wall.png" ] } }'
PLAIN_TEXTURE = 'Appearance { texture ImageTexture { url [ "wall.png" ] } }'


def test_a_textured_wall_reflects_by_its_image_s_mean_red(tmp_path: Path) -> None:
    # Half the image red 1, half black, every pixel green: a mean red of 0.5, f = 0.6.
    image = np.zeros((8, 8, 3), dtype=np.uint8)
    image[:, :4, 0] = 255
    image[:, :, 1] = 255
    world, report = import_wbt(textured_wall(tmp_path, PBR_TEXTURE, image))
    assert [o["reflectance"] for o in report["obstacles"]] == [pytest.approx(0.6)]
    assert report["wall_textures"][0]["candidates"][0].endswith("textures/wall.png")
    readings, expected = front_readings(world, 0.6)
    assert readings == pytest.approx(expected, rel=0.02, abs=1.0)
    _, white = front_readings(world, 1.0)
    assert np.all(readings < white - 50.0), (readings, white)


def test_a_camera_sees_a_textured_wall_in_its_image_s_mean_colour(tmp_path: Path) -> None:
    """The one mean colour of the image gives the infra-red factor (by its red) and the
    colour a camera draws: half red, all green is (0.5, 1, 0) times the base colour."""
    image = np.zeros((8, 8, 3), dtype=np.uint8)
    image[:, :4, 0] = 255
    image[:, :, 1] = 255
    appearance = (
        'PBRAppearance { baseColor 1 0.5 1 baseColorMap ImageTexture { url [ "textures/wall.png" '
        "] } }"
    )
    world, report = import_wbt(textured_wall(tmp_path, appearance, image))
    assert report["wall_textures"][0]["colour"] == [1.0, 0.5, 1.0]
    assert world.wall_colours().tolist() == [pytest.approx([0.5, 0.5, 0.0])]
    assert [o["reflectance"] for o in report["obstacles"]] == [pytest.approx(0.6)]


@pytest.mark.parametrize(
    ("appearance", "factor"),
    [
        # The appearance's own red and roughness apply to the texture's: 0.2 + 0.8 * 0.25 * 0.5.
        (
            "PBRAppearance { baseColor 0.5 1 1 roughness 1 baseColorMap ImageTexture { url [ "
            '"textures/wall.png" ] } }',
            0.3,
        ),
        # An Appearance's texture is found in textures/ by its file name; its material's
        # diffuse colour does not count under a texture, its transparency does.
        (
            "Appearance { material Material { diffuseColor 0 0 0 transparency 0.5 } texture "
            'ImageTexture { url [ "wall.png" ] } }',
            0.4,
        ),
    ],
)
def test_a_texture_s_red_multiplies_the_appearance_s(
    tmp_path: Path, appearance: str, factor: float
) -> None:
    image = np.full((4, 4, 3), [127.5, 0, 0], dtype=np.float64).round().astype(np.uint8)
    _, report = import_wbt(textured_wall(tmp_path, appearance, image))
    assert [o["reflectance"] for o in report["obstacles"]] == [pytest.approx(factor, abs=2e-3)]


def test_a_textured_wall_without_its_image_reflects_as_white_and_says_so(
    tmp_path: Path,
) -> None:
    """As a floor texture, a wall texture that is nowhere is a warning naming the files looked
    for, once."""
    world, report = import_wbt(textured_wall(tmp_path, PLAIN_TEXTURE, None))
    assert [o["reflectance"] for o in report["obstacles"]] == [1.0]
    said = [w for w in report["warnings"] if "wall texture" in w]
    assert len(said) == 1 and '"wall.png" not found (looked for ' in said[0]
    assert str(tmp_path / "textures" / "wall.png") in said[0]
    assert np.isnan(world.wall_colours()).all()
    readings, expected = front_readings(world, 1.0)
    assert readings == pytest.approx(expected, rel=0.02, abs=1.0)


def test_a_wall_textured_by_a_webots_url_reflects_by_that_image(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Wall textures are found as floor textures are: a webots:// URL in the Webots installation.
    from PIL import Image

    monkeypatch.setenv("MAZESIM_PROTO_CACHE", str(tmp_path / "cache"))
    monkeypatch.setenv("WEBOTS_HOME", str(tmp_path / "webots"))
    name = "projects/default/worlds/textures/half_red.png"
    (tmp_path / "webots" / name).parent.mkdir(parents=True)
    image = np.zeros((8, 8, 3), dtype=np.uint8)
    image[:, :4, 0] = 255
    Image.fromarray(image).save(tmp_path / "webots" / name)
    appearance = f'PBRAppearance {{ baseColorMap ImageTexture {{ url [ "webots://{name}" ] }} }}'
    world_file = str(tmp_path / "project" / "worlds" / "w.wbt")
    _, report = import_wbt_text(wall_ahead(appearance), world_file)
    assert [o["reflectance"] for o in report["obstacles"]] == [pytest.approx(0.6)], report
