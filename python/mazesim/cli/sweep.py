"""``mazesim sweep``: run a grid of training settings on Ray (or one after the other).

The sweep file is read and checked before Ray starts, so a mistake in it is reported at once as
one line. Ray itself is imported only when the sweep runs on it.
"""

from __future__ import annotations

import argparse
import json
import os
import shlex
import sys
from collections.abc import Sequence
from typing import Any, TextIO

from mazesim._paths import output_files, refuse_overwriting_inputs
from mazesim.cli._args import add_out_folder, positive_int
from mazesim.cli._help import examples
from mazesim.cli.progress import add_progress_option, progress_display
from mazesim.distributed.config import PARAMETERS, TRAINER_DEFAULTS, load_sweep_config
from mazesim.errors import MissingDependencyError

__all__ = ["run_sweep_command"]

#: Exit code of a sweep that finished with failed runs (the others are all written).
EXIT_RUNS_FAILED = 1


def _parameter_help() -> str:
    def default(name: str, value: Any) -> str:
        if name in TRAINER_DEFAULTS:
            return ""  # each trainer's, which the help text gives
        return f" (default {'none' if value is None else json.dumps(value)})"

    return "; ".join(f"{p.name}{default(p.name, p.default)}: {p.help}" for p in PARAMETERS)


def register(commands: Any) -> None:
    """Adds ``sweep`` to the ``mazesim`` command's subparsers."""
    parser = commands.add_parser(
        "sweep",
        help="train a grid of settings (seeds, rates, mazes) as Ray tasks; summarise them",
        description=(
            "Run every setting of a sweep file (TOML: a [sweep] table with name, cpus_per_task "
            "and max_retries; a [grid] table where a list is an axis and a single value is "
            "fixed) as a Ray task: train, evaluate the greedy policy, write the tables and the "
            "training curve. Everything is gathered into DIR: runs/<id>/ per setting, "
            "results.json, results.csv and sweep.png (success rate and training time per "
            "setting). Without --address a local Ray instance is started on this machine; "
            "with it, the sweep runs on that cluster (every machine needs the same mazesim and "
            "'pip install mazesim[ray]'). A worker that dies is retried; a run that fails is "
            "reported and the others are kept. Runs already finished in DIR are not run again. "
            "Exit code 0: all runs ok; 1: some failed; 2: an error in the input."
        ),
        epilog=examples(
            "mazesim sweep examples/sweep.toml --sequential --out my-sweep",
            "mazesim sweep examples/sweep.toml --cpus 2",
            "mazesim sweep examples/sweep.toml --address auto --out runs/sweep",
            notes="Grid parameters: " + _parameter_help() + ". See examples/sweep.toml.",
        ),
    )
    parser.add_argument("config", metavar="CONFIG", help="the sweep file (.toml)")
    parser.add_argument(
        "--address",
        metavar="ADDR",
        help="a running Ray cluster: 'auto', HOST:6379 or ray://HOST:10001; or 'local' "
        "(the default: start a local Ray instance)",
    )
    add_out_folder(parser, "mazesim-sweep")
    parser.add_argument(
        "--cpus",
        type=positive_int,
        metavar="N",
        help="CPUs of the local Ray instance (default: this machine's cores)",
    )
    parser.add_argument(
        "--sequential",
        action="store_true",
        help="run the settings one after the other in this process, without Ray",
    )
    parser.add_argument(
        "--quiet", action="store_true", help="print only the summary, not a line per run"
    )
    add_progress_option(parser)
    parser.set_defaults(run=lambda args: run_sweep_command(args, sys.stdout))


def _summary_lines(runs: Sequence[dict[str, Any]]) -> list[str]:
    """One line per setting group: seeds ok / failed, mean success and training time."""
    groups: dict[str, list[dict[str, Any]]] = {}
    for run in runs:
        groups.setdefault(run["label"], []).append(run)
    width = max((len(label) for label in groups), default=7)
    lines = [f"{'setting':<{width}}  runs  failed  success  training (s)"]
    for label, members in groups.items():
        ok = [run for run in members if run["status"] == "ok"]
        failed = sum(1 for run in members if run["status"] == "failed")
        success = (
            f"{100.0 * sum(run['success_rate'] or 0.0 for run in ok) / len(ok):6.1f}%"
            if ok
            else "    n/a"
        )
        seconds = f"{sum(run['training_seconds'] for run in ok) / len(ok):12.2f}" if ok else ""
        lines.append(f"{label:<{width}}  {len(members):4d}  {failed:6d}  {success}  {seconds}")
    return lines


def run_sweep_command(args: argparse.Namespace, out: TextIO) -> int:
    """Runs ``mazesim sweep`` and prints its summary."""
    from mazesim.distributed.runner import run_sequential, run_sweep

    refuse_overwriting_inputs(
        output_files(
            args.out, ("sweep.toml", "settings.json", "results.json", "results.csv", "sweep.png")
        ),
        [("the sweep file", args.config)],
    )
    config = load_sweep_config(args.config)
    if not args.sequential:
        from mazesim.distributed.cluster import import_ray

        try:
            import_ray()
        except MissingDependencyError as missing:
            raise MissingDependencyError(
                f"{missing}; or run the sweep in this process, without Ray: "
                f"mazesim sweep {shlex.quote(str(args.config))} --sequential"
            ) from None

    def progress(line: str) -> None:
        if not args.quiet:
            out.write(line + "\n")
            out.flush()

    where = "in this process" if args.sequential else f"on Ray ({args.address or 'local'})"
    progress(f"sweep {config.name}: {len(config.settings)} runs {where}, into {args.out}")
    total = len(config.settings)
    with progress_display(args, unit="runs") as display:
        finished = [0]

        def run_finished(line: str) -> None:
            progress(line)
            finished[0] += 1
            display("sweep", min(finished[0], total), total)

        display("sweep", 0, total)
        if args.sequential:
            summary = run_sequential(config, args.out, progress=run_finished)
        else:
            summary = run_sweep(
                config, args.out, args.address, cpus=args.cpus, progress=run_finished
            )
    for line in _summary_lines(summary.runs):
        out.write(line + "\n")
    rate = summary.env_steps / max(summary.wall_seconds, 1e-9)
    out.write(
        f"wall-clock {summary.wall_seconds:.1f} s, {summary.env_steps} env-steps "
        f"({rate:,.0f} per second)\n"
        f"wrote {os.path.join(args.out, 'results.json')}, results.csv, sweep.png, runs/\n"
    )
    if summary.failed:
        sys.stderr.write(f"mazesim sweep: {len(summary.failed)} run(s) failed; see results.json\n")
        return EXIT_RUNS_FAILED
    return 0
