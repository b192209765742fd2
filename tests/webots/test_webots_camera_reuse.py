"""The camera renders only what it must: the floor paint tests each region against the points
near it alone, giving the regions seen as testing every point did, so images stay byte for
byte; a camera whose robot and fellows have not moved keeps its image without drawing it again."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import mazesim
from mazesim.webots import camera as cameras
from mazesim.webots import controller, prepare, run_controller
from mazesim.webots import simulation as simulations
from mazesim.webots.camera import CameraView, render
from mazesim.webots.rays import FloorPaint, WallBoxes
from mazesim.webots.scene import Scene
from native_controllers import NEEDS_COMPILERS, write_source

#: Walls round a floor of overlapping paint of every shape, some coloured: later paint covers
#: earlier, rotated rectangles, circles and polyline capsules among them.
PAINTED = (
    'format = "mazesim-world"\nversion = 1\n[start]\nx = -0.2\ny = 0.05\nyaw = 0.3\n'
    "[[walls]]\ncenter = [0.5, 0.0]\nsize = [0.02, 1.0]\ncolour = [0.9, 0.1, 0.1]\n"
    "[[walls]]\ncenter = [-0.5, 0.0]\nsize = [0.02, 1.0]\n"
    "[[walls]]\ncenter = [0.0, 0.5]\nsize = [1.0, 0.02]\n"
    '[[paint]]\nshape = "rect"\ncenter = [0.0, 0.0]\nsize = [0.6, 0.4]\nyaw = 0.4\n'
    "reflectance = 0.3\n"
    '[[paint]]\nshape = "circle"\ncenter = [0.1, 0.1]\nradius = 0.12\nreflectance = 0.6\n'
    "colour = [0.0, 0.8, 0.2]\n"
    '[[paint]]\nshape = "polyline"\npoints = [[-0.3, -0.2], [0.0, 0.15], [0.3, -0.1]]\n'
    "width = 0.03\nreflectance = 0.2\n"
    '[[paint]]\nshape = "rect"\ncenter = [0.2, 0.0]\nsize = [0.05, 0.3]\nyaw = -1.2\n'
    "reflectance = 0.9\ncolour = [0.1, 0.2, 0.9]\n"
)


@pytest.fixture(autouse=True)
def release() -> Iterator[None]:
    yield
    controller.Robot.created = None
    simulations.release()


@pytest.fixture
def drawn(monkeypatch: pytest.MonkeyPatch) -> list[Any]:
    """The robot poses of the images the cameras draw, in order."""
    poses: list[Any] = []

    def counted(*arguments: Any) -> Any:
        poses.append(arguments[3])
        return render(*arguments)

    monkeypatch.setattr(cameras, "render", counted)
    return poses


def every_point_tested(paint: FloorPaint) -> FloorPaint:
    """The same paint with every point tested against every region."""
    paint._grid.bounded = False
    return paint


def test_paint_regions_are_those_found_testing_every_point() -> None:
    world = mazesim.World.from_toml(PAINTED, "painted")
    paint = FloorPaint(world)
    generator = np.random.default_rng(7)
    x = generator.uniform(-0.6, 0.6, (50, 40))
    y = generator.uniform(-0.6, 0.6, (50, 40))
    x[0, :3] = [np.nan, np.inf, -np.inf]
    found = paint.region(x, y)
    assert found.shape == x.shape
    assert set(np.unique(found)) == {-1, 0, 1, 2, 3, 4}
    np.testing.assert_array_equal(found, every_point_tested(FloorPaint(world)).region(x, y))


@pytest.mark.parametrize("pitch", [0.0, 0.5])
def test_camera_images_are_those_of_testing_every_point(pitch: float) -> None:
    world = mazesim.World.from_toml(PAINTED, "painted")
    walls = WallBoxes(world, sensed=True)
    view = CameraView(width=120, height=80, pitch=pitch)
    grid, everywhere = FloorPaint(world), every_point_tested(FloorPaint(world))
    colours: set[bytes] = set()
    for pose in [(-0.2, 0.05, 0.3), (0.0, -0.3, 1.4), (0.3, 0.2, 3.0), (-0.35, -0.3, 0.8)]:
        image = render(view, walls, grid, pose)
        assert image.tobytes() == render(view, walls, everywhere, pose).tobytes()
        colours |= {pixel.tobytes() for pixel in np.unique(image.reshape(-1, 4), axis=0)}
    assert len(colours) >= 4


def test_a_still_camera_keeps_its_image_without_drawing_it_again(drawn: list[Any]) -> None:
    world = mazesim.World.from_toml(PAINTED, "painted")
    prepare(world, seconds=2.0, noise=False)
    robot = controller.Robot()
    camera = robot.getDevice("camera")
    camera.enable(32)
    robot.step(32)
    first = camera.getImage()
    for _ in range(3):
        robot.step(32)
    assert len(drawn) == 1
    assert camera.getImage() == first
    left, right = robot.getDevice("left wheel motor"), robot.getDevice("right wheel motor")
    for motor in (left, right):
        motor.setPosition(float("inf"))
        motor.setVelocity(4.0)
    robot.step(32)
    assert camera.getImage() != first
    assert len(drawn) == 2


def last_image(world: mazesim.World, read_every_step: bool, drawn: list[Any]) -> bytes | None:
    """The camera's image after 20 steps of a robot driving in an arc."""
    prepare(world, seconds=2.0, noise=False)
    robot = controller.Robot()
    camera = robot.getDevice("camera")
    camera.enable(64)
    left, right = robot.getDevice("left wheel motor"), robot.getDevice("right wheel motor")
    for motor, speed in ((left, 3.0), (right, 4.0)):
        motor.setPosition(float("inf"))
        motor.setVelocity(speed)
    for _ in range(20):
        robot.step(32)
        if read_every_step:
            camera.getImage()
    image = camera.getImage()
    controller.Robot.created = None
    simulations.release()
    return image


