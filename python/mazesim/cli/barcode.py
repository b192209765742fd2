"""``mazesim barcode-study``: the barcode reading study of the report's Fig. 4.3 and 4.5.

The command runs :func:`mazesim.barcode.study.run_study`, prints a table (or, with ``--json``,
the JSON object documented in the README), and writes CSV tables and bar charts into ``--out``.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from collections.abc import Callable
from typing import Any, TextIO

import mazesim
from mazesim._paths import make_output_folder
from mazesim.barcode.decoders import DECODERS
from mazesim.barcode.link import LINKS
from mazesim.barcode.study import (
    DEFAULT_ENVS,
    DEFAULT_READINGS,
    DEFAULT_SPEED,
    DEFAULT_SPEEDS,
    DEFAULT_THRESHOLD,
    DEFAULT_THRESHOLDS,
    StudyResult,
    Tally,
    run_study,
)
from mazesim.cli._args import add_out_folder, add_seed_option, name_list, positive_int
from mazesim.cli._help import examples
from mazesim.cli.progress import add_progress_option, progress_display
from mazesim.errors import _shown

__all__ = ["run_barcode_study"]

#: Largest wheel speed the study accepts, rad/s (the e-puck's motor limit).
MAX_SPEED = 6.28


def _number_list(
    text: str, what: str, accept: Callable[[float], bool], expected: str
) -> list[float]:
    values = []
    for part in text.split(","):
        try:
            value = float(part)
        except ValueError:
            raise argparse.ArgumentTypeError(
                f"expected comma-separated {what}, found {_shown(part.strip())} in {_shown(text)}"
            ) from None
        if not (math.isfinite(value) and accept(value)):
            raise argparse.ArgumentTypeError(f"expected {expected}, found {_shown(part.strip())}")
        values.append(value)
    return values


def threshold_list(text: str) -> list[float]:
    """Comma-separated obstacle thresholds in volts."""
    return _number_list(text, "volts", lambda v: v > 0.0, "thresholds above 0 V")


def speed_list(text: str) -> list[float]:
    """Comma-separated wheel speeds in rad/s."""
    return _number_list(
        text, "speeds in rad/s", lambda v: 0.0 < v <= MAX_SPEED, f"speeds in (0, {MAX_SPEED}]"
    )


def decoder_list(text: str) -> list[str]:
    """Comma-separated decoder names."""
    return name_list(text, tuple(DECODERS), "decoders")


def register(commands: Any) -> None:
    """Adds ``barcode-study`` to the ``mazesim`` command's subparsers."""
    parser = commands.add_parser(
        "barcode-study",
        help="measure barcode reading (right / wrong / missed) by threshold and by speed",
        description=(
            "The barcode reading study of the source report (Fig. 4.3 and 4.5). Robots of the "
            "'seed' profile wander the maze with the report's exploration controller (turn on "
            "the spot when the front Sharp sensor reads above the obstacle threshold, otherwise "
            "veer away from walls); every barcode crossing the simulator reports is one reading "
            "and each decoder is judged on it: right (checkpoint and direction), wrong, or "
            "missed (no valid read). Each threshold runs at the default speed, each speed at "
            "the default threshold. Writes by_threshold.csv/.png and by_speed.csv/.png into "
            "DIR."
        ),
        epilog=examples(
            "mazesim barcode-study",
            "mazesim barcode-study --link ros --out study-ros",
            "mazesim barcode-study --thresholds 1.2,2.0 --speeds 3.14,6.28 --readings 500 --json",
            notes="Decoders: alg7 = the report's Alg. 7 (middle sample of each fifth, threshold "
            "700); robust = places samples along the code with wheel odometry. Shares in the JSON "
            "output are in [0, 1]; 'spurious' counts valid reads of no crossing.",
        ),
    )
    parser.add_argument(
        "--readings",
        type=positive_int,
        default=DEFAULT_READINGS,
        metavar="N",
        help="barcode crossings judged per setting (default: %(default)s)",
    )
    parser.add_argument(
        "--thresholds",
        type=threshold_list,
        default=list(DEFAULT_THRESHOLDS),
        metavar="V,V,...",
        help="obstacle thresholds in volts, run at the default speed "
        "(default: 1.2,1.4,1.6,1.8,2.0; 1.2 V is about 11 cm, 2.0 V about 6 cm)",
    )
    parser.add_argument(
        "--speeds",
        type=speed_list,
        default=list(DEFAULT_SPEEDS),
        metavar="S,S,...",
        help="wheel speeds in rad/s, run at the default threshold "
        f"(default: 1.57,3.14,4.71,6.28; the motor limit is {MAX_SPEED})",
    )
    parser.add_argument(
        "--decoders",
        type=decoder_list,
        default=list(DECODERS),
        metavar="NAME,...",
        help="decoders to judge on the same readings (default: alg7,robust)",
    )
    parser.add_argument(
        "--default-threshold",
        type=lambda text: threshold_list(text)[0],
        default=DEFAULT_THRESHOLD,
        metavar="V",
        help="threshold of the speed study, volts (default: %(default)s)",
    )
    parser.add_argument(
        "--default-speed",
        type=lambda text: speed_list(text)[0],
        default=DEFAULT_SPEED,
        metavar="S",
        help="speed of the threshold study, rad/s (default: %(default)s)",
    )
    parser.add_argument(
        "--link",
        choices=LINKS,
        default="lockstep",
        help="how the controller and decoders see the simulator: lockstep = every control "
        "step; ros = a node that wakes every 1-3 steps, as the report's unsynchronised ROS "
        "node, and misses the samples in between (default: %(default)s)",
    )
    parser.add_argument(
        "--world",
        default="seed-maze",
        metavar="NAME|PATH",
        help="a built-in world or world file with barcode checkpoints (default: %(default)s)",
    )
    parser.add_argument(
        "--envs",
        type=positive_int,
        default=DEFAULT_ENVS,
        metavar="N",
        help="robots wandering at once in the batch engine (default: %(default)s)",
    )
    add_seed_option(parser, "the start poses, sensor noise and turning choices")
    add_out_folder(parser, "mazesim-barcode-study", "the CSV tables and charts")
    parser.add_argument(
        "--json",
        action="store_true",
        help="print the results as one JSON object instead of a table",
    )
    add_progress_option(parser)
    parser.set_defaults(run=lambda args: run_barcode_study(args, sys.stdout))


