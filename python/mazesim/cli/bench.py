"""``mazesim bench``: steady-state env-steps per second, contact share and memory per env.

The measuring is :mod:`mazesim.benchmark`'s (docs/performance.md); this module parses the
options, shows the progress over the batch sizes (in env-steps, so that a large batch weighs
more than a small one) and prints the table (or, with ``--json``, one JSON object).
"""

from __future__ import annotations

import argparse
import json
from dataclasses import fields
from typing import Any

from mazesim.benchmark import MIN_WARMUP_STEPS, BenchSettings
from mazesim.benchmark.size_sweep import machine, run_sizes, single_env_rate, table
from mazesim.cli._args import (
    MAX_COUNT,
    add_setting_options,
    seed_argument,
    whole_number,
)
from mazesim.cli._help import examples
from mazesim.cli.progress import add_progress_option, progress_display
from mazesim.errors import _shown

__all__ = ["run_bench"]

#: The one default of each setting: the bench's own.
DEFAULTS = BenchSettings()
#: Batch sizes measured when --envs is not given.
DEFAULT_SIZES = [1, 64, 1024, 4096]


def _counts(text: str, what: str, example: str) -> list[int]:
    """Whole numbers in [1, MAX_COUNT], comma-separated; ``what`` names them in messages."""
    try:
        counts = [int(part) for part in text.split(",") if part.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected {what} like {example}, found {_shown(text)}"
        ) from None
    if not counts or min(counts) < 1 or max(counts) > MAX_COUNT:
        raise argparse.ArgumentTypeError(
            f"expected {what} in [1, {MAX_COUNT}], found {_shown(text)}"
        )
    return counts


def _env_counts(text: str) -> list[int]:
    return _counts(text, "env counts", "1,64,1024")


def _steps_per_call(text: str) -> list[int]:
    return _counts(text, "steps per call", "1,100")


def _warmup_steps(text: str) -> int:
    return whole_number(text, MIN_WARMUP_STEPS)


def run_bench(args: argparse.Namespace) -> int:
    """Runs ``mazesim bench``."""
    settings = BenchSettings(
        **{f.name: getattr(args, f.name) for f in fields(BenchSettings) if "help" in f.metadata},
        warmup_steps=args.warmup,
        steps_per_call=max(args.steps_per_call),
    )
    with progress_display(args, unit="env-steps") as display:
        reports = run_sizes(
            settings,
            args.envs,
            progress=lambda done, total: display("bench", done, total),
            steps_per_call=args.steps_per_call,
        )
    single = single_env_rate()
    if args.json:
        document: dict[str, Any] = {
            "settings": {
                **{k: v for k, v in vars(settings).items() if k != "envs"},
                "envs": args.envs,
                "steps_per_call": args.steps_per_call,
            },
            "machine": machine(),
            "results": reports,
            "single_env_python_steps_per_s": single,
        }
        print(json.dumps(document))
        return 0
    print(table(reports))
    print(f"one env stepped from Python (Simulator, rule in plain Python): {single:,.0f} steps/s")
    return 0


def register(commands: Any) -> None:
    """Adds ``mazesim bench`` to the command line."""
    parser = commands.add_parser(
        "bench",
        help="measure steady-state env-steps per second, contact share and memory per env",
        description=(
            "Run a workload on a batch of 5 x 5 mazes (the e-puck with all 11 sensors read "
            "each step, 32 ms steps) at each batch size, each in a fresh process: a warm-up of "
            "at least 1,000 steps with episodes reset as they end, then timed blocks. Prints "
            "env-steps per wall-second and per CPU-second, the share of steps in contact and "
            "resident bytes per env (docs/performance.md)."
        ),
        epilog=examples(
            "mazesim bench",
            "mazesim bench --envs 64,1024 --json",
            "mazesim bench --workload contact --envs 1024",
            "mazesim bench --envs 1024 --steps-per-call 1,100",
        ),
    )
    parser.add_argument(
        "--envs",
        type=_env_counts,
        default=DEFAULT_SIZES,
        metavar="N,N,...",
        help="batch sizes (default: 1,64,1024,4096)",
    )
    add_setting_options(
        parser,
        DEFAULTS,
        {"seed": seed_argument},  # the counts take their fields' declared ranges
    )
    parser.add_argument(
        "--warmup",
        type=_warmup_steps,
        default=DEFAULTS.warmup_steps,
        metavar="K",
        help=f"untimed steps first, at least {MIN_WARMUP_STEPS} (default: {DEFAULTS.warmup_steps})",
    )
    parser.add_argument(
        "--steps-per-call",
        type=_steps_per_call,
        default=[DEFAULTS.steps_per_call],
        metavar="K,K,...",
        help="control steps per call into the engine, one run each: 1 steps from Python with "
        "the rule in numpy; more runs the engine's own controller for the workload in one "
        "BatchSimulator.run call (braitenberg and random only) "
        f"(default: {DEFAULTS.steps_per_call})",
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    add_progress_option(parser)
    parser.set_defaults(run=run_bench)
