"""A world run whose robots each write their proximity sensors' readings, tables and types after
one step, for the tests of a robot's own DistanceSensor nodes in world runs."""

from __future__ import annotations

import json
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import pytest

from mazesim.webots.lockstep import run_world

#: The e-puck's proximity sensors: name, x, y, yaw (Webots' E-puck PROTO, rounded).
SENSORS = (
    ("ps0", 0.03, -0.01, -0.3),
    ("ps1", 0.022, -0.025, -0.8),
    ("ps2", 0.0, -0.031, -1.5708),
    ("ps3", -0.03, -0.015, -2.644),
    ("ps4", -0.03, 0.015, 2.639),
    ("ps5", 0.0, 0.031, 1.5708),
    ("ps6", 0.022, 0.025, 0.8),
    ("ps7", 0.03, 0.01, 0.3),
)

#: A controller that writes its robot's ps0..ps7 readings, tables and types after one step
#: into ``$PROBE_LOG/<robot name>.json``.
PROBE = """
import json, os
from controller import Robot

robot = Robot()
sensors = [robot.getDevice(f"ps{i}") for i in range(8)]
for sensor in sensors:
    sensor.enable(32)
robot.step(32)
with open(os.path.join(os.environ["PROBE_LOG"], robot.getName() + ".json"), "w") as log:
    json.dump({
        "values": [sensor.getValue() for sensor in sensors],
        "tables": [sensor.getLookupTable() for sensor in sensors],
        "types": [sensor.getType() for sensor in sensors],
    }, log)
"""


def table_text(rows: tuple[tuple[float, float, float], ...]) -> str:
    """``rows`` as a ``lookupTable`` field's values."""
    return ", ".join(" ".join(repr(v) for v in row) for row in rows)


def plain_robot(
    rows: tuple[tuple[float, float, float], ...] | None,
    *,
    name: str = "e-puck",
    at: tuple[float, float] = (0.203, 0.0),
    controller_name: str = "<extern>",
) -> str:
    """A plain ``Robot`` e-puck node at ``at`` facing +x whose ps0..ps7 carry ``rows`` (no
    ``lookupTable`` field when None)."""
    table = "" if rows is None else f" lookupTable [ {table_text(rows)} ]"
    sensors = "".join(
        f'    DistanceSensor {{ translation {x} {y} 0.033 rotation 0 0 1 {yaw} name "{sensor}"'
        f"{table} }}\n"
        for sensor, x, y, yaw in SENSORS
    )
    return (
        f"Robot {{\n  translation {at[0]} {at[1]} 0\n  children [\n"
        f"{sensors}"
        '    HingeJoint { device [ RotationalMotor { name "left wheel motor" } ] '
        "endPoint Solid { translation 0 0.026 0.02 } }\n"
        '    HingeJoint { device [ RotationalMotor { name "right wheel motor" } ] '
        "endPoint Solid { translation 0 -0.026 0.02 } }\n"
        f'  ]\n  name "{name}"\n  controller "{controller_name}"\n}}\n'
    )


#: The header and arena of the worlds of these tests: walls at x, y = +-0.25 m.


def probe_world_run(
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    text: str,
    others: Mapping[str, str] | None = None,
) -> dict[str, dict[str, list[Any]]]:
    """Runs the world ``text`` (its robots' controller ``probe``, or one of ``others``: Python
    sources by controller name) for 0.1 s without noise in a project under ``tmp_path``;
    returns what each robot wrote, by robot name."""
    project = tmp_path / "project"
    (project / "worlds").mkdir(parents=True)
    for name, source in {"probe": PROBE, **(others or {})}.items():
        (project / "controllers" / name).mkdir(parents=True)
        (project / "controllers" / name / f"{name}.py").write_text(source)
    world = project / "worlds" / "probe.wbt"
    world.write_text(text)
    logs = tmp_path / "logs"
    logs.mkdir()
    monkeypatch.setenv("PROBE_LOG", str(logs))
    run = run_world(str(world), seconds=0.1, noise=False)
    assert [robot.exit_status for robot in run.robots] == [0] * len(run.robots)
    return {path.stem: json.loads(path.read_text()) for path in logs.glob("*.json")}
