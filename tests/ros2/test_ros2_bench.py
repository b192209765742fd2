"""``benches/ros2_lockstep.py``: it measures full-topic-set lockstep round trips over ROS 2 in a
private network namespace and fails when the best repeat is below its goal."""

from __future__ import annotations

import re
import sys
from pathlib import Path

from ros2_support import needs_namespace, needs_ros2, run_in_namespace

pytestmark = [needs_ros2, needs_namespace]

SCRIPT = Path(__file__).resolve().parents[2] / "benches" / "ros2_lockstep.py"


def _bench(goal: str) -> tuple[int, str]:
    command = [sys.executable, str(SCRIPT), "--steps", "200", "--repeats", "1", "--no-ros1"]
    result = run_in_namespace([], [*command, "--goal", goal])
    return result.returncode, result.stdout


def test_the_bench_measures_round_trips_and_fails_below_its_goal() -> None:
    code, out = _bench("1")
    assert code == 0, out
    best = re.search(r"best: ([\d,]+) lockstep control steps/s over ROS 2", out)
    assert best is not None and int(best.group(1).replace(",", "")) > 1, out
    assert re.search(r"bridge per step: simulate \d+ µs, encode \d+ µs, write \d+ µs", out), out
    code, out = _bench("1e9")
    assert code == 1 and "below the goal" in out, out
