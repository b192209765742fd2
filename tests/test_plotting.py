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
    assert len(ax.collections) == 1  # the walls
    # One patch per paint region, plus the start (circle and arrow) and the goal.
    expected = len(world.paint_regions()) + 2 + (world.goal is not None)
    assert len(ax.patches) == expected
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
