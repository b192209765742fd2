"""A robot node's own ``DistanceSensor`` nodes as its robot profile.

A plain ``Robot`` (or Webots 6-7 ``DifferentialWheels``) e-puck saved expanded lists its own
``DistanceSensor`` nodes ps0..ps7 (gs0..gs2), each with its own ``lookupTable`` (Webots'
default one where the node has no such field): Webots reads each sensor through it.
:func:`own_sensors` turns the tables that differ from the built-in profile's into a copy of that
profile, for a run of one robot (:mod:`mazesim.webots.simulation`) and for each robot of a world
of several (:mod:`mazesim.webots.lockstep`) alike; a robot whose sensors are all the profile's
is simulated by the profile's name, as ever.
"""

from __future__ import annotations

import copy
import json
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


@dataclass(frozen=True)
class OwnSensors:
    """What a robot node's own sensors make of its built-in profile.

    Attributes:
        tables: The world's lookup tables the robot's sensors read through, by sensor name:
            those that differ from the profile's and that the profile format takes.
        profile: The built-in profile with those tables, or None when every sensor reads as
            the profile's (the profile's name then simulates the robot).
        warnings: What of the robot node's sensors is not used, and why (those sensors read
            through the profile's tables), one line per reason.
    """

    tables: dict[str, list[Row]] = field(default_factory=dict)
    profile: RobotProfile | None = None
    warnings: list[str] = field(default_factory=list)


def own_sensors(name: str, scene: Scene | None) -> OwnSensors:
    """The sensors of a robot node (its ``scene``) simulated by built-in profile ``name``.

    Each of the profile's sensors whose ``DistanceSensor`` node the robot node lists with
    another table than the profile's reads through the node's table; a table the profile format
    refuses, or a ``lookupTable`` field not of rows of 3 numbers, keeps the profile's, with a
    warning naming the sensors and what was found.
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
            _profile_with_tables(layout, {sensor["name"]: table})
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
    profile = _profile_with_tables(layout, tables) if tables else None
    return OwnSensors(tables, profile, warnings)


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


def _profile_with_tables(layout: dict[str, Any], tables: Mapping[str, list[Row]]) -> RobotProfile:
    """The profile of a parsed profile file, each sensor named in ``tables`` reading through a
    copy of its model with that table (one copy per model and table: ``world-table-N``)."""
    layout = copy.deepcopy(layout)
    models = layout.setdefault("models", {})
    copies: dict[tuple[str, tuple[Row, ...]], str] = {}
    for sensor in [*layout.get("distance_sensors", []), *layout.get("ground_sensors", [])]:
        table = tables.get(sensor["name"])
        if table is None:
            continue
        key = (sensor["model"], tuple(table))
        if key not in copies:
            copies[key] = f"world-table-{len(copies)}"
            rows = [list(row) for row in table]
            models[copies[key]] = {**models[sensor["model"]], "table": rows}
        sensor["model"] = copies[key]
    return RobotProfile.from_toml(_toml_text(layout), "the world's sensor tables")


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
