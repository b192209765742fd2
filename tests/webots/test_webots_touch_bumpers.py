"""Bumper TouchSensors on e-pucks read their own boundingObject's contact, not the whole body's
(reference manual, TouchSensor: a "bumper" returns 1 when its bounding object collides): a
front bumper touching a wall while the body does not, a robot rear-ended by another e-puck,
and side bumpers turned on the robot (#32, #33)."""

from __future__ import annotations

import functools
from pathlib import Path

import pytest

from swarm_project import run_project

PROJECT = Path(__file__).resolve().parent.parent / "data" / "webots-touch-bumpers"

run = functools.partial(run_project, PROJECT)


def test_a_front_bumper_touching_a_wall_reads_1_and_the_rear_one_0(tmp_path: Path) -> None:
    """The e-puck stands 3.5 mm from the arena's wall, its front bumper's box 0.5 mm from it:
    the body touches nothing, the bumper does."""
    _, logs = run("front_wall", tmp_path, 1.0)
    rows = logs["bumped"]["rows"]
    assert len(rows) > 10
    assert all(row["front bumper"] == 1.0 for row in rows)
    assert all(row["rear bumper"] == 0.0 for row in rows)


def test_a_rear_ended_e_puck_reads_its_rear_bumper_not_its_front_one(tmp_path: Path) -> None:
    """Another e-puck drives into the standing one from behind and pushes it: its rear bumper
    reads 1 from the contact on, its front bumper 0 throughout."""
    _, logs = run("rear_ended", tmp_path, 2.0)
    rows = logs["bumped"]["rows"]
    assert rows[0] == {"front bumper": 0.0, "rear bumper": 0.0}, "the pusher 2.6 cm behind"
    assert all(row["front bumper"] == 0.0 for row in rows)
    assert all(row["rear bumper"] == 1.0 for row in rows[-20:])


def test_side_bumpers_turned_on_the_robot_read_the_wall_on_their_side(tmp_path: Path) -> None:
    """A left bumper in a Pose turned a quarter left (its box placed by another Pose) touches
    the wall beside the robot; the right one, turned a quarter right, touches nothing."""
    _, logs = run("side_bumpers", tmp_path, 1.0)
    rows = logs["bumped"]["rows"]
    assert len(rows) > 10
    assert all(row == {"left bumper": 1.0, "right bumper": 0.0} for row in rows)


def test_a_bumper_s_bounding_object_through_use_and_transform_is_placed_in_its_frame() -> None:
    """A ``USE``d Cylinder in a Transform turned a quarter left and moved: a disc of the
    cylinder's radius where the Transform puts it, in the sensor's frame; a node without a
    boundingObject, or one the file does not write, has none."""
    from mazesim.webots.robot_frames import bounding_footprints

    text = """#VRML_SIM R2023b utf8
DEF ROUND Cylinder { radius 0.01 height 0.01 }
Robot {
  children [
    TouchSensor {
      name "nose"
      boundingObject Transform {
        translation 0.02 0 0
        rotation 0 0 1 1.5708
        children [ Pose { translation 0.01 0 0 children [ USE ROUND ] } ]
      }
    }
    TouchSensor { }
  ]
}
"""
    (nose,) = bounding_footprints(text, 3, "TouchSensor", "nose", False)
    assert (nose.x, nose.y, nose.half, nose.radius) == pytest.approx(
        (0.02, 0.01, None, 0.01), abs=1e-6
    )
    assert bounding_footprints(text, 3, "TouchSensor", "touch sensor", False, "touch sensor") == []
    assert bounding_footprints(text, 3, "TouchSensor", "tail", False) == []
