"""How long a full default transfer study takes, against the 10-minute budget of its issue.

Not a test: run it by hand (or ``make bench-transfer``)::

    .venv/bin/python benches/bench_transfer.py [--policy NAME ...] [--episodes 200]
        [--budget 600] [--json]

Each navigator named (by default the shipped one and the randomised one) runs the full default
study, ``mazesim transfer-study``'s: every axis, the pairs, 200 episodes a cell, robust checkpoint
events, odometry from the wheel encoders. The figure is each study's wall time (the study alone:
loading the navigator and drawing the heat maps are left out) and its episodes per second. The
script exits with status 1 when a study takes longer than ``--budget`` seconds, so it fails where
the budget is missed.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from typing import Any

from mazesim import load_world
from mazesim.learn.tables import load_policy
from mazesim.transfer import StudyOptions, run_study, study_size

#: The issue's budget for a full default study on a 2-core machine, in seconds.
BUDGET_S = 600.0


def measure(name: str | None, episodes: int, threads: int) -> dict[str, Any]:
    """Times one full default study of the navigator ``name`` (None: the shipped one)."""
    policy = load_policy(name)
    world = load_world(policy.world_name)
    options = StudyOptions(episodes=episodes, threads=threads)
    cells, total = study_size(options)
    start = time.perf_counter()
    result = run_study(policy, world, options, label=name or "shipped")
    seconds = time.perf_counter() - start
    return {
        "policy": name or "shipped",
        "cells": cells,
        "episodes": total,
        "seconds": seconds,
        "episodes_per_second": total / seconds,
        "baseline_success": result.baseline.measure.success_rate,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--policy",
        action="append",
        default=None,
        metavar="NAME",
        help="a navigator to study: 'shipped', 'randomised' or a folder; repeat for several "
        "(default: shipped and randomised)",
    )
    parser.add_argument("--episodes", type=int, default=200, help="episodes a cell (200)")
    parser.add_argument("--threads", type=int, default=0, help="worker threads (0: all cores)")
    parser.add_argument(
        "--budget", type=float, default=BUDGET_S, help=f"seconds a study may take ({BUDGET_S:g})"
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args()
    names = args.policy or ["shipped", "randomised"]
    studies = [
        measure(None if name == "shipped" else name, args.episodes, args.threads) for name in names
    ]
    over = [study["policy"] for study in studies if study["seconds"] > args.budget]
    report = {
        "studies": studies,
        "budget_seconds": args.budget,
        "within_budget": not over,
        "load_average": os.getloadavg()[0],
        "machine": platform.machine(),
        "cpus": os.cpu_count(),
    }
    if args.json:
        print(json.dumps(report, indent=2))
    else:
        print(f"full default transfer studies, {args.episodes} episodes a cell")
        for study in studies:
            print(
                f"  {study['policy']:<12} {study['cells']:4d} cells {study['seconds']:7.1f} s "
                f"{study['episodes_per_second']:7.1f} episodes/s"
            )
        verdict = "met" if not over else "missed by " + ", ".join(over)
        print(f"  budget {args.budget:g} s: {verdict}")
    if over:
        sys.exit(1)


if __name__ == "__main__":
    main()
