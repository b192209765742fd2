"""A robot node's own ``DistanceSensor`` nodes as its robot profile.

A plain ``Robot`` (or Webots 6-7 ``DifferentialWheels``) e-puck saved expanded lists its own
``DistanceSensor`` nodes ps0..ps7 (gs0..gs2), each with its own ``lookupTable`` (Webots'
default one where the node has no such field) and its own pose: Webots reads each sensor
through its table, from where it sits. :func:`own_sensors` turns the tables and poses that
differ from the built-in profile's into a copy of that profile, for a run of one robot
(:mod:`mazesim.webots.simulation`) and for each robot of a world of several
(:mod:`mazesim.webots.lockstep`) alike; a robot whose sensors are all the profile's is
simulated by the profile's name, as ever.
"""

from __future__ import annotations

import copy
import json
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from mazesim._core import RobotProfile
from mazesim._toml import load_toml
from mazesim.errors import MazesimError
from mazesim.webots.scene import Row, Scene

__all__ = ["OwnSensors", "own_sensors"]

#: How much of a refused ``lookupTable`` field a warning quotes.
QUOTED_CHARACTERS = 80
#: How far (m) a sensor of the world may sit from the profile's and still be the profile's (a
#: world writes the E-puck's positions rounded to the millimetre).
SAME_POSITION_M = 1e-3
#: How far (rad) a sensor's heading may turn from the profile's and still be the profile's (a
#: world writes ps0's -0.3008 as -0.3, ps6's 0.7992 as 0.8).
SAME_HEADING_RAD = 0.01
#: A distance sensor whose ray rises or falls more than this (rad) from the floor's plane keeps
#: the profile's pose: mazesim's rays are level.
STEEPEST_RAY_RAD = math.pi / 4


@dataclass(frozen=True)
class OwnSensors:
    """What a robot node's own sensors make of its built-in profile.

    Attributes:
        tables: The world's lookup tables the robot's sensors read through, by sensor name:
            those that differ from the profile's and that the profile format takes.
        poses: The world's poses of the robot's sensors, by sensor name, where they differ from
            the profile's: x, y (m) and, for a distance sensor, the heading of its ray (rad).
        profile: The built-in profile with those tables and poses, or None when every sensor
            is the profile's (the profile's name then simulates the robot).
        warnings: What of the robot node's sensors is not used, and why (those sensors read
            through the profile's tables), one line per reason.
    """

    tables: dict[str, list[Row]] = field(default_factory=dict)
    poses: dict[str, tuple[float, ...]] = field(default_factory=dict)
    profile: RobotProfile | None = None
    warnings: list[str] = field(default_factory=list)


def own_sensors(name: str, scene: Scene | None) -> OwnSensors:
    """The sensors of a robot node (its ``scene``) simulated by built-in profile ``name``.

    Each of the profile's sensors whose ``DistanceSensor`` node the robot node lists with
    another table than the profile's reads through the node's table; a table the profile format
    refuses, or a ``lookupTable`` field not of rows of 3 numbers, keeps the profile's, with a
    warning naming the sensors and what was found. A sensor node that the robot node holds
    itself, placed or turned otherwise than the profile's sensor, casts its ray from the node's
    pose (see :func:`_moved_sensors`).
    """
    if scene is None or not (scene.sensor_tables or scene.malformed_tables):
        return OwnSensors()
    layout = _profile_layout(name)
    models = layout.get("models", {})
    tables: dict[str, list[Row]] = {}
    # The refused sensors by the reason.
    refused: dict[str, list[str]] = {}
    for sensor in [*layout.get("distance_sensors", []), *layout.get("ground_sensors", [])]:
        if (found := scene.malformed_tables.get(sensor["name"])) is not None:
            refused.setdefault(_not_rows_of_three(found), []).append(repr(sensor["name"]))
            continue
        table = scene.sensor_tables.get(sensor["name"])
        if table is None or [tuple(row) for row in models[sensor["model"]]["table"]] == table:
            continue
        try:
            _profile_with(layout, {sensor["name"]: table})
        except MazesimError as error:
            # The format's reason, without the place in the generated profile text.
            reason = str(error).split("`: ", 1)[-1]
            refused.setdefault(reason, []).append(repr(sensor["name"]))
            continue
        tables[sensor["name"]] = table
    warnings = [
        f"the world's lookupTable of DistanceSensor {', '.join(names)} was not used (read "
        f"through the {name} profile's table instead): {reason}"
        for reason, names in refused.items()
    ]
    poses = _moved_sensors(layout, scene)
    profile = _profile_with(layout, tables, poses) if tables or poses else None
    return OwnSensors(tables, poses, profile, warnings)


