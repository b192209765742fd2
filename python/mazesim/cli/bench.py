"""``mazesim bench``: env-steps per second and memory per env of the canonical workload.

The workload and its measurement are in :mod:`mazesim.bench`; this module parses the options,
shows the progress over the batch sizes and prints the table (or, with ``--json``, one JSON
object).
"""

from __future__ import annotations

import argparse
import json
import os
from typing import Any

from mazesim.cli._args import MAX_COUNT, non_negative_int
from mazesim.cli.progress import add_progress_option, progress_display

__all__ = ["register", "run_bench"]


def _env_counts(text: str) -> list[int]:
    try:
        counts = [int(part) for part in text.split(",") if part.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected env counts like 1,64,1024, found {text!r}"
        ) from None
    if not counts or min(counts) < 1 or max(counts) > MAX_COUNT:
        raise argparse.ArgumentTypeError(f"expected env counts in [1, {MAX_COUNT}], found {text!r}")
    return counts


def run_bench(args: argparse.Namespace) -> int:
    """Runs ``mazesim bench``."""
    from mazesim.bench import WORKLOAD, _auto_steps, _measure_in_child, single_env_rate

    results = []
    # One run per batch size, then the single env stepped from Python.
    total = len(args.envs) + 1
    with progress_display(args, unit="runs") as display:
        display("bench", 0, total)
        for done, envs in enumerate(args.envs, start=1):
            steps = args.steps or _auto_steps(envs)
            result = _measure_in_child(envs, steps, args.threads)
            results.append({k: result[k] for k in ("envs", "env_steps_per_s", "bytes_per_env")})
            display("bench", done, total)
        single = single_env_rate(20_000 if args.steps == 0 else max(args.steps, 1000))
        display("bench", total, total)
    workload = dict(WORKLOAD, threads=args.threads or os.cpu_count(), cpus=os.cpu_count())
    if args.json:
        print(
            json.dumps(
                {"workload": workload, "results": results, "single_env_python_steps_per_s": single}
            )
        )
        return 0
    print(f"workload: {WORKLOAD['maze']}; {WORKLOAD['robot']}; 32 ms steps; Braitenberg")
    print(f"threads: {workload['threads']} of {os.cpu_count()} cpus")
    print(f"{'envs':>7}  {'env-steps/s':>13}  {'bytes/env':>10}")
    for r in results:
        print(f"{r['envs']:>7}  {r['env_steps_per_s']:>13,.0f}  {r['bytes_per_env']:>10,}")
    print(f"one env stepped from Python: {single:,.0f} steps/s")
    return 0


def register(commands: Any) -> None:
    """Adds ``mazesim bench`` to the command line."""
    parser = commands.add_parser(
        "bench",
        help="measure env-steps per second and memory per env of the canonical workload",
        description=(
            "Run the canonical workload (a distinct 5 x 5 maze per env, the e-puck with all 11 "
            "sensors read each step, 32 ms steps, Braitenberg wheel speeds) at each batch size, "
            "each in a fresh process, and print env-steps per second and resident bytes per env."
        ),
    )
    parser.add_argument(
        "--envs",
        type=_env_counts,
        default=[1, 64, 1024, 4096, 65536],
        metavar="N,N,...",
        help="batch sizes (default: 1,64,1024,4096,65536)",
    )
    parser.add_argument(
        "--steps",
        type=non_negative_int,
        default=0,
        metavar="K",
        help="steps per batch size (default: enough for about 1.5 s each)",
    )
    parser.add_argument(
        "--threads",
        type=non_negative_int,
        default=0,
        metavar="T",
        help="worker threads (default: 0 = all cores)",
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    add_progress_option(parser)
    parser.set_defaults(run=run_bench)
