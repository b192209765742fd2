"""``generate_maze``'s layout as a ``MazeLayout``: checked when made, frozen, shown and pickled as
a value; the layout's former keywords still draw the same maze, with a ``DeprecationWarning``,
for one release."""

from __future__ import annotations

import copy
import pickle
from typing import Any

import pytest

import mazesim
from mazesim import MazeLayout, generate_maze


@pytest.mark.parametrize(
    "former",
    [
        {"cell_size": 0.3, "wall_thickness": 0.02},
        {"checkpoints": False, "floor_reflectance": 0.5},
        {"cell_size": 0.25, "wall_thickness": 0.01, "checkpoints": True, "floor_reflectance": 0.36},
    ],
)
def test_former_keywords_warn_and_draw_the_maze_the_layout_draws(former: dict[str, Any]) -> None:
    with pytest.warns(DeprecationWarning, match="generate_maze's keyword .* is deprecated"):
        old = generate_maze(6, 4, seed=9, loops=0.2, **former)
    new = generate_maze(6, 4, seed=9, loops=0.2, layout=MazeLayout(**former))
    assert old == new and old.to_toml() == new.to_toml()
    assert new.checkpoints() or not former.get("checkpoints", True)


def test_the_default_layout_is_the_maze_without_one() -> None:
    plain = generate_maze(5, 5, seed=3, loops=0.1)
    assert plain.to_toml() == generate_maze(5, 5, 3, loops=0.1, layout=MazeLayout()).to_toml()
    wide = generate_maze(5, 5, seed=3, loops=0.1, layout=MazeLayout(cell_size=0.3))
    assert wide != plain


def test_the_layout_shows_and_keeps_its_values() -> None:
    layout = MazeLayout(cell_size=0.3, checkpoints=False)
    assert repr(layout) == (
        "MazeLayout(cell_size=0.3, wall_thickness=0.01, checkpoints=False, floor_reflectance=0.36)"
    )
    assert (layout.cell_size, layout.wall_thickness) == (0.3, 0.01)
    assert (layout.checkpoints, layout.floor_reflectance) == (False, 0.36)
    assert layout == MazeLayout(0.3, 0.01, False) and layout != MazeLayout()
    assert hash(layout) == hash(MazeLayout(0.3, checkpoints=False)) and layout != "MazeLayout"
    for again in (pickle.loads(pickle.dumps(layout)), copy.deepcopy(layout)):
        assert again == layout and repr(again) == repr(layout)
    with pytest.raises(AttributeError):
        layout.cell_size = 0.5  # type: ignore[misc]


@pytest.mark.parametrize(
    ("make", "says"),
    [
        (lambda: MazeLayout(cell_size=0.0), "wall thickness < cell size"),
        (lambda: MazeLayout(wall_thickness=0.3), "wall thickness < cell size"),
        (lambda: MazeLayout(cell_size=float("nan")), "wall thickness < cell size"),
        (lambda: MazeLayout(floor_reflectance=1.5), "floor_reflectance in"),
        (lambda: MazeLayout(checkpoints="no"), "checkpoints"),
        (lambda: MazeLayout(cell_size="wide"), "cell_size"),
        (lambda: generate_maze(layout={"cell_size": 0.3}), "expected layout to be a MazeLayout"),
        (lambda: generate_maze(layout=MazeLayout(), cell_size=0.3), "either layout or"),
        (lambda: generate_maze(not_a_keyword=1), "not_a_keyword"),
    ],
)
def test_bad_layouts_are_refused(make: Any, says: str) -> None:
    with pytest.raises(mazesim.InvalidArgumentError, match=says):
        make()
