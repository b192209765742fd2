"""A robot node's own ``DistanceSensor`` nodes as its robot profile.

A plain ``Robot`` (or Webots 6-7 ``DifferentialWheels``) e-puck saved expanded lists its own
``DistanceSensor`` nodes ps0..ps7 (gs0..gs2), each with its own ``lookupTable`` (Webots'
default one where the node has no such field), its own pose and its own ``type``: Webots reads
each sensor through its table, from where it sits, along its ray as its rotation tilts it, and
only an ``infra-red`` one by the colour of what its ray meets. An ``E-puck`` PROTO node's rays
rise by the PROTO's stock tilt (:data:`~mazesim.webots.scene.EPUCK_IR_ELEVATION`).
:func:`own_sensors` turns the tables, poses, tilts and types that differ from the built-in
profile's into a copy of that profile, for a run of one robot (:mod:`mazesim.webots.simulation`)
and for each robot of a world of several (:mod:`mazesim.webots.lockstep`) alike; a robot whose
sensors are all the profile's is simulated by the profile's name, as ever.

A tilted ray in the 2-D model: walls have no height, so a ray tilted by ``e`` (up or down)
meets a wall at horizontal distance ``h`` after ``h / cos(e)`` of its length and reaches
``cos(e)`` of its length across the floor. A ray tilted down from height ``z`` meets the floor
``z / sin(e)`` along it; within its range Webots reads the floor there, which mazesim does not
(a warning says so at the run's start). The E-puck PROTO's rays rise, from 3.3 cm: no floor.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from mazesim._core import RobotProfile
from mazesim._toml import dump_toml, load_toml
from mazesim.errors import MazesimError, _shown
from mazesim.webots.distance_rays import INFRA_RED as INFRA_RED_TYPE
from mazesim.webots.distance_rays import sensor_type
from mazesim.webots.own_drive import drive_layout
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
#: the profile's pose and a level ray.
STEEPEST_RAY_RAD = math.pi / 4
#: A ray tilted less than this (rad) from the floor's plane is level (cos 0.01 = 0.99995).
LEVEL_RAY_RAD = 0.01
#: The ``type`` of a DistanceSensor whose readings depend on the colour its ray meets.
INFRA_RED = "infra-red"
#: What the 2-D model leaves out of each other ``type`` of DistanceSensor (Webots' reference
#: manual, DistanceSensor): read by the distance alone, whatever colour the ray meets.
TYPE_LIMITS = {
    "generic": "",
    "sonar": (
        "a ray meeting a wall more than 22.5 degrees off its normal is not lost (Webots then "
        "reads the table's last value)"
    ),
    "laser": "the red spot it draws is not drawn on camera images",
}


@dataclass(frozen=True)
class OwnSensors:
    """What a robot node's own sensors make of its built-in profile.

    Attributes:
        tables: The world's lookup tables the robot's sensors read through, by sensor name:
            those that differ from the profile's and that the profile format takes, and the
            empty ones (``lookupTable []``: the sensor reads 0, as Webots' DistanceSensor reads
            through no table; the profile keeps its own table for it).
        poses: The world's poses of the robot's sensors, by sensor name, where they differ from
            the profile's: x, y (m) and, for a distance sensor, the heading of its ray (rad).
        elevations: How far each distance sensor's ray is tilted from the floor's plane (rad,
            up or down alike), by sensor name, where it is not level: the world's own sensor
            rotation where the world writes it, the PROTO's stock tilt otherwise.
        types: The ``type`` of each distance sensor that is not ``infra-red``, by sensor name:
            it reads the distance its ray runs, whatever colour it meets.
        profile: The built-in profile with those tables and poses, or None when every sensor
            is the profile's (the profile's name then simulates the robot).
        warnings: What of the robot node's sensors is not used, and why (those sensors read
            through the profile's tables), one line per reason.
    """

    tables: dict[str, list[Row]] = field(default_factory=dict)
    poses: dict[str, tuple[float, ...]] = field(default_factory=dict)
    elevations: dict[str, float] = field(default_factory=dict)
    types: dict[str, str] = field(default_factory=dict)
    profile: RobotProfile | None = None
    warnings: list[str] = field(default_factory=list)


def own_sensors(name: str, scene: Scene | None) -> OwnSensors:
    """The sensors of a robot node (its ``scene``) simulated by built-in profile ``name``.

    Each of the profile's sensors whose ``DistanceSensor`` node the robot node lists with
    another table than the profile's reads through the node's table; a table the profile format
    refuses, or a ``lookupTable`` field not of rows of 3 numbers, keeps the profile's, with a
    warning naming the sensors and what was found. A sensor node that the robot node holds
    itself, placed or turned otherwise than the profile's sensor, casts its ray from the node's
    pose (see :func:`_moved_sensors`), tilted as :func:`_tilted_rays` says; one whose node's
    ``type`` is not ``infra-red`` reads the distance alone (:func:`_ray_types`).
    """
    if scene is None or not (
        scene.sensor_tables
        or scene.malformed_tables
        or scene.sensor_poses
        or scene.infrared_elevation
        or scene.drive
        or scene.drive_refused
        or scene.sensor_ray_counts
    ):
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
        if not table:
            tables[sensor["name"]] = table
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
    elevations, floor_warnings = _tilted_rays(layout, scene)
    types, type_warnings = _ray_types(layout, scene)
    warnings += floor_warnings + type_warnings + _one_ray(layout, scene)
    if scene.drive is not None:
        warnings += scene.drive.warnings
        layout = copy.deepcopy(layout)
        drive_layout(layout, scene.drive)
    elif scene.drive_refused is not None:
        warnings.append(
            f"its own two wheels do not drive it: {scene.drive_refused}; the e-puck's wheels "
            "and body stand in for them"
        )
    # An empty table reads 0 through the device alone: the profile keeps its own for it.
    rows = {name: table for name, table in tables.items() if table}
    changed = rows or poses or elevations or types or scene.drive
    profile = _profile_with(layout, rows, poses, elevations, set(types)) if changed else None
    return OwnSensors(tables, poses, elevations, types, profile, warnings)


def _tilted_rays(layout: Mapping[str, Any], scene: Scene) -> tuple[dict[str, float], list[str]]:
    """How far each distance sensor's ray of a parsed profile file is tilted from the floor's
    plane where it is not level (rad): the rise of the world's own sensor node where the robot
    node holds it (``Scene.sensor_poses``; one steeper than :data:`STEEPEST_RAY_RAD` keeps a
    level ray), else the robot node's stock tilt (``Scene.infrared_elevation``: an
    ``E-puck`` PROTO's); and a warning naming the rays tilted down that meet the floor within
    their range."""
    models = layout.get("models", {})
    elevations: dict[str, float] = {}
    floor: list[str] = []
    for sensor in layout.get("distance_sensors", []):
        name = sensor["name"]
        pose = scene.sensor_poses.get(name)
        if pose is None:
            tilt = scene.infrared_elevation
        elif abs(pose[3]) > STEEPEST_RAY_RAD:
            continue
        else:
            tilt = abs(pose[3])
            reach = float(models[sensor["model"]]["table"][-1][0])
            height = scene.sensor_heights.get(name, 0.0)
            if pose[3] < -LEVEL_RAY_RAD and height / math.sin(tilt) < reach:
                floor.append(f"{_shown(name)} ({height / math.sin(tilt):.3f} m)")
        if tilt > LEVEL_RAY_RAD:
            elevations[name] = tilt
    warnings = (
        [
            f"the ray of DistanceSensor {', '.join(floor)} points down at the floor within its "
            "range, where Webots reads the floor: mazesim's rays meet walls, robots and bodies "
            "only, so it reads them as a ray tilted up as much"
        ]
        if floor
        else []
    )
    return elevations, warnings


def _ray_types(layout: Mapping[str, Any], scene: Scene) -> tuple[dict[str, str], list[str]]:
    """The ``type`` of each distance sensor of a parsed profile file whose node the robot node
    lists with a type other than ``infra-red`` (``Scene.sensor_types``), by name; and what the
    2-D model does not give of those types (:data:`TYPE_LIMITS`), one line per type."""
    types: dict[str, str] = {}
    by_type: dict[str, list[str]] = {}
    for sensor in layout.get("distance_sensors", []):
        found = scene.sensor_types.get(sensor["name"], INFRA_RED)
        # Read as Webots reads the field: "Infrared" is infra-red, an unknown word a sonar.
        if sensor_type(found) != INFRA_RED_TYPE:
            types[sensor["name"]] = found
            by_type.setdefault(found, []).append(repr(sensor["name"]))
    warnings = []
    for found, names in by_type.items():
        limit = TYPE_LIMITS.get(found.lower())
        if limit is None:
            limit = (
                f"expected one of {', '.join(map(repr, [*TYPE_LIMITS, INFRA_RED]))}, found "
                f"{_shown(found)}, which Webots reads as a sonar: {TYPE_LIMITS['sonar']}"
            )
        if limit:
            warnings.append(
                f"DistanceSensor {', '.join(names)} (type {_shown(found)}) reads the distance "
                f"alone, whatever colour its ray meets; {limit}"
            )
    return types, warnings


def _one_ray(layout: Mapping[str, Any], scene: Scene) -> list[str]:
    """A warning naming the distance sensors of a parsed profile file whose node casts several
    rays (``Scene.sensor_ray_counts``), which the profile's sensors cast one of, one line per
    count."""
    by_count: dict[int, list[str]] = {}
    for sensor in layout.get("distance_sensors", []):
        if (count := scene.sensor_ray_counts.get(sensor["name"])) is not None:
            by_count.setdefault(count, []).append(repr(sensor["name"]))
    return [
        f"DistanceSensor {', '.join(names)} casts {count} rays in Webots (numberOfRays "
        f"{count}, spread over its aperture and averaged); mazesim casts one, along its axis"
        for count, names in by_count.items()
    ]


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
    elevations: Mapping[str, float] | None = None,
    ranges: set[str] | None = None,
) -> RobotProfile:
    """The profile of a parsed profile file, each sensor named in ``tables`` reading through a
    copy of its model with that table, each named in ``ranges`` through a copy of kind
    ``range`` (one copy per model, table and kind: ``world-table-N``), each named in ``poses``
    at that position (and heading), each named in ``elevations`` with its ray so tilted."""
    layout = copy.deepcopy(layout)
    models = layout.setdefault("models", {})
    copies: dict[tuple[str, tuple[Row, ...], bool], str] = {}
    for sensor in [*layout.get("distance_sensors", []), *layout.get("ground_sensors", [])]:
        name = sensor["name"]
        if (pose := (poses or {}).get(name)) is not None:
            sensor["position"] = [pose[0], pose[1]]
            if len(pose) > 2:
                sensor["heading"] = pose[2]
        if (elevation := (elevations or {}).get(name)) is not None:
            sensor["elevation"] = elevation
        table, ranged = tables.get(name), name in (ranges or set())
        if table is None and not ranged:
            continue
        model = models[sensor["model"]]
        rows = table if table is not None else [tuple(row) for row in model["table"]]
        key = (sensor["model"], tuple(rows), ranged)
        if key not in copies:
            copies[key] = f"world-table-{len(copies)}"
            kind = {"kind": "range"} if ranged else {}
            models[copies[key]] = {**model, "table": [list(row) for row in rows], **kind}
        sensor["model"] = copies[key]
    return RobotProfile.from_toml(dump_toml(layout), "the world's sensors")
