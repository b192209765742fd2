"""The self-contained HTML replay: one file with the run, the viewer's script and its style.

:func:`write_html` turns a :class:`RecordedRun` into a page that needs no server and no network:
the world's geometry and the run's frames go in a JSON block, the viewer (``viewer/replay.js``
and ``viewer/replay.css``, package data) inline beside it. The page draws walls, floor paint,
checkpoints with their ids and reading direction, the maze grid, start and goal; the robot with
its heading, its trail and its sensor rays coloured by reading; a panel of the readings of the
step shown (raw and Table 4.1 levels), the action, the running sub-task and the higher level's
decisions with the value of each sub-task; a timeline of sub-tasks, barcode reads and decisions;
and play/pause, speed, a time slider, step buttons, keyboard shortcuts and an episode selector.
A run of several robots draws each robot, its trail and its rays in a colour of its own, with a
legend and a row per robot in the panel; the sensor table shows the robot chosen there.
"""

from __future__ import annotations

import html
import json
import os
from importlib import resources
from typing import Any

import mazesim
from mazesim._atomic import atomic_file
from mazesim._core import RobotProfile, World
from mazesim.actions import ACTIONS
from mazesim.replay.run import RecordedRun

__all__ = ["replay_html", "scene_of", "world_scene", "write_html"]


def _viewer_file(name: str) -> str:
    return resources.files("mazesim.replay").joinpath("viewer", name).read_text(encoding="utf-8")


def _rounded(values: Any, digits: int = 4) -> Any:
    """Numbers (in nested lists and tuples) rounded to ``digits`` decimals."""
    if isinstance(values, (list, tuple)):
        return [_rounded(value, digits) for value in values]
    if isinstance(values, float):
        return round(values, digits)
    return values


def world_scene(world: World) -> dict[str, Any]:
    """What the viewer draws of a world: bounds, floor, paint, walls, checkpoints, grid, start
    and goal, in metres and radians."""
    paint = []
    for region in world.paint_regions():
        paint.append({key: _rounded(value) for key, value in region.items()})
    checkpoints = []
    for checkpoint in world.checkpoints():
        x, y = (float(v) for v in checkpoint["center"])  # type: ignore[attr-defined]
        checkpoints.append(
            {
                "id": checkpoint["id"],
                "code": checkpoint["code"],
                "x": round(x, 4),
                "y": round(y, 4),
                "yaw": round(float(checkpoint["yaw"]), 4),  # type: ignore[arg-type]
                "width": round(float(checkpoint["width"]), 4),  # type: ignore[arg-type]
            }
        )
    grid = None
    maze = world.cell_maze()
    if maze is not None:
        origin = maze["origin"]
        grid = {
            "rows": maze["rows"],
            "cols": maze["cols"],
            "cell": maze["cell_size"],
            "origin": _rounded(list(origin)),  # type: ignore[call-overload]
        }
    return {
        "name": world.name,
        "bounds": _rounded(list(world.bounds)),
        "floor": world.floor_background,
        "paint": paint,
        "walls": _rounded(world.wall_boxes()[:, :5].tolist()),
        "checkpoints": checkpoints,
        "grid": grid,
        "start": _rounded(list(world.start)),
        "goal": None if world.goal is None else _rounded(list(world.goal)),
    }


def _robot_scene(profile: RobotProfile) -> dict[str, Any]:
    """What the viewer draws of a robot profile: body, sensors and their readings' names."""
    return {
        "name": profile.name,
        "radius": profile.body_radius,
        "sensors": _rounded(profile.distance_sensor_poses().tolist()),
        "names": [*profile.distance_sensor_names, *profile.ground_sensor_names],
        "distance_count": len(profile.distance_sensor_names),
        "unit": profile.distance_sensor_unit,
        "distance_max": profile.distance_sensor_max,
    }


def scene_of(run: RecordedRun) -> dict[str, Any]:
    """The JSON the viewer reads: the world, the robot, the action table and the run (without
    the world's TOML text, which the page does not need); for a run of several robots also
    ``robots``, each robot's name and profile, robot 0 first."""
    values = run.as_json()
    values["world"] = {"name": run.world.name}
    scene: dict[str, Any] = {
        "world": world_scene(run.world),
        "robot": _robot_scene(run.robot_profile),
        "actions": {code: action.description for code, action in ACTIONS.items()},
        "run": values,
    }
    if run.robots:
        scene["robots"] = [
            {**_robot_scene(robot.robot_profile), "robot_name": robot.name} for robot in run.robots
        ]
    return scene


def replay_html(run: RecordedRun, title: str | None = None) -> str:
    """The replay page of a run, as text."""
    heading = title or f"{run.world.name}: {run.controller}, seed {run.seed}"
    scene = json.dumps(scene_of(run), separators=(",", ":"))
    # Inside <script>, "</script" would end the block early and "<!--<script" change how the
    # rest is parsed: no "<" is left in the JSON, whose "\u003c" reads the same.
    scene = scene.replace("<", "\\u003c")
    page = _viewer_file("replay.html")
    for marker, value in (
        ("__STYLE__", _viewer_file("replay.css")),
        ("__SCRIPT__", _viewer_file("replay.js")),
        ("__TITLE__", html.escape(heading)),
        ("__VERSION__", html.escape(mazesim.__version__)),
        ("__SCENE__", scene),
    ):
        page = page.replace(marker, value)
    return page


def write_html(run: RecordedRun, path: str | os.PathLike[str], title: str | None = None) -> None:
    """Writes the replay page of a run (atomically)."""
    with atomic_file(path) as handle:
        handle.write(replay_html(run, title).encode("utf-8"))
