"""A device's getters refuse a wrong argument with mazesim's own error, before the sensor's first
reading as after it: a derived getter (a GPS's speed, an inertial unit's quaternion, a touch
sensor's force vector) answered NaN to any arguments until then, and ``Camera.saveImage`` let a
path object's own failure out (both found by the fuzzed registry, ``make fuzz``)."""

from __future__ import annotations

import math
import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from mazesim.errors import InvalidArgumentError, WrongTypeError
from mazesim.webots import controller, simulation
from supervised_world import supervisor_in

WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
E-puck {
  controller "<extern>"
  supervisor TRUE
  turretSlot [ GPS { } ]
}
"""


class _PathThatFails(os.PathLike[str]):
    def __fspath__(self) -> str:
        raise RuntimeError("this path object cannot say its path")


@pytest.fixture
def robot(tmp_path: Path) -> Iterator[Any]:
    yield supervisor_in(tmp_path, WORLD)
    controller.Robot.created = None
    simulation.release()


def test_a_derived_getter_refuses_an_argument_before_and_after_the_first_reading(
    robot: Any,
) -> None:
    gps = robot.getDevice("gps")
    gps.enable(32)
    with pytest.raises(InvalidArgumentError):
        gps.getSpeed(1)
    assert math.isnan(gps.getSpeed())
    robot.step(32)
    with pytest.raises(InvalidArgumentError):
        gps.getSpeedVector("x")
    assert math.isfinite(gps.getSpeed())


def test_save_image_takes_text_or_a_path_and_refuses_a_path_that_fails(
    robot: Any, tmp_path: Path
) -> None:
    camera = robot.getDevice("camera")
    camera.enable(32)
    robot.step(32)
    with pytest.raises(WrongTypeError, match="cannot say its path"):
        camera.saveImage(_PathThatFails())
    with pytest.raises(WrongTypeError, match="filename"):
        camera.saveImage(b"image.png")  # type: ignore[arg-type]
    assert camera.saveImage(tmp_path / "image.png") == 0
    assert camera.saveImage(str(tmp_path / "image.jpg"), 80) == 0
    assert (tmp_path / "image.png").stat().st_size > 0
