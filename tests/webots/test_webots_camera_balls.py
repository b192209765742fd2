"""The camera sees the world's balls (movable bodies whose collision shape is a sphere) in their
colours where they are now; a world without balls renders as before (#32)."""

from __future__ import annotations

import hashlib
from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

import mazesim
from mazesim.webots import controller, prepare
from mazesim.webots.camera import WALL_SHADE, Ball, CameraView, render
from mazesim.webots.importer import import_wbt, import_wbt_text
from mazesim.webots.rays import FloorPaint, WallBoxes
from mazesim.webots.scene import read_scene

pytestmark = pytest.mark.usefixtures("fresh_robot")

HEADER = "#VRML_SIM R2023b utf8\n"
#: An e-puck at the origin facing +x, and Webots' Ball PROTO (its stand-in, offline), blue,
#: 15 cm ahead.
BALL_WORLD = (
    HEADER
    + 'EXTERNPROTO "webots://projects/objects/balls/protos/Ball.proto"\n'
    + "E-puck { supervisor TRUE }\n"
    + "DEF BALL Ball { translation 0.15 0 0.0325 color 0 0 1 }\n"
)
#: The blue of a ball of ``color 0 0 1``, lit as the camera lights walls.
BLUE = (0, 0, round(255 * WALL_SHADE))


@pytest.fixture(autouse=True)
def _offline(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Webots' PROTOs are their stand-ins: no download, no Webots installation."""
    monkeypatch.setenv("MAZESIM_OFFLINE", "1")
    monkeypatch.setenv("MAZESIM_PROTO_CACHE", str(tmp_path / "cache"))
    monkeypatch.delenv("WEBOTS_HOME", raising=False)


def blue_columns(camera: controller.Camera) -> list[int]:
    """The image columns where the camera's last image has a pixel of the ball's blue."""
    data = camera.getImage()
    assert data is not None
    image = np.frombuffer(data, dtype=np.uint8)
    pixels = image.reshape(camera.getHeight(), camera.getWidth(), 4)[:, :, 2::-1]
    return sorted({int(x) for x in np.nonzero((pixels == BLUE).all(axis=2))[1]})


def test_the_ball_proto_is_a_blue_sphere_in_the_report() -> None:
    _, report = import_wbt_text(BALL_WORLD, "ball.wbt")
    (ball,) = report["bodies"]
    assert ball["sphere"] is True and ball["colour"] == [0.0, 0.0, 1.0]
    assert ball["radius"] == pytest.approx(0.0325)
    # Without a color the PROTO's own default, Webots' 1.0 0.54 0.08 (orange).
    _, plain = import_wbt_text(BALL_WORLD.replace(" color 0 0 1", ""), "plain.wbt")
    assert plain["bodies"][0]["colour"] == pytest.approx([1.0, 0.54, 0.08])


def test_a_box_with_physics_is_no_sphere() -> None:
    box = (
        HEADER + "E-puck { }\nSolid { translation 0.2 0 0.02 boundingObject Box { size 0.04 "
        "0.04 0.04 } physics Physics { mass 0.1 } }\n"
    )
    _, report = import_wbt_text(box, "box.wbt")
    (body,) = report["bodies"]
    assert body["sphere"] is False and body["colour"] is None


def test_the_e_puck_sees_the_blue_ball_ahead_then_where_it_was_moved(tmp_path: Path) -> None:
    path = tmp_path / "ball.wbt"
    path.write_text(BALL_WORLD)
    world, report = import_wbt(str(path))
    scene = read_scene(BALL_WORLD, report["robot_model"], report["robot_line"])
    prepare(world, seconds=10.0, noise=False, report=report, scene=scene)
    controller.Robot.created = None
    supervisor = controller.Supervisor()
    camera = supervisor.getDevice("camera")
    camera.enable(32)
    supervisor.step(32)
    middle = camera.getWidth() // 2
    ahead = blue_columns(camera)
    assert middle - 1 in ahead and middle in ahead
    # 3.25 cm of radius 12 cm from the lens spans 2 asin(0.0325 / 0.12) = 0.55 rad: 33 of the
    # 52 columns (focal length 58.3 pixels).
    assert 31 <= len(ahead) <= 34, ahead
    # Moved 6 cm to the robot's left (+y), its right edge is 0.21 rad left of the middle:
    # column 13.
    ball = supervisor.getFromDef("BALL")
    assert ball is not None
    translation = ball.getField("translation")
    assert translation is not None
    translation.setSFVec3f([0.15, 0.06, 0.0325])
    supervisor.step(32)
    left = blue_columns(camera)
    assert left and 12 <= max(left) <= 14 and min(left) == 0, left


def test_a_nearer_wall_hides_the_ball() -> None:
    world = mazesim.World.from_toml(
        'format = "mazesim-world"\nversion = 1\n[start]\nx = 0.0\ny = 0.0\nyaw = 0.0\n'
        "[[walls]]\ncenter = [0.1, 0.0]\nsize = [0.01, 0.4]\n",
        "screen",
    )
    view = CameraView()
    walls, floor = WallBoxes(world), FloorPaint(world)
    ball = Ball(0.2, 0.0, 0.0325, (0.0, 0.0, 1.0), 0.2)
    hidden = render(view, walls, floor, (0.0, 0.0, 0.0), balls=[ball])
    assert np.array_equal(hidden, render(view, walls, floor, (0.0, 0.0, 0.0)))
    seen = render(view, walls, floor, (0.0, 0.0, 0.0), balls=[Ball(0.06, 0.0, 0.02, None, 0.2)])
    # A ball without a colour (reflectance 0.2) is black; it stands before the wall.
    assert tuple(seen[view.height // 2, view.width // 2, :3]) == (0, 0, 0)


def image_digest(image: npt.NDArray[np.uint8]) -> str:
    return hashlib.sha256(image.tobytes()).hexdigest()[:16]


def test_a_world_without_balls_renders_bit_for_bit_as_before() -> None:
    # A pushable box (no sphere) among walls and paint: the digest of its image was taken
    # before balls were drawn.
    text = (
        HEADER + "E-puck { camera_rotation 0 1 0 0.2 }\n"
        "Solid { translation 0.25 0 0.05 children [ Shape { appearance PBRAppearance { "
        "baseColor 0.1 0.9 0.2 } geometry DEF W Box { size 0.02 0.5 0.1 } } ] "
        "boundingObject USE W }\n"
        "Solid { translation 0.12 0.03 0.02 boundingObject Box { size 0.04 0.04 0.04 } "
        "physics Physics { mass 0.1 } }\n"
        "Pose { translation 0.075 0 0.0005 children [ Shape { appearance PBRAppearance { "
        "baseColor 0 0 1 } geometry Box { size 0.04 0.04 0.001 } } ] }\n"
    )
    world, report = import_wbt_text(text, "no-balls.wbt")
    assert len(report["bodies"]) == 1
    view = CameraView(pitch=0.2)
    image = render(view, WallBoxes(world, sensed=True), FloorPaint(world), (0.0, 0.0, 0.0))
    assert image_digest(image) == DIGEST_WITHOUT_BALLS


DIGEST_WITHOUT_BALLS = "5dc7095630861c7f"
