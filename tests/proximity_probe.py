"""A world run whose robots each write their proximity sensors' readings, tables and types after
one step, for the tests of a robot's own DistanceSensor nodes in world runs."""

from __future__ import annotations

import json
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


def probe_world_run(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, text: str
) -> dict[str, dict[str, list[Any]]]:
    """Runs the world ``text`` (its robots' controller ``probe``) for 0.1 s without noise in a
    project under ``tmp_path``; returns what each robot wrote, by robot name."""
    project = tmp_path / "project"
    (project / "worlds").mkdir(parents=True)
    (project / "controllers" / "probe").mkdir(parents=True)
    (project / "controllers" / "probe" / "probe.py").write_text(PROBE)
    world = project / "worlds" / "probe.wbt"
    world.write_text(text)
    logs = tmp_path / "logs"
    logs.mkdir()
    monkeypatch.setenv("PROBE_LOG", str(logs))
    run = run_world(str(world), seconds=0.1, noise=False)
    assert [robot.exit_status for robot in run.robots] == [0] * len(run.robots)
    return {path.stem: json.loads(path.read_text()) for path in logs.glob("*.json")}
