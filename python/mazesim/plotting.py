"""Pictures of worlds and trajectories, drawn with matplotlib.

:func:`plot_world` draws a world onto a matplotlib ``Axes``: floor paint in grey levels equal to
its reflectance (black 0.2 ... white 1.0), walls, barcode checkpoints labelled by id, the goal and
the start pose; :func:`world_legend_handles` gives the legend entries of those markers.
:func:`save_trajectory_png` adds a robot's path (its start, its end and where it touched a wall)
with a legend and writes a PNG file atomically.
Figures are rendered with the Agg backend and never touch pyplot's global state, so this module
works headless and leaves the user's interactive backend alone.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt
from matplotlib import colormaps
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import PathCollection, PolyCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Circle, FancyArrow, Patch, Polygon
from matplotlib.path import Path

from mazesim._figures import save_figure
from mazesim._sizes import number_array
from mazesim.errors import InvalidArgumentError
from mazesim.render.topdown import _number, _pair

if TYPE_CHECKING:
    from matplotlib.artist import Artist
    from matplotlib.axes import Axes

    from mazesim._core import World

__all__ = [
    "plot_world",
    "save_trajectory_png",
    "trajectory_legend",
    "world_figure",
    "world_legend_handles",
]

WALL_COLOR = "#8c3b1f"
GOAL_COLOR = "#2ca02c"
START_COLOR = "#1f77b4"
PATH_COLOR = "#d62728"
CHECKPOINT_COLOR = "#ffd92f"
COLLISION_COLOR = "#000000"


def _rectangle_corners(
    center_x: float, center_y: float, size_x: float, size_y: float, yaw: float
) -> npt.NDArray[np.float64]:
    """Corners (4, 2) of a box of the given size, centred and rotated by ``yaw``."""
    half = (
        np.array([[-size_x, -size_y], [size_x, -size_y], [size_x, size_y], [-size_x, size_y]]) * 0.5
    )
    cos_yaw, sin_yaw = math.cos(yaw), math.sin(yaw)
    rotation = np.array([[cos_yaw, -sin_yaw], [sin_yaw, cos_yaw]])
    return half @ rotation.T + np.array([center_x, center_y])


def _capsule_outline(
    a: tuple[float, float], b: tuple[float, float], radius: float, arc_points: int = 12
) -> npt.NDArray[np.float64]:
    """Outline (M, 2) of the points within ``radius`` of the segment a-b."""
    start_x, start_y = a
    end_x, end_y = b
    heading = math.atan2(end_y - start_y, end_x - start_x)
    # Around b from the right side to the left side, then around a back to the right side.
    arc = np.linspace(-math.pi / 2, math.pi / 2, arc_points)
    around_b = np.column_stack(
        [end_x + radius * np.cos(heading + arc), end_y + radius * np.sin(heading + arc)]
    )
    around_a = np.column_stack(
        [
            start_x + radius * np.cos(heading + math.pi + arc),
            start_y + radius * np.sin(heading + math.pi + arc),
        ]
    )
    return np.vstack([around_b, around_a])


def _grey(reflectance: float) -> tuple[float, float, float]:
    """The RGB grey that shows a reflectance factor (clamped to [0, 1])."""
    level = min(max(float(reflectance), 0.0), 1.0)
    return (level, level, level)


def _background_reflectance(world: World) -> float:
    """The reflectance of the bare floor, sampled well outside everything in the world."""
    xmin, ymin, _, _ = world.bounds
    return float(world.floor_reflectance(xmin - 1.0, ymin - 1.0))


def _paint_path(region: dict[str, object]) -> Path | None:
    """The outline of one paint region, or None for a shape this module does not know."""
    shape = region["shape"]
    if shape == "rect":
        center_x, center_y = _pair(region["center"])
        size_x, size_y = _pair(region["size"])
        yaw = _number(region.get("yaw", 0.0))
        corners = _rectangle_corners(center_x, center_y, size_x, size_y, yaw)
        return Path(np.vstack([corners, corners[:1]]), closed=True)
    if shape == "circle":
        return Path.circle(_pair(region["center"]), _number(region["radius"]))
    if shape == "capsule":
        outline = _capsule_outline(
            _pair(region["a"]), _pair(region["b"]), _number(region["radius"])
        )
        return Path(np.vstack([outline, outline[:1]]), closed=True)
    return None


def _draw_paint(ax: Axes, world: World) -> None:
    """Draws the floor paint as one collection of outlines: a floor texture read as paint gives
    tens of thousands of regions, which matplotlib draws in seconds so, and in most of a minute
    as as many patches. Later regions cover earlier ones (the collection's order), all below
    walls and markers."""
    paths: list[Path] = []
    greys: list[tuple[float, float, float]] = []
    for region in world.paint_regions():
        path = _paint_path(region)
        if path is not None:
            paths.append(path)
            greys.append(_grey(_number(region["reflectance"])))
    if paths:
        ax.add_collection(
            PathCollection(paths, facecolors=greys, edgecolors="none", linewidths=1.0, zorder=1.0)
        )


def _draw_walls(ax: Axes, world: World) -> None:
    boxes = np.asarray(world.wall_boxes(), dtype=np.float64).reshape(-1, 6)
    if len(boxes) == 0:
        return
    outlines = [_rectangle_corners(*box[:5]) for box in boxes]
    ax.add_collection(
        PolyCollection(
            outlines, facecolors=WALL_COLOR, edgecolors=WALL_COLOR, linewidths=0.3, zorder=3
        )
    )


def _draw_markers(ax: Axes, world: World) -> None:
    for checkpoint in world.checkpoints():
        center_x, center_y = _pair(checkpoint["center"])
        yaw = _number(checkpoint["yaw"])
        # The label sits just past the code in its reading direction.
        label_x = center_x + 0.075 * math.cos(yaw)
        label_y = center_y + 0.075 * math.sin(yaw)
        ax.text(
            label_x,
            label_y,
            str(checkpoint["id"]),
            ha="center",
            va="center",
            fontsize=7,
            color="black",
            zorder=5,
            bbox={
                "boxstyle": "circle,pad=0.2",
                "facecolor": CHECKPOINT_COLOR,
                "edgecolor": "black",
                "lw": 0.5,
            },
        )
    goal = world.goal
    if goal is not None:
        goal_x, goal_y, radius = goal
        ax.add_patch(Circle((goal_x, goal_y), radius, facecolor=GOAL_COLOR, alpha=0.45, zorder=4))
        ax.text(goal_x, goal_y, "GOAL", ha="center", va="center", fontsize=7, zorder=5)
    start_x, start_y, start_yaw = world.start
    ax.add_patch(
        Circle((start_x, start_y), 0.037, facecolor="none", edgecolor=START_COLOR, lw=1.0, zorder=6)
    )
    ax.add_patch(
        FancyArrow(
            start_x,
            start_y,
            0.05 * math.cos(start_yaw),
            0.05 * math.sin(start_yaw),
            width=0.006,
            head_width=0.02,
            head_length=0.015,
            length_includes_head=True,
            color=START_COLOR,
            zorder=6,
        )
    )


def world_legend_handles(world: World) -> list[Artist]:
    """Legend entries of what :func:`plot_world` draws of ``world``: walls, floor paint,
    checkpoints, start and goal (those the world has)."""
    handles: list[Artist] = [Patch(facecolor=WALL_COLOR, label="walls")]
    if world.paint_regions():
        handles.append(
            Patch(facecolor=_grey(0.2), edgecolor="grey", label="floor paint (grey = reflectance)")
        )
    if world.checkpoints():
        handles.append(
            Line2D(
                [],
                [],
                marker="o",
                linestyle="none",
                markersize=8,
                markerfacecolor=CHECKPOINT_COLOR,
                markeredgecolor="black",
                label="checkpoint (its id)",
            )
        )
    handles.append(
        Line2D(
            [],
            [],
            marker=r"$\rightarrow$",
            linestyle="none",
            markersize=10,
            color=START_COLOR,
            label="start pose",
        )
    )
    if world.goal is not None:
        handles.append(Patch(facecolor=GOAL_COLOR, alpha=0.45, label="goal"))
    return handles


def trajectory_legend(
    ax: Axes, world: World, extra: Sequence[Artist] = (), outside: bool = True
) -> None:
    """Puts the legend of a trajectory picture: the world's markers, then ``extra`` entries
    (paths, their ends, collisions, decisions)."""
    handles = [*world_legend_handles(world), *extra]
    if outside:
        ax.legend(
            handles=handles,
            loc="upper left",
            bbox_to_anchor=(1.02, 1.0),
            fontsize=7,
            frameon=False,
        )
    else:
        ax.legend(handles=handles, loc="best", fontsize=7)


def plot_world(ax: Axes, world: World) -> None:
    """Draws a world onto matplotlib axes.

    The bare floor and floor paint are grey levels equal to their reflectance, walls are solid
    boxes, barcode checkpoints carry their id just past the code in its reading direction, the
    goal is a green disc and the start pose a circle of the e-puck's size with an arrow.

    Args:
        ax: The axes to draw on; their aspect is set to equal and their limits to the world.
        world: The world to draw.
    """
    xmin, ymin, xmax, ymax = world.bounds
    margin = 0.03 * max(xmax - xmin, ymax - ymin, 1e-3)
    ax.set_facecolor(_grey(_background_reflectance(world)))
    _draw_paint(ax, world)
    _draw_walls(ax, world)
    _draw_markers(ax, world)
    ax.set_xlim(xmin - margin, xmax + margin)
    ax.set_ylim(ymin - margin, ymax + margin)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")


#: The least span a trajectory picture shows, metres (a world without walls has no extent).
MIN_PICTURE_SPAN = 0.2
BODY_COLOR = "#b5651d"


def trajectory_limits(
    world: World, xs: npt.ArrayLike, ys: npt.ArrayLike
) -> tuple[float, float, float, float] | None:
    """The extent of a trajectory picture, (xmin, xmax, ymin, ymax): the world's walls and the
    whole path, at least :data:`MIN_PICTURE_SPAN` across (a world without walls is framed by the
    path alone); None without a finite point."""
    path_x = number_array(xs, "xs", nan_means="a gap in the path").ravel()
    path_y = number_array(ys, "ys", nan_means="a gap in the path").ravel()
    finite = np.isfinite(path_x) & np.isfinite(path_y)
    if not finite.any():
        return None
    xmin, ymin, xmax, ymax = world.bounds
    if not world.wall_boxes().size:  # no walls: the bounds say nothing of the scene
        xmin, ymin, xmax, ymax = math.inf, math.inf, -math.inf, -math.inf
    xmin, xmax = min(xmin, path_x[finite].min()), max(xmax, path_x[finite].max())
    ymin, ymax = min(ymin, path_y[finite].min()), max(ymax, path_y[finite].max())
    span = max(xmax - xmin, ymax - ymin, MIN_PICTURE_SPAN)
    cx, cy = (xmin + xmax) / 2.0, (ymin + ymax) / 2.0
    half_x = max(xmax - xmin, MIN_PICTURE_SPAN) / 2.0 + 0.03 * span
    half_y = max(ymax - ymin, MIN_PICTURE_SPAN) / 2.0 + 0.03 * span
    return (float(cx - half_x), float(cx + half_x), float(cy - half_y), float(cy + half_y))


def draw_bodies(ax: Axes, world: World) -> list[Artist]:
    """Outlines the world's movable bodies at their start poses; returns their legend entry
    (none without bodies)."""
    bodies = world.bodies()
    for body in bodies:
        cx, cy = _pair(body["center"])
        if body.get("shape") == "circle":
            radius = _number(body["radius"])
            ax.add_patch(Circle((cx, cy), radius, fill=False, edgecolor=BODY_COLOR, zorder=6))
            continue
        sx, sy = (v / 2.0 for v in _pair(body["size"]))
        yaw = _number(body.get("yaw", 0.0))
        c, s = math.cos(yaw), math.sin(yaw)
        corners = [
            (cx + c * dx - s * dy, cy + s * dx + c * dy)
            for dx, dy in ((sx, sy), (-sx, sy), (-sx, -sy), (sx, -sy))
        ]
        ax.add_patch(Polygon(corners, closed=True, fill=False, edgecolor=BODY_COLOR, zorder=6))
    if not bodies:
        return []
    return [Patch(facecolor="none", edgecolor=BODY_COLOR, label="movable body (start)")]


def world_figure(
    world: World, width: float, heights: tuple[float, float], margin: float
) -> tuple[Figure, Axes]:
    """A figure for a picture of ``world``, with the world drawn on its axes.

    Args:
        world: The world.
        width: The figure's width in inches.
        heights: The least and the most height in inches.
        margin: Inches added to the height the world's aspect asks for (titles, legends).
    """
    xmin, ymin, xmax, ymax = world.bounds
    aspect = (ymax - ymin) / max(xmax - xmin, 1e-3)
    height = max(heights[0], min(heights[1], 6.0 * aspect + margin))
    figure = Figure(figsize=(width, height), dpi=120)
    FigureCanvasAgg(figure)
    ax = figure.add_subplot()
    plot_world(ax, world)
    return figure, ax


def save_trajectory_png(
    world: World,
    xs: npt.ArrayLike,
    ys: npt.ArrayLike,
    path: str | os.PathLike[str],
    title: str | None = None,
    collisions: npt.ArrayLike | None = None,
) -> None:
    """Draws a world with a robot's path on top and writes it as a PNG file (or PDF or SVG, by
    the suffix of ``path``).

    The legend names the walls, paint, checkpoints, start pose and goal, and the path, its start
    and end and the places where the robot touched a wall.

    The file is written atomically: to a temporary file in the same folder, renamed over ``path``.

    Args:
        world: The world the robot drove in.
        xs: The x coordinates of the path in metres.
        ys: The y coordinates of the path in metres, as many as ``xs``.
        path: The file to write (``.png``, ``.pdf``, ``.svg``, or no suffix: PNG); its folder
            must exist.
        title: A title above the picture; by default the world's name.
        collisions: (K, 2) positions where the robot touched a wall, marked with crosses.

    Raises:
        InvalidArgumentError: ``xs`` and ``ys`` differ in length.
    """
    path_x = number_array(xs, "xs", nan_means="a gap in the path").ravel()
    path_y = number_array(ys, "ys", nan_means="a gap in the path").ravel()
    if path_x.shape != path_y.shape:
        raise InvalidArgumentError(
            f"a trajectory needs as many x as y coordinates; found {path_x.size} and {path_y.size}"
        )
    figure, ax = world_figure(world, 8.0, (3.0, 9.0), 0.6)
    extra: list[Artist] = draw_bodies(ax, world)
    if path_x.size:
        limits = trajectory_limits(world, path_x, path_y)
        if limits is not None:
            ax.set_xlim(limits[0], limits[1])
            ax.set_ylim(limits[2], limits[3])
        extra += ax.plot(path_x, path_y, color=PATH_COLOR, linewidth=1.2, zorder=7, label="path")
        extra += ax.plot(
            path_x[:1],
            path_y[:1],
            marker="s",
            markersize=5,
            linestyle="none",
            color=START_COLOR,
            zorder=8,
            label="path start",
        )
        extra += ax.plot(
            path_x[-1:],
            path_y[-1:],
            marker="o",
            markersize=5,
            linestyle="none",
            color=PATH_COLOR,
            zorder=8,
            label="path end",
        )
    if collisions is not None:
        contacts = number_array(collisions, "collisions").reshape(-1, 2)
        if len(contacts):
            extra += ax.plot(
                contacts[:, 0],
                contacts[:, 1],
                marker="x",
                markersize=5,
                linestyle="none",
                color=COLLISION_COLOR,
                zorder=9,
                label=f"touching a wall ({len(contacts)} steps)",
            )
    trajectory_legend(ax, world, extra)
    ax.set_title(world.name if title is None else title)
    save_figure(figure, path)


def save_robot_paths_png(
    world: World,
    paths: Sequence[tuple[str, npt.ArrayLike, npt.ArrayLike]],
    path: str | os.PathLike[str],
    title: str | None = None,
) -> None:
    """Draws a world with several robots' paths, one colour each, and writes it as a PNG file
    (or PDF or SVG, by the suffix of ``path``), atomically.

    Args:
        world: The world the robots drove in.
        paths: Each robot's name, x and y coordinates (metres).
        path: The file to write (``.png``, ``.pdf``, ``.svg``, or no suffix: PNG); its folder
            must exist.
        title: A title above the picture; by default the world's name.
    """
    figure, ax = world_figure(world, 8.0, (3.0, 9.0), 0.6)
    extra: list[Artist] = draw_bodies(ax, world)
    every_x = np.concatenate([np.asarray(xs, dtype=np.float64).ravel() for _, xs, _ in paths])
    every_y = np.concatenate([np.asarray(ys, dtype=np.float64).ravel() for _, _, ys in paths])
    limits = trajectory_limits(world, every_x, every_y) if every_x.size else None
    if limits is not None:
        ax.set_xlim(limits[0], limits[1])
        ax.set_ylim(limits[2], limits[3])
    colours = colormaps["tab10"]
    for number, (name, xs, ys) in enumerate(paths):
        path_x = np.asarray(xs, dtype=np.float64).ravel()
        path_y = np.asarray(ys, dtype=np.float64).ravel()
        colour = colours(number % 10)
        extra += ax.plot(path_x, path_y, color=colour, linewidth=1.2, zorder=7, label=name)
        ax.plot(path_x[:1], path_y[:1], marker="s", markersize=4, color=colour, zorder=8)
        ax.plot(path_x[-1:], path_y[-1:], marker="o", markersize=4, color=colour, zorder=8)
    trajectory_legend(ax, world, extra)
    ax.set_title(world.name if title is None else title)
    save_figure(figure, path)
