"""A world saved with the e-puck's body in a wall: Webots' physics pushes it out at the first
steps, so the import starts it at the nearest pose clear of the walls, and says so."""

from __future__ import annotations

import pytest

import mazesim
from mazesim.errors import InvalidArgumentError
from mazesim.webots import import_wbt_text

RADIUS = 0.037  # the e-puck's body
ARENA_INNER = 0.5  # a 1 m RectangleArena's walls start here


def arena_world(y: float) -> str:
    """A 1 m RectangleArena with an e-puck saved at (0, y) facing +x."""
    return f"""#VRML_SIM R2025a utf8
WorldInfo {{
}}
RectangleArena {{
  floorSize 1 1
}}
E-puck {{
  translation 0 {y} 0
  controller "void"
}}
"""


def test_a_body_saved_a_centimetre_into_the_arena_wall_starts_just_clear_of_it() -> None:
    world, report = import_wbt_text(arena_world(-0.48), "saved.wbt")
    x, y, yaw = world.start
    # pushed straight out of the wall (+y), to within a millimetre of touching it
    assert x == pytest.approx(0.0, abs=1e-9)
    assert -ARENA_INNER + RADIUS - 1e-3 <= y <= -ARENA_INNER + RADIUS + 1e-3
    assert yaw == pytest.approx(0.0, abs=1e-9)
    simulator = mazesim.Simulator(world)
    assert simulator.pose[1] == pytest.approx(y, abs=1e-6)
    moved = [w for w in report["warnings"] if "into a wall" in w]
    assert len(moved) == 1
    assert "(0.0000, -0.4800)" in moved[0] and "0.0170 m" in moved[0]
    assert report["robots"][0]["pose"][1] == pytest.approx(y, abs=1e-9)


def test_a_body_clear_of_the_walls_keeps_its_saved_pose_without_a_warning() -> None:
    world, report = import_wbt_text(arena_world(-0.45), "clear.wbt")
    assert world.start[1] == pytest.approx(-0.45, abs=1e-9)
    assert not [w for w in report["warnings"] if "into a wall" in w]


def test_a_body_deeper_than_the_push_out_limit_stays_refused() -> None:
    block = """Solid {
  translation 0 0 0.05
  boundingObject Box {
    size 0.3 0.3 0.1
  }
}
"""
    world, report = import_wbt_text(arena_world(0.0) + block, "deep.wbt")
    assert world.start[:2] == pytest.approx((0.0, 0.0), abs=1e-9)
    assert not [w for w in report["warnings"] if "into a wall" in w]
    with pytest.raises(InvalidArgumentError, match="clear of the walls"):
        mazesim.Simulator(world)
