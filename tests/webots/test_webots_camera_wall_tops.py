"""The camera draws each wall to its own top (#32): a level camera sees over a wall lower than
its view and what stands behind it. Before, every wall was drawn 0.1 m tall, so a 4 cm wall hid
a red wall behind it. A level camera's rows share one line across the floor per column, and
``WallBoxes.cast_sloped`` weighs each line's walls once for all its rows; it meets exactly
what it meets casting each row alone (the oracle below).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from mazesim.webots.rays import WallBoxes
from supervised_world import supervisor_in

pytestmark = pytest.mark.usefixtures("fresh_robot")


def random_walls(rng: np.random.Generator) -> WallBoxes:
    """Up to 30 boxes overlapping at random, tops from the floor to 15 cm, some untopped."""
    count = int(rng.integers(0, 30))
    boxes = [
        (*rng.uniform(-1, 1, 2), *rng.uniform(0.01, 0.3, 2), rng.uniform(-3, 3), 0.5)
        for _ in range(count)
    ]
    walls = WallBoxes.of_boxes(boxes)
    tops = rng.uniform(0.0, 0.15, count)
    tops[rng.random(count) < 0.2] = np.inf
    walls.top = tops
    return walls


@pytest.mark.parametrize("seed", range(4))
def test_rows_every_line_shares_meet_what_each_row_cast_alone_meets(seed: int) -> None:
    rng = np.random.default_rng(seed)
    for _ in range(60):
        walls = random_walls(rng)
        columns, rows = int(rng.integers(1, 40)), int(rng.integers(1, 30))
        angles = rng.uniform(-math.pi, math.pi, columns)
        lines = np.stack([np.cos(angles), np.sin(angles)], 1) * rng.uniform(0.5, 2, (columns, 1))
        slopes = np.sort(rng.uniform(-0.6, 0.6, rows))[::-1]
        height = float(rng.choice([0.028, 0.0, 0.2, rng.uniform(0, 0.2)]))
        origin = (float(rng.uniform(-1, 1)), float(rng.uniform(-1, 1)))
        untopped = float(rng.choice([math.inf, 0.1]))
        # Each row alone: a ray per line, each weighing its own walls.
        alone = [
            walls.cast_sloped(origin, lines, height, np.full(columns, s), untopped) for s in slopes
        ]
        expected, expected_wall, expected_top = (np.stack(part) for part in zip(*alone))
        grid = np.repeat(slopes[:, None], columns, axis=1)
        found, found_wall, found_top = walls.cast_sloped(origin, lines, height, grid, untopped)
        # A falling row sees the floor beyond where it meets it: only nearer hits count.
        floor = np.where(slopes < 0, height / np.maximum(-slopes, 1e-300), np.inf)[:, None]
        seen = np.isfinite(expected) & (expected <= floor)
        assert np.array_equal(seen, np.isfinite(found) & (found <= floor))
        assert found[seen] == pytest.approx(expected[seen], rel=1e-12, abs=1e-12)
        assert np.array_equal(found_wall[seen], expected_wall[seen])
        assert np.array_equal(found_top[seen], expected_top[seen])


def test_a_line_past_its_last_wall_meets_nothing_where_another_line_goes_on() -> None:
    # Two lines along +x: the first crosses a wall, the second passes beside it and meets
    # nothing. A falling ray of the second once "landed" on the untopped wall it misses, at
    # -inf, while the first line still weighed its wall.
    walls = WallBoxes.of_boxes([(1.0, 0.0, 0.1, 0.1, 0.0, 0.5)])
    lines = np.array([[1.0, 0.0], [1.0, 0.5]])
    distance, wall, _ = walls.cast_sloped((0.0, 0.0), lines, 0.2, np.array([[-0.1, -0.1]]))
    assert distance[0, 0] == pytest.approx(0.95) and wall[0, 0] == 0
    assert math.isinf(distance[0, 1]) and distance[0, 1] > 0 and wall[0, 1] == -1


#: A red wall 10 cm tall 0.4 m ahead of the e-puck (its camera 2.8 cm up, level).
RED_WALL = """Solid {
  translation 0.4 0 0.05
  children [ Shape {
    appearance PBRAppearance { baseColor 1 0 0 roughness 1 metalness 0 }
    geometry DEF R Box { size 0.02 0.6 0.1 }
  } ]
  boundingObject USE R
}
"""
#: A grey wall ``{height}`` m tall 0.1 m ahead of the e-puck, between it and the red one.
FRONT_WALL = """Solid {{
  translation 0.1 0 {centre}
  children [ Shape {{ geometry DEF F Box {{ size 0.02 0.6 {height} }} }} ]
  boundingObject USE F
  name "front"
}}
"""


def red_share(tmp_path: Path, front: float) -> float:
    """The share of the e-puck camera's image that is the red wall's red, with a front wall
    ``front`` m tall."""
    text = (
        "#VRML_SIM R2025a utf8\nWorldInfo { basicTimeStep 16 }\n"
        "RectangleArena { floorSize 2 2 }\n"
        + RED_WALL
        + FRONT_WALL.format(centre=front / 2, height=front)
        + 'E-puck { supervisor TRUE controller "<extern>" }\n'
    )
    robot = supervisor_in(tmp_path, text)
    camera = robot.getDevice("camera")
    camera.enable(16)
    robot.step(16)
    image = np.frombuffer(camera.getImage(), dtype=np.uint8).reshape(-1, 4)
    red = (image[:, 2] > 150) & (image[:, 1] < 60) & (image[:, 0] < 60)
    return float(red.mean())


def test_a_level_camera_sees_a_red_wall_over_a_lower_wall_in_front_of_it(
    tmp_path: Path,
) -> None:
    (tmp_path / "low").mkdir()
    (tmp_path / "tall").mkdir()
    # The camera is 3 cm ahead of the robot's centre, 2.8 cm up: the 3 cm wall's top is 2 mm
    # above it 6 cm away (slope 0.033), the red wall's 7.2 cm above it 0.36 m away (0.2): the
    # rows between see red.
    over = red_share(tmp_path / "low", 0.03)
    hidden = red_share(tmp_path / "tall", 0.1)
    assert hidden == 0.0
    assert over > 0.05
