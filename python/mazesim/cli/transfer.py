"""``mazesim transfer-study``: a navigator on a grid of perturbations of its robot.

The command runs :func:`mazesim.transfer.run_study`, prints a table of the cells (or, with
``--json``, the JSON object documented in docs/transfer.md), and writes ``transfer.json`` and the
heat maps into ``--out``.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from typing import Any, TextIO

from mazesim._paths import make_output_folder
from mazesim.cli._args import (
    add_out_folder,
    add_seed_option,
    name_list,
    non_negative_int,
    positive_int,
)
from mazesim.cli._help import examples
from mazesim.cli.progress import add_progress_option, progress_display

__all__ = ["axes_argument", "run_transfer_study"]

#: The axes' names (kept here so that building the parser imports no simulator).
AXIS_NAMES = (
    "robot", "wheel_radius", "axle_length", "motor_mismatch", "noise_scale", "ir_angle",
    "ir_offset", "wall_reflectance", "ground_drift", "latency", "link", "slip",
)  # fmt: skip


def axes_argument(text: str) -> list[str]:
    """Comma-separated axis names."""
    return name_list(text, AXIS_NAMES, "axes")


def register(commands: Any) -> None:
    """Adds ``transfer-study`` to the ``mazesim`` command's subparsers."""
    parser = commands.add_parser(
        "transfer-study",
        help="measure a navigator on a grid of robot perturbations (sim-to-real transfer)",
        description=(
            "How would the tables survive a real robot? Drive a hierarchical navigator (by "
            "default the one shipped for seed-maze) in its world with the robot perturbed one "
            "axis at a time (each at its documented levels) and in pairs (each axis at its "
            "harshest level, the one of lowest single-axis success), and report success, "
            "contacts per episode and path ratio per cell against the unperturbed baseline. "
            "Every cell drives the same episodes (start jitter and noise seeds), through the "
            "batch engine. Writes transfer.json, transfer_single.png and transfer_pairs.png "
            "into DIR."
        ),
        epilog=examples(
            "mazesim transfer-study",
            "mazesim transfer-study --axes latency,link --episodes 20 --no-pairs",
            "mazesim transfer-study --policy my-navigator --out study --json",
            notes="Axes: robot (another profile, readings mapped into the seed robot's volts), "
            "wheel_radius and axle_length (x0.95-x1.05), motor_mismatch (one motor 5-10 % "
            "weaker), noise_scale (x0.5-x4), ir_angle (5-15 degrees outward), ir_offset (+-5-10 "
            "mm along the heading), wall_reflectance (x0.8-x0.2), ground_drift (x0.8-x1.2), "
            "latency (1-3 control steps), link (the unsynchronised ROS node of the barcode "
            "study), slip (10-50 % of the motion lost in contact). See docs/transfer.md.",
        ),
    )
    parser.add_argument(
        "--policy",
        default=None,
        metavar="DIR",
        help="folder of a saved hierarchical navigator, or 'randomised': the one shipped trained "
        "with domain randomisation (default: the one shipped for seed-maze)",
    )
    parser.add_argument(
        "--episodes",
        type=positive_int,
        default=None,
        metavar="N",
        help="episodes per cell (default: 200)",
    )
    parser.add_argument(
        "--axes",
        type=axes_argument,
        default=list(AXIS_NAMES),
        metavar="NAME,...",
        help="the axes to study (default: all twelve)",
    )
    parser.add_argument(
        "--no-pairs",
        action="store_true",
        help="run the single-axis cells only, not the pairwise ones",
    )
    parser.add_argument(
        "--events",
        choices=("truth", "robust"),
        default="robust",
        help="checkpoint events from the simulator's ground truth or the robust barcode "
        "decoder reading the ground sensor, as a real robot must (default: %(default)s)",
    )
    parser.add_argument(
        "--odometry",
        choices=("encoders", "truth"),
        default="encoders",
        help="what the navigator's odometry (its door sub-tasks' turns and distances, the "
        "heading it holds where blind) is measured from: each robot's wheel encoders read with "
        "its profile's nominal wheel radius and axle length, as on a real robot, or the "
        "simulator's true pose (default: %(default)s)",
    )
    parser.add_argument(
        "--max-steps",
        type=positive_int,
        default=None,
        metavar="N",
        help="control steps (64 ms) after which an episode fails (default: 2000)",
    )
    add_seed_option(
        parser, "the episodes' start jitter and sensor noise and of the link's wake-ups", "S"
    )
    parser.add_argument(
        "--threads",
        type=non_negative_int,
        default=0,
        metavar="T",
        help="worker threads of the batch; results do not depend on it (default: 0 = all cores)",
    )
    add_out_folder(parser, "mazesim-transfer-study", "transfer.json and the heat maps")
    parser.add_argument(
        "--json",
        action="store_true",
        help="print the results as one JSON object instead of a table",
    )
    add_progress_option(parser)
    parser.set_defaults(run=lambda args: run_transfer_study(args, sys.stdout))


def _rate(value: float | None, form: str) -> str:
    return "-" if value is None else format(value, form)


def _table(result: Any) -> str:
    lines = [
        f"  {'cell':<46} {'success':>8} {'contacts':>9} {'path':>6}",
    ]
    for cell in [result.baseline, *result.single, *result.pairs]:
        measure = cell.measure
        lines.append(
            f"  {cell.setting.label():<46} {measure.success_rate:>8.1%} "
            f"{measure.mean_collisions:>9.2f} {_rate(measure.mean_path_ratio, '.2f'):>6}"
        )
    return "\n".join(lines) + "\n"


def run_transfer_study(args: argparse.Namespace, out: TextIO) -> int:
    """Runs the study, writes its files and prints the table or the JSON object."""
    from mazesim.learn.tables import load_policy
    from mazesim.transfer import StudyOptions, parse_axes, run_study
    from mazesim.transfer.heatmap import write_study_files
    from mazesim.transfer.study import DEFAULT_EPISODES, DEFAULT_MAX_STEPS

    make_output_folder(args.out)  # a bad --out fails before the study runs
    policy = load_policy(args.policy)
    world = policy.learned_world()
    options = StudyOptions(
        axes=parse_axes(args.axes),
        episodes=args.episodes if args.episodes is not None else DEFAULT_EPISODES,
        pairs=not args.no_pairs,
        seed=args.seed,
        events=args.events,
        odometry=args.odometry,
        max_steps=args.max_steps if args.max_steps is not None else DEFAULT_MAX_STEPS,
        threads=args.threads,
    )
    started = time.perf_counter()
    with progress_display(args, unit="episodes") as display:
        result = run_study(
            policy,
            world,
            options,
            label="shipped" if args.policy is None else str(args.policy),
            progress=display,
        )
    elapsed = time.perf_counter() - started
    written = write_study_files(result, args.out)
    if args.json:
        out.write(json.dumps(result.as_json(), indent=2) + "\n")
        return 0
    out.write(
        f"{result.policy} navigator in {result.world}: {result.episodes_label}, "
        f"seed {result.seed}, {result.events} checkpoint events, {result.odometry_label}\n"
    )
    out.write(_table(result))
    out.write(f"ran in {elapsed:.1f} s; wrote {', '.join(written)}\n")
    return 0
