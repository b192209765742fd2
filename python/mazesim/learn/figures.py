"""Trajectory pictures of navigator episodes, in the manner of the report's Fig. 4.6 and 4.8.

The maze is drawn by :func:`mazesim.plotting.plot_world`; on it, each episode's path, and along
the first path markers ``D1``, ``D2``... where the higher level chose a sub-task (the report numbers
the robot's positions the same way; the ``D`` keeps them apart from the checkpoint ids), and a
legend: the world's markers, each path with its start and end, and each decision as
``D3: left turn at checkpoint +5``.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence

import numpy as np
import numpy.typing as npt

from mazesim._core import World
from mazesim._figures import save_figure
from mazesim.learn.subtasks import SUBTASK_CODES, SUBTASK_NAMES
from mazesim.plotting import START_COLOR, trajectory_legend, world_figure

__all__ = ["decision_label", "save_episodes_png"]

#: Colours of successive episodes' paths.
PATH_COLOURS = ("#d62728", "#1f77b4", "#9467bd", "#ff7f0e", "#17becf", "#8c564b")


def decision_label(number: int, event: int, option: int) -> str:
    """How a decision reads in legends: ``"D3: left turn at checkpoint +5"``."""
    turn = SUBTASK_NAMES[option].lower().replace(" on a door", "")
    turn = turn.replace("going forward", "straight on")
    return f"D{number}: {turn} at checkpoint {event:+d}"


def save_episodes_png(
    world: World,
    paths: Mapping[int, npt.NDArray[np.float64]],
    marks: Mapping[int, Sequence[tuple[float, float, int, int]]],
    path: str | os.PathLike[str],
    title: str,
    arrived: Mapping[int, bool] | None = None,
) -> None:
    """Draws episodes' trajectories on the world and writes a PNG file atomically.

    Args:
        world: The world the episodes ran in.
        paths: Episode number -> (T, 2) positions.
        marks: Episode number -> (x, y, event, sub-task) where the higher level chose.
        path: The PNG file; its folder must exist.
        title: The title above the picture.
        arrived: Episode number -> whether it reached the goal (shown in the legend).
    """
    figure, ax = world_figure(world, 7.5, (4.0, 10.0), 1.2)
    extra = []
    for place, episode in enumerate(sorted(paths)):
        trajectory = paths[episode]
        if len(trajectory) == 0:
            continue
        colour = PATH_COLOURS[place % len(PATH_COLOURS)]
        outcome = ""
        if arrived is not None and episode in arrived:
            outcome = ", goal" if arrived[episode] else ", no goal"
        extra += ax.plot(
            trajectory[:, 0],
            trajectory[:, 1],
            color=colour,
            linewidth=1.1,
            alpha=0.85,
            zorder=7,
            label=f"episode {episode}{outcome}",
        )
        ax.plot(
            trajectory[:1, 0], trajectory[:1, 1], "s", color=START_COLOR, markersize=3, zorder=8
        )
        ax.plot(trajectory[-1:, 0], trajectory[-1:, 1], "o", color=colour, markersize=3, zorder=8)
    if paths:
        extra += ax.plot([], [], "s", color=START_COLOR, markersize=4, label="path start")
        extra += ax.plot([], [], "o", color="grey", markersize=4, label="path end")
    first = min(paths) if paths else None
    for number, (x, y, event, option) in enumerate(
        marks.get(first, []) if first is not None else [], 1
    ):
        ax.annotate(
            f"D{number}",
            (x, y),
            fontsize=6,
            ha="center",
            va="center",
            color="white",
            zorder=9,
            bbox={"boxstyle": "round,pad=0.15", "facecolor": "#08519c", "edgecolor": "none"},
        )
        extra += ax.plot(
            [],
            [],
            linestyle="none",
            marker=f"$D{number}$",
            color="#08519c",
            markersize=9,
            label=f"{decision_label(number, event, option)} ({SUBTASK_CODES[option]})",
        )
    trajectory_legend(ax, world, extra)
    ax.set_title(title, fontsize=9)
    save_figure(figure, path)
