"""Runs one of the tests' multi-robot Webots projects whole (``tests/data/webots-swarm-*``), its
controllers writing what they saw into JSON logs: the one runner of the swarm-world suites."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from mazesim.webots.lockstep import WorldRun, run_world

#: The body radius of an e-puck (m).
BODY_RADIUS = 0.037


def run_project(
    project: Path, world: str, logs: Path, seconds: float, **controllers: str
) -> tuple[WorldRun, dict[str, Any]]:
    """Runs ``project``'s world ``world`` (the ``.wbt`` file of that name in its ``worlds``
    folder) for ``seconds`` with seed 5, ``controllers`` given by robot name as on the command
    line; returns the run and each controller's log (``SWARM_LOG``/NAME.json) by name."""
    logs.mkdir(parents=True, exist_ok=True)
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("SWARM_LOG", str(logs))
        done = run_world(
            str(project / "worlds" / f"{world}.wbt"),
            seconds=seconds,
            seed=5,
            controllers=controllers,
        )
    return done, {p.stem: json.loads(p.read_text()) for p in logs.glob("*.json")}
