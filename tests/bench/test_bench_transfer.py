"""``benches/bench_transfer.py``: it times full default studies and fails past its budget."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

SCRIPT = Path(__file__).resolve().parents[2] / "benches" / "bench_transfer.py"


def _run(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, str(SCRIPT), "--policy", "shipped", "--episodes", "1", *args],
        capture_output=True,
        text=True,
        check=False,
    )


def test_it_times_the_whole_grid_and_fails_past_its_budget() -> None:
    within = _run("--json")
    assert within.returncode == 0, within.stderr
    report = json.loads(within.stdout)
    (study,) = report["studies"]
    # Every axis and the pairs: 1 baseline + 41 single-axis cells + 66 pairs.
    assert study["policy"] == "shipped" and study["cells"] == 108 and study["episodes"] == 108
    assert study["seconds"] > 0 and report["within_budget"] and report["budget_seconds"] == 600
    missed = _run("--budget", "0.001")
    assert missed.returncode == 1
    assert "missed by shipped" in missed.stdout
