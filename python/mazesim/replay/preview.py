"""A labelled picture of a world, for world authors: ``mazesim show WORLD``.

:func:`save_world_preview` draws a world with :func:`mazesim.plotting.plot_world` (walls, floor
paint, checkpoints, start, goal), adds the maze grid when the world has one, each checkpoint's
code and an arrow along its reading direction (arrival), a legend, and the importer's warnings
listed beside the picture, and writes a PNG atomically.
"""

from __future__ import annotations

import math
import os
import textwrap
from collections.abc import Sequence
from pathlib import Path

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from mazesim import load_world
from mazesim._core import World
from mazesim._figures import save_figure
from mazesim.plotting import plot_world, world_legend_handles

__all__ = ["GRID_COLOR", "load_with_warnings", "save_world_preview"]

GRID_COLOR = "#6baed6"


def _draw_grid(ax: object, world: World) -> bool:
    """Draws the cell grid of a maze world; returns whether there was one."""
    maze = world.cell_maze()
    if maze is None:
        return False
    rows, cols = int(maze["rows"]), int(maze["cols"])  # type: ignore[call-overload]
    cell = float(maze["cell_size"])  # type: ignore[arg-type]
    x0, y0 = (float(v) for v in maze["origin"])  # type: ignore[attr-defined]
    style = {"color": GRID_COLOR, "linewidth": 0.6, "linestyle": ":", "zorder": 2}
    for col in range(cols + 1):
        ax.plot([x0 + col * cell] * 2, [y0, y0 + rows * cell], **style)  # type: ignore[attr-defined]
    for row in range(rows + 1):
        ax.plot([x0, x0 + cols * cell], [y0 + row * cell] * 2, **style)  # type: ignore[attr-defined]
    return True


def _draw_codes(ax: object, world: World) -> None:
    """Each checkpoint's code beside it and an arrow along its reading direction."""
    for checkpoint in world.checkpoints():
        x, y = (float(v) for v in checkpoint["center"])  # type: ignore[attr-defined]
        yaw = float(checkpoint["yaw"])  # type: ignore[arg-type]
        ax.annotate(  # type: ignore[attr-defined]
            "",
            xy=(x + 0.045 * math.cos(yaw), y + 0.045 * math.sin(yaw)),
            xytext=(x - 0.045 * math.cos(yaw), y - 0.045 * math.sin(yaw)),
            arrowprops={"arrowstyle": "->", "color": "black", "lw": 0.8},
            zorder=6,
        )
        ax.text(  # type: ignore[attr-defined]
            x - 0.06 * math.cos(yaw),
            y - 0.06 * math.sin(yaw),
            str(checkpoint["code"]),
            fontsize=5.5,
            ha="center",
            va="center",
            family="monospace",
            zorder=6,
            bbox={"boxstyle": "round,pad=0.1", "facecolor": "white", "alpha": 0.8, "lw": 0},
        )


def save_world_preview(
    world: World,
    path: str | os.PathLike[str],
    warnings: Sequence[str] | None = None,
    title: str | None = None,
) -> None:
    """Draws a world with its legend (and the importer's warnings) into a PNG file.

    Args:
        world: The world.
        path: The PNG file; its folder must exist.
        warnings: The importer's warnings of a ``.wbt`` world, listed beside the picture (an
            empty list says there were none); None for a world that was not imported, which
            gets no such note.
        title: The title; by default the world's name and size.
    """
    xmin, ymin, xmax, ymax = world.bounds
    aspect = (ymax - ymin) / max(xmax - xmin, 1e-3)
    figure = Figure(figsize=(10.0, max(4.5, min(10.0, 6.0 * aspect + 1.0))), dpi=110)
    FigureCanvasAgg(figure)
    ax = figure.add_axes((0.07, 0.08, 0.55, 0.84))
    plot_world(ax, world)
    has_grid = _draw_grid(ax, world)
    _draw_codes(ax, world)
    handles = world_legend_handles(world)
    if world.checkpoints():
        handles.append(
            Line2D(
                [],
                [],
                marker=r"$\rightarrow$",
                linestyle="none",
                color="black",
                markersize=9,
                label="code (bars, e.g. 10110) read along the arrow: arrival",
            )
        )
    if has_grid:
        handles.append(Line2D([], [], color=GRID_COLOR, linestyle=":", label="maze cells"))
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8)
    checkpoints = len(world.checkpoints())
    ax.set_title(
        title
        or f"{world.name}: {xmax - xmin:.2f} x {ymax - ymin:.2f} m, {checkpoints} checkpoints",
        fontsize=10,
    )
    if warnings is not None:
        notes = [f"importer warnings ({len(warnings)}):"] if warnings else ["no importer warnings"]
        for warning in warnings[:25]:
            notes += textwrap.wrap(f"- {warning}", 60, subsequent_indent="  ")
        if len(warnings) > 25:
            notes.append(f"... and {len(warnings) - 25} more")
        figure.text(0.66, 0.08, "\n".join(notes), fontsize=7, va="bottom", ha="left", wrap=True)
    save_figure(figure, path, tight=False)


def load_with_warnings(name_or_path: str) -> tuple[World, list[str] | None]:
    """A world and the importer's warnings (None unless it is a ``.wbt`` file)."""
    if Path(name_or_path).suffix.lower() == ".wbt":
        from mazesim.webots.importer import import_wbt

        world, report = import_wbt(name_or_path)
        return world, [str(warning) for warning in report["warnings"]]
    return load_world(name_or_path), None
