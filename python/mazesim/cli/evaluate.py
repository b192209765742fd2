"""``mazesim eval``: evaluating a trained hierarchical navigator.

``mazesim eval`` drives greedy episodes with a saved navigator (by default the one shipped for
seed-maze), prints what it measured (or, with ``--json``, one JSON object), and can write the
per-step trace of the first episode (``--trace``) and its trajectories (``--plot``); with
``--address`` it spreads the episodes over a Ray cluster, or a local Ray instance (``local``).
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import sys
from pathlib import Path
from typing import Any, TextIO

from mazesim import load_world
from mazesim._paths import refuse_overwriting_inputs
from mazesim.cli._args import output_path, positive_int, seed_argument
from mazesim.hrl.navigation import DEFAULT_MAX_STEPS, EVENT_SOURCES
from mazesim.replay.options import add_viewing_options, recording_requested, write_views

__all__ = ["register", "run_eval"]

#: Episodes that ``eval --html/--video/--record`` records (the first ones of the first world).
RECORDED_EPISODES = 3


def register(commands: Any) -> None:
    """Adds ``eval`` to the ``mazesim`` command's subparsers."""
    evaluate = commands.add_parser(
        "eval",
        help="measure a trained navigator: success, collisions, steps, decisions",
        description=(
            "Drive greedy episodes with a trained navigator (by default the one shipped for "
            "seed-maze) with sensor noise and a random start jitter of up to 2 cm and 10 degrees, "
            "and report the success rate, collisions, steps against the shortest path and the "
            "sub-tasks chosen at each checkpoint. In a world the navigator's higher level did "
            "not learn (a file, or 'random': unseen generated 5 x 5 mazes), only the higher level "
            "is trained there first, for at most 200 episodes per maze."
        ),
    )
    evaluate.add_argument(
        "--policy",
        default=None,
        metavar="DIR",
        help="folder of a saved navigator (default: the one shipped for seed-maze)",
    )
    evaluate.add_argument(
        "--world",
        default=None,
        metavar="NAME|PATH|random",
        help="a built-in world, a world file, or 'random' for unseen generated mazes "
        "(default: the navigator's world)",
    )
    evaluate.add_argument(
        "--episodes",
        type=positive_int,
        default=200,
        metavar="N",
        help="evaluation episodes (with 'random': spread over --mazes mazes) "
        "(default: %(default)s)",
    )
    evaluate.add_argument(
        "--mazes",
        type=positive_int,
        default=100,
        metavar="M",
        help="unseen mazes of --world random (default: %(default)s)",
    )
    evaluate.add_argument(
        "--seed",
        type=seed_argument,
        default=0,
        metavar="S",
        help="seed of the episodes' start jitter and sensor noise, and of the random mazes "
        "(default: %(default)s)",
    )
    evaluate.add_argument(
        "--events",
        choices=(*EVENT_SOURCES, "both"),
        default="both",
        help="checkpoint events from the simulator's ground truth, from the robust barcode "
        "decoder, or both, reported side by side (default: %(default)s)",
    )
    evaluate.add_argument(
        "--max-steps",
        type=positive_int,
        default=DEFAULT_MAX_STEPS,
        metavar="N",
        help="control steps (64 ms) after which an episode fails (default: %(default)s)",
    )
    evaluate.add_argument(
        "--json",
        action="store_true",
        help='print one JSON object: {"episodes", "success_rate", "mean_collisions", '
        '"mean_steps", "mean_path_ratio", ...}',
    )
    evaluate.add_argument(
        "--trace",
        type=output_path,
        default=None,
        metavar="FILE",
        help="write the per-step trace of the first episode (as the report's Fig. 4.7)",
    )
    evaluate.add_argument(
        "--plot",
        type=output_path,
        default=None,
        metavar="FILE",
        help="draw the first episodes' trajectories on the maze into a PNG (Fig. 4.6 / 4.8)",
    )
    evaluate.add_argument(
        "--address",
        default=None,
        metavar="ADDR",
        help="spread the episodes over Ray: 'local' starts a Ray instance on this machine for "
        "the evaluation; 'auto', HOST:6379 or ray://HOST:10001 joins a running cluster (every "
        "machine needs the same mazesim and 'pip install mazesim[ray]'). The results are the "
        "same as without it (default: no Ray, every episode in this process)",
    )
    add_viewing_options(evaluate)
    evaluate.set_defaults(run=lambda args: run_eval(args, sys.stdout))


def run_eval(args: argparse.Namespace, out: TextIO) -> int:
    """Runs ``mazesim eval``."""
    from mazesim.hrl.evaluate import (
        evaluate_navigator,
        print_summary,
    )
    from mazesim.hrl.tables import load_policy

    policy_files = [
        (f"the navigator's {name}", Path(args.policy) / name)
        for name in ("policy.json", "tables.npz")
        if args.policy is not None
    ]
    refuse_overwriting_inputs(
        [("--trace", args.trace), ("--plot", args.plot)],
        [*policy_files, ("--world", args.world)],
    )
    policy = load_policy(args.policy)
    if args.world == "random":
        from mazesim.hrl.evaluate import unseen_mazes

        worlds = unseen_mazes(args.mazes, args.seed)
        per_world = max(1, math.ceil(args.episodes / len(worlds)))
        label = f"{len(worlds)} unseen generated 5 x 5 mazes"
    else:
        worlds = [load_world(args.world if args.world is not None else policy.world_name)]
        per_world = args.episodes
        label = worlds[0].name
    sources = list(EVENT_SOURCES) if args.events == "both" else [args.events]
    with contextlib.ExitStack() as ray:
        if args.address is not None:
            from mazesim.distributed.cluster import ray_session

            ray.enter_context(ray_session(args.address))  # one Ray session for every source
        report = evaluate_navigator(
            policy,
            worlds,
            per_world,
            seed=args.seed,
            sources=sources,
            max_steps=args.max_steps,
            trace_path=args.trace,
            plot_path=args.plot,
            ray_address=args.address,
            record_runs=min(per_world, RECORDED_EPISODES) if recording_requested(args) else 0,
        )
    if report.run is not None:
        report.written += write_views(
            args, report.run, f"{label}: {policy.kind} navigator, seed {args.seed}"
        )
    if args.json:
        first = report.summaries[sources[0]]
        values: dict[str, Any] = first.as_json()
        for source in sources[1:]:
            values[f"{source}_decoder"] = report.summaries[source].as_json()
        out.write(json.dumps(values) + "\n")
        return 0
    source_names = {
        "truth": "checkpoint events from the ground truth",
        "robust": ("checkpoint events read by the robust barcode decoder"),
    }
    out.write(f"navigator {policy.source} ({policy.kind}) in {label}, seed {args.seed}\n")
    if report.adapted:
        out.write(
            "  the higher level was trained here first (lower-level tables kept, "
            "at most 200 episodes per maze)\n"
        )
    for source in sources:
        print_summary(report.summaries[source], out, source_names[source])
    for path in report.written:
        out.write(f"wrote {path}\n")
    return 0
