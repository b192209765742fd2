"""A supervisor's ``exportImage``: the view of the running world written as a PNG or JPEG file.

Webots saves "the current image of Webots main window" (reference manual, Supervisor,
``wb_supervisor_export_image``), through a temporary file renamed to the target, so that a
webcam page never reads half a file. A headless run has no 3D window; its view is the top-down
frame that ``--video`` draws (:class:`mazesim.render.topdown.TopDownRenderer`): the walls where
they are now (moved, imported, removed by a supervisor), the robot with its rays, its path so
far and, in a world run, the other robots where they are (a supervisor without a body, a plain
``Robot``, shows only those). The file's extension chooses the
format (``.png``; ``.jpg`` or ``.jpeg`` at ``quality``); any other is refused with an error on
stderr, as Webots refuses it, and nothing is written.
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim.errors import _shown

__all__ = ["IMAGE_FORMATS", "VIEW_SIZE", "export_view", "view_image"]

#: The formats an exported image is written in, by file extension (lower case).
IMAGE_FORMATS = {".png": "PNG", ".jpg": "JPEG", ".jpeg": "JPEG"}
#: Width and height of the exported view in pixels: a ``--video`` frame's.
VIEW_SIZE = 400


def _walls_now(simulation: Any) -> npt.NDArray[np.float64]:
    """The walls as they stand now, as (N, 5) boxes: centre x, y, size x, y, yaw."""
    from mazesim.webots.walls_now import WallsNow

    walls = WallsNow(simulation).walls()
    yaw = np.arctan2(walls.sin, walls.cos)
    return np.column_stack((walls.center, 2.0 * walls.half, yaw)).reshape(-1, 5)


def _has_body(simulation: Any, index: int) -> bool:
    """Whether robot ``index`` of the world has a body the frame draws (an e-puck's)."""
    robots = simulation.report.get("robots") or []
    return index >= len(robots) or robots[index].get("profile") is not None


def _other_robots(simulation: Any) -> list[Any]:
    """The world run's other robots that have a body, where they are now, each as the frame
    draws it, without a trail (none in a run of one robot)."""
    if simulation.fleet is None:
        return []
    no_trail = np.empty((0, 2))
    return [
        ((float(pose[0]), float(pose[1]), float(pose[2])), False, no_trail)
        for index, pose in enumerate(simulation.fleet.poses())
        if index != simulation.robot_index and pose is not None
        if _has_body(simulation, index)
    ]


def view_image(simulation: Any) -> npt.NDArray[np.uint8]:
    """The view of ``simulation``'s world now: a (400, 400, 3) uint8 top-down frame."""
    from mazesim._core import RobotProfile
    from mazesim.render.topdown import TopDownRenderer

    simulator = simulation.simulator
    profile = getattr(simulator, "robot", None) or RobotProfile.builtin("e-puck")
    renderer = TopDownRenderer(
        simulation.world,
        profile,
        (VIEW_SIZE, VIEW_SIZE),
        profile.distance_sensor_range,
        walls=_walls_now(simulation),
    )
    others = _other_robots(simulation)
    bodiless = simulation.fleet is not None and not _has_body(simulation, simulation.robot_index)
    if bodiless and others:
        # A supervisor without a body (a plain Robot): the view shows the robots there are.
        pose, _, _ = others.pop(0)
        return renderer.frame(pose, others=others)
    x, y, yaw = (float(v) for v in simulator.pose)
    return renderer.frame(
        (x, y, yaw),
        bool(simulator.colliding),
        trail=np.column_stack((simulation.xs, simulation.ys)),
        others=others,
    )


def export_view(simulation: Any, filename: str, quality: int) -> str | None:
    """Writes the view of ``simulation``'s world to ``filename`` (atomically), in the format its
    extension names; None once written, else Webots' kind of error (nothing is written)."""
    from PIL import Image

    from mazesim._atomic import atomic_file
    from mazesim.errors import MazesimError

    function = "wb_supervisor_export_image()"
    if not filename:
        return f"Error: {function} called with NULL or empty 'filename' argument."
    if not (isinstance(quality, int) and 1 <= quality <= 100):
        return f"Error: {function}: 'quality' argument ({quality}) must be between 1 and 100."
    extension = os.path.splitext(filename)[1].lower()
    if extension not in IMAGE_FORMATS:
        known = ", ".join(f"'{e}'" for e in IMAGE_FORMATS)
        return (
            f"Error: {function}: unsupported image format {_shown(extension or '(none)')} of "
            f"{filename}: the target file should have one of the extensions {known}."
        )
    image = Image.fromarray(view_image(simulation))
    options = {"quality": quality} if IMAGE_FORMATS[extension] == "JPEG" else {}
    try:
        with atomic_file(filename) as handle:
            image.save(handle, IMAGE_FORMATS[extension], **options)
    except (OSError, MazesimError) as failed:
        return f"Error: {function}: cannot write {filename}: {failed}."
    return None
