"""Importing Webots ``.wbt`` worlds as mazesim worlds.

The reading and the conversion happen in the compiled core (``mazesim_core::wbt``): every
collision shape of the world that meets the e-puck's height becomes a wall, the e-puck's pose
becomes the start, ``WorldInfo.basicTimeStep`` the time step. The report says what was imported
and what was not (unknown PROTOs, meshes, tilted or dynamic objects), in metres and radians,
world frame, z up.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import Any, Literal, TypedDict, cast

from mazesim import _core
from mazesim._core import World

__all__ = [
    "BoxObstacle",
    "CircleObstacle",
    "ImportReport",
    "RobotPose",
    "import_wbt",
    "import_wbt_text",
    "robot_warnings",
]

#: Robot node types that mazesim simulates as they are.
E_PUCK_MODELS = ("E-puck", "e-puck", "e-puck2", "E-puck2")


class BoxObstacle(TypedDict):
    """A box seen from above: centre [x, y], size [sx, sy] along its own axes, yaw."""

    kind: Literal["box"]
    center: list[float]
    size: list[float]
    yaw: float


class CircleObstacle(TypedDict):
    """An upright cylinder, capsule or sphere seen from above (a ring of walls in the world)."""

    kind: Literal["circle"]
    center: list[float]
    radius: float


class RobotPose(TypedDict):
    """The e-puck's start pose."""

    x: float
    y: float
    yaw: float


class ImportReport(TypedDict):
    """What ``mazesim import-wbt --json`` prints."""

    obstacles: list[BoxObstacle | CircleObstacle]
    robot: RobotPose | None
    basic_time_step_ms: float
    warnings: list[str]


def import_wbt(path: str | os.PathLike[str]) -> tuple[World, ImportReport]:
    """Imports a Webots world file.

    Args:
        path: A ``.wbt`` file of any Webots version from V8.5 to R2025a.

    Returns:
        The mazesim world (named after the file) and the import report.

    Raises:
        WorldFormatError: The file is not a readable Webots world; ``line`` and ``column`` say
            where.
        MazesimIOError: The file cannot be read.
    """
    world, report = _core.import_wbt(os.fspath(path))
    return world, cast(ImportReport, report)


def import_wbt_text(text: str, source: str = "<string>") -> tuple[World, ImportReport]:
    """Imports the text of a Webots world file.

    Args:
        text: The file's text.
        source: A name for error messages (and for the world, from its file stem).

    Returns:
        The mazesim world and the import report.

    Raises:
        WorldFormatError: The text is not a readable Webots world.
    """
    world, report = _core.import_wbt_text(text, source)
    return world, cast(ImportReport, report)


def robot_warnings(report: Mapping[str, Any]) -> list[str]:
    """Warnings about the world's robot that the report does not already give.

    Args:
        report: An import report; its ``robot_model`` (when present) names the robot's type.

    Returns:
        A warning when the robot is not an e-puck (it then runs as the report's
        ``robot_profile``, by default the e-puck), unless a report warning already names it.
    """
    model = report.get("robot_model")
    if not model or model in E_PUCK_MODELS:
        return []
    if any(str(model) in str(warning) for warning in report.get("warnings", [])):
        return []
    profile = report.get("robot_profile") or "e-puck"
    return [f"the world's robot is a {model}, not an e-puck: mazesim runs it as the {profile}"]