def _table(title: str, key: str, tallies: list[Tally]) -> str:
    unit = "V" if key == "threshold_v" else "rad/s"
    lines = [
        title,
        f"  {'decoder':<8} {unit:>6} {'right':>7} {'wrong':>7} {'missed':>7} {'spur.':>7}",
    ]
    for t in tallies:
        value = t.threshold_v if key == "threshold_v" else t.speed
        lines.append(
            f"  {t.decoder:<8} {value:>6g} {t.share(t.right):>7.1%} {t.share(t.wrong):>7.1%} "
            f"{t.share(t.missed):>7.1%} {t.share(t.spurious):>7.1%}"
        )
    return "\n".join(lines) + "\n"


def run_barcode_study(args: argparse.Namespace, out: TextIO) -> int:
    """Runs the study, writes its files and prints the table or the JSON object."""
    from mazesim.barcode.charts import write_study_files
    from mazesim.maze import refuse_blocked_start

    world = mazesim.load_world(args.world)
    refuse_blocked_start(world, args.world)
    make_output_folder(args.out)
    started = time.perf_counter()
    with progress_display(args, unit="readings") as display:
        result: StudyResult = run_study(
            world,
            readings=args.readings,
            thresholds=args.thresholds,
            speeds=args.speeds,
            decoders=args.decoders,
            seed=args.seed,
            envs=args.envs,
            default_threshold_v=args.default_threshold,
            default_speed=args.default_speed,
            progress=lambda done, total: display("barcode-study", done, total),
            link=args.link,
        )
    elapsed = time.perf_counter() - started
    written = write_study_files(result, args.out)
    if args.json:
        out.write(json.dumps(result.to_json(), indent=2) + "\n")
        return 0
    out.write(
        _table(
            f"by obstacle threshold (speed {result.default_speed:g} rad/s, "
            f"{result.readings} readings each, {result.link} link)",
            "threshold_v",
            result.by_threshold,
        )
    )
    out.write(
        _table(
            f"by wheel speed (threshold {result.default_threshold_v:g} V, "
            f"{result.readings} readings each, {result.link} link)",
            "speed",
            result.by_speed,
        )
    )
    out.write(f"ran in {elapsed:.1f} s; wrote {', '.join(written)}\n")
    return 0
