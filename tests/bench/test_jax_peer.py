"""The JAX peer of ``make bench-peers`` models the same workload as the numpy peer and mazesim.

The measurements run in a subprocess (``jax_peer_probe.py``: JAX's threads would make every later
``fork`` of the test runner warn). Skipped without jax (``make bench-peers`` installs it).
"""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

if importlib.util.find_spec("jax") is None:
    pytest.skip("jax is not installed (`make bench-peers` installs it)", allow_module_level=True)

PROBE = Path(__file__).resolve().parent / "jax_peer_probe.py"
ENVS = 8


@pytest.fixture(scope="module")
def probe() -> dict[str, Any]:
    done = subprocess.run(
        [sys.executable, str(PROBE), str(ENVS)], capture_output=True, text=True, check=True
    )
    report: dict[str, Any] = json.loads(done.stdout)
    return report


def test_one_step_from_the_same_poses_agrees_with_the_numpy_peer(probe: dict[str, Any]) -> None:
    step = probe["step"]
    assert step["poses"] == ENVS
    assert step["max_position_gap_m"] < 1e-5
    assert step["max_heading_gap_rad"] < 1e-5
    assert step["max_relative_reading_gap"] < 1e-3


def test_trajectories_follow_the_numpy_peer(probe: dict[str, Any]) -> None:
    trajectories = probe["trajectories"]
    assert trajectories["share_within_tolerance"] == 1.0
    assert trajectories["first_step_apart"] is None


def test_readings_match_mazesim_at_the_same_poses(probe: dict[str, Any]) -> None:
    assert probe["ps_max_abs_gap_to_mazesim"] < 0.5  # raw counts, of up to 4,095


def test_many_steps_per_call_equal_as_many_calls(probe: dict[str, Any]) -> None:
    ten = probe["ten_steps"]
    assert ten["pose_gap"] < 1e-6
    assert ten["reading_gap"] < 1e-5
    assert ten["least_distance_moved"] > 0.01


def test_lean_variant_reads_no_ground_sensors(probe: dict[str, Any]) -> None:
    assert probe["lean"] == {"name": "jax-lean", "width": 8}