def test_a_camera_never_read_draws_nothing_and_its_image_is_the_sampled_one(
    drawn: list[Any],
) -> None:
    world = mazesim.World.from_toml(PAINTED, "painted")
    every = last_image(world, True, drawn)
    assert len(drawn) == 10  # one image per 64 ms sampling period, the robot moving
    drawn.clear()
    prepare(world, seconds=2.0, noise=False)
    robot = controller.Robot()
    robot.getDevice("camera").enable(64)
    for _ in range(20):
        robot.step(32)
    assert drawn == []
    controller.Robot.created = None
    simulations.release()
    once = last_image(world, False, drawn)
    assert len(drawn) == 1
    assert once is not None and once == every


#: A C controller driving in an arc for 20 steps of 32 ms with its camera sampling every 64 ms;
#: with an argument it reads the image after the last step and prints its bytes' sum.
C_ARC = """#include <stdio.h>
#include <webots/camera.h>
#include <webots/motor.h>
#include <webots/robot.h>

int main(int argc, char **argv) {
  wb_robot_init();
  WbDeviceTag camera = wb_robot_get_device("camera");
  wb_camera_enable(camera, 64);
  const char *motors[2] = {"left wheel motor", "right wheel motor"};
  const double speeds[2] = {3.0, 4.0};
  for (int m = 0; m < 2; m++) {
    WbDeviceTag motor = wb_robot_get_device(motors[m]);
    wb_motor_set_position(motor, INFINITY);
    wb_motor_set_velocity(motor, speeds[m]);
  }
  for (int i = 0; i < 20; i++)
    wb_robot_step(32);
  if (argc > 1) {
    const unsigned char *image = wb_camera_get_image(camera);
    const unsigned char *again = wb_camera_get_image(camera);
    long sum = 0;
    int size = 4 * wb_camera_get_width(camera) * wb_camera_get_height(camera);
    for (int k = 0; image && k < size; k++)
      sum += image[k];
    printf("image sum %ld same %d\\n", sum, image == again);
  }
  wb_robot_cleanup();
  return 0;
}
"""


@NEEDS_COMPILERS
def test_a_c_controllers_camera_never_read_draws_nothing_and_reads_the_sampled_image(
    drawn: list[Any], tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    """The image crosses the link when the controller asks for it, not at every step: a camera
    enabled and never read draws no image; read once after the last step, it draws one, the
    image a Python controller gets, and a second read in the same step asks for nothing."""
    world = mazesim.World.from_toml(PAINTED, "painted")
    expected = last_image(world, False, drawn)
    assert expected is not None
    drawn.clear()
    source = write_source(tmp_path, "arc", C_ARC)
    run = run_controller(source.parent, world, seconds=2.0, noise=False)
    assert run.exit_status == 0
    assert drawn == []
    capfd.readouterr()
    run = run_controller(
        source.parent, world, seconds=2.0, noise=False, scene=Scene(controller_args=["read"])
    )
    assert run.exit_status == 0
    assert len(drawn) == 1
    assert f"image sum {sum(expected)} same 1" in capfd.readouterr().out