def _moved_sensors(layout: Mapping[str, Any], scene: Scene) -> dict[str, tuple[float, ...]]:
    """The world's pose of each sensor of a parsed profile file whose node the robot node holds
    itself (``Scene.sensor_poses``) more than :data:`SAME_POSITION_M` or
    :data:`SAME_HEADING_RAD` from the profile's: x, y and, for a distance sensor, its heading.
    A distance sensor whose ray is steeper than :data:`STEEPEST_RAY_RAD` keeps the profile's."""
    moved: dict[str, tuple[float, ...]] = {}
    for sensor in layout.get("distance_sensors", []):
        pose = scene.sensor_poses.get(sensor["name"])
        if pose is None or abs(pose[3]) > STEEPEST_RAY_RAD:
            continue
        x, y, heading, _ = pose
        turned = abs(math.remainder(heading - float(sensor["heading"]), math.tau))
        if _moved(sensor["position"], x, y) or turned > SAME_HEADING_RAD:
            moved[sensor["name"]] = (x, y, heading)
    for sensor in layout.get("ground_sensors", []):
        pose = scene.sensor_poses.get(sensor["name"])
        if pose is not None and _moved(sensor["position"], pose[0], pose[1]):
            moved[sensor["name"]] = (pose[0], pose[1])
    return moved


def _moved(position: list[float], x: float, y: float) -> bool:
    """Whether (x, y) is more than :data:`SAME_POSITION_M` from a profile's ``position``."""
    return math.hypot(x - float(position[0]), y - float(position[1])) > SAME_POSITION_M


def _not_rows_of_three(found: str) -> str:
    """Why a ``lookupTable`` field's text ``found`` is not used."""
    numbers = found.replace(",", " ").split()
    quoted = found if len(found) <= QUOTED_CHARACTERS else found[:QUOTED_CHARACTERS] + " ..."
    return (
        f"expected rows of 3 numbers (distance, value, noise), found [{quoted}] "
        f"({len(numbers)} value{'' if len(numbers) == 1 else 's'})"
    )


def _profile_layout(name: str) -> dict[str, Any]:
    """The built-in profile ``name`` as its parsed profile file."""
    return load_toml(RobotProfile.builtin(name).to_toml(), f"the {name} profile")


def _profile_with(
    layout: dict[str, Any],
    tables: Mapping[str, list[Row]],
    poses: Mapping[str, tuple[float, ...]] | None = None,
) -> RobotProfile:
    """The profile of a parsed profile file, each sensor named in ``tables`` reading through a
    copy of its model with that table (one copy per model and table: ``world-table-N``), each
    named in ``poses`` at that position (and heading)."""
    layout = copy.deepcopy(layout)
    models = layout.setdefault("models", {})
    copies: dict[tuple[str, tuple[Row, ...]], str] = {}
    for sensor in [*layout.get("distance_sensors", []), *layout.get("ground_sensors", [])]:
        if (pose := (poses or {}).get(sensor["name"])) is not None:
            sensor["position"] = [pose[0], pose[1]]
            if len(pose) > 2:
                sensor["heading"] = pose[2]
        table = tables.get(sensor["name"])
        if table is None:
            continue
        key = (sensor["model"], tuple(table))
        if key not in copies:
            copies[key] = f"world-table-{len(copies)}"
            rows = [list(row) for row in table]
            models[copies[key]] = {**models[sensor["model"]], "table": rows}
        sensor["model"] = copies[key]
    return RobotProfile.from_toml(_toml_text(layout), "the world's sensors")


def _toml_text(layout: Mapping[str, Any], path: str = "") -> str:
    """TOML text of a parsed profile file: keys of values, then tables, then arrays of tables."""
    lines = [
        f"{key} = {_toml_value(value)}"
        for key, value in layout.items()
        if not isinstance(value, dict) and not _is_table_array(value)
    ]
    for key, value in layout.items():
        inner = f"{path}.{key}" if path else key
        if isinstance(value, dict):
            lines.append(f"\n[{inner}]\n{_toml_text(value, inner)}")
        elif _is_table_array(value):
            lines.extend(f"\n[[{inner}]]\n{_toml_text(item, inner)}" for item in value)
    return "\n".join(lines)


def _is_table_array(value: Any) -> bool:
    return isinstance(value, list) and bool(value) and all(isinstance(v, dict) for v in value)


def _toml_value(value: Any) -> str:
    """One TOML value: a string, boolean, number or array of them."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(item) for item in value) + "]"
    return repr(value)
