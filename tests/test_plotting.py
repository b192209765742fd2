"""Pictures of worlds and trajectories."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest
from matplotlib.figure import Figure

import mazesim
from mazesim.errors import InvalidArgumentError
from mazesim.plotting import plot_world, save_trajectory_png

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def test_plot_world_draws_walls_paint_and_labels(builtin_name: str) -> None:
    world = mazesim.load_world(builtin_name)
    ax = Figure().add_subplot()
    plot_world(ax, world)
    labels = sorted(text.get_text() for text in ax.texts)
    ids = sorted(str(checkpoint["id"]) for checkpoint in world.checkpoints())
    assert labels == sorted(ids + (["GOAL"] if world.goal is not None else []))
    regions = world.paint_regions()
    # The walls, and the floor paint as one collection of a path per region, in their order
    # (later regions cover earlier ones) and in the grey of its reflectance.
    assert len(ax.collections) == 1 + bool(regions)
    if regions:
        paint = ax.collections[0]
        assert len(paint.get_paths()) == len(regions)
        greys = [min(max(float(region["reflectance"]), 0.0), 1.0) for region in regions]
        assert np.allclose(paint.get_facecolors()[:, :3], np.repeat(greys, 3).reshape(-1, 3))
    # The start (circle and arrow) and the goal are patches of their own.
    assert len(ax.patches) == 2 + (world.goal is not None)
    xmin, ymin, xmax, ymax = world.bounds
    left, right = ax.get_xlim()
    assert left < xmin and right > xmax


def test_save_trajectory_png_writes_a_png_atomically(tmp_path: Path) -> None:
    world = mazesim.load_world("seed-maze")
    path = tmp_path / "path.png"
    xs = np.linspace(0.125, 0.6, 50)
    save_trajectory_png(world, xs, np.full(50, 0.125), path, title="a test")
    assert path.read_bytes().startswith(PNG_MAGIC)
    first = path.stat().st_size
    save_trajectory_png(world, [], [], path)
    assert path.read_bytes().startswith(PNG_MAGIC)
    assert path.stat().st_size != first
    assert os.listdir(tmp_path) == ["path.png"]


def test_save_trajectory_png_rejects_mismatched_coordinates(tmp_path: Path) -> None:
    with pytest.raises(InvalidArgumentError, match="3 and 2"):
        save_trajectory_png(mazesim.load_world("arena"), [0, 1, 2], [0, 1], tmp_path / "x.png")
    assert not (tmp_path / "x.png").exists()


def test_trajectory_of_a_world_without_walls_is_framed_by_the_path(tmp_path: Path) -> None:
    from mazesim.plotting import trajectory_limits
    from mazesim.webots.importer import import_wbt_text

    world, _ = import_wbt_text("#VRML_SIM R2023b utf8\nE-puck { }\n", "empty.wbt")
    xs, ys = np.linspace(0.0, 0.5, 20), np.linspace(0.0, 0.1, 20)
    xmin, xmax, ymin, ymax = trajectory_limits(world, xs, ys) or (0.0, 0.0, 0.0, 0.0)
    # The whole path, with a margin, and no less than 0.2 m across (it was +-30 micrometres).
    assert xmin < 0.0 and xmax > 0.5 and xmax - xmin < 0.6
    assert ymin < 0.0 and ymax > 0.1 and ymax - ymin >= 0.2
    assert trajectory_limits(world, [np.nan], [np.nan]) is None
    save_trajectory_png(world, xs, ys, tmp_path / "t.png")
    assert (tmp_path / "t.png").read_bytes()[:4] == b"\x89PNG"


def test_trajectory_picture_outlines_movable_bodies(tmp_path: Path) -> None:
    from mazesim.webots.importer import import_wbt_text

    text = (
        "#VRML_SIM R2023b utf8\nSolid { translation 0.3 0 0.05 "
        "boundingObject Box { size 0.1 0.1 0.1 } physics Physics { mass 0.2 } }\nE-puck { }\n"
    )
    world, report = import_wbt_text(text, "push.wbt")
    assert len(report["bodies"]) == 1
    figure = Figure()
    from mazesim.plotting import draw_bodies

    ax = figure.add_subplot()
    (entry,) = draw_bodies(ax, world)
    assert entry.get_label() == "movable body (start)" and len(ax.patches) == 1
