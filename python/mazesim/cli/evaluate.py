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
from dataclasses import fields
from pathlib import Path
from typing import Any, TextIO

from mazesim import World, load_world
from mazesim._figures import figure_file
from mazesim._paths import refuse_overwriting_inputs
from mazesim.cli._args import add_setting_options, output_path, seed_argument
from mazesim.cli._help import examples
from mazesim.cli.progress import add_progress_option, progress_display
from mazesim.errors import UnknownNameError, _shown
from mazesim.replay.navigator import Recording
from mazesim.replay.views import (
    add_viewing_options,
    recording_requested,
    viewing_outputs,
    write_views,
)

__all__ = ["run_eval"]

#: Episodes that ``eval --html/--video/--record`` records (the first ones of the first world).
RECORDED_EPISODES = 3
#: The ``--world`` that stands for unseen generated 5 x 5 mazes.
RANDOM_WORLD = "random"
#: Episodes whose paths ``eval --plot`` draws (the first ones of the first world).
PLOTTED_EPISODES = 3


def _write_trace_and_plot(
    args: argparse.Namespace, record: Any, summary: Any, world: Any, source: str, kind: str
) -> list[str]:
    """Writes ``--trace`` and ``--plot`` of the first source's episodes; returns their paths."""
    from mazesim._atomic import atomic_file
    from mazesim.learn.evaluation_text import trace_text

    written = []
    if args.trace is not None:
        text = trace_text(record.trace_lines, world, args.seed, source)
        with atomic_file(args.trace) as handle:
            handle.write(text.encode("utf-8"))
        written.append(str(args.trace))
    if args.plot is not None:
        from mazesim.learn.figures import save_episodes_png

        save_episodes_png(
            world,
            record.episode_paths,
            record.marks,
            args.plot,
            title=(
                f"{world.name}: {kind} navigator, seed {args.seed}; "
                f"{100 * summary.success_rate:.0f}% of {summary.episodes} episodes reached the goal"
            ),
            arrived={number: result.arrived for number, result in record.outcomes.items()},
        )
        written.append(str(args.plot))
    return written


def _world_or_random(name: str) -> World:
    """The world ``--world`` names, where 'random' (unseen generated mazes, which the caller
    makes) is one name more: a typo of it gets it as the one meant.

    Raises:
        UnknownNameError: Neither a built-in world nor a file; ends with the name meant.
    """
    try:
        return load_world(name)
    except UnknownNameError as unknown:
        if unknown.suggestion is not None:
            raise
        raise UnknownNameError(
            f"{unknown}, or {_shown(RANDOM_WORLD)} for unseen generated 5 x 5 mazes",
            available=[*(unknown.available or []), RANDOM_WORLD],
            name=name,
        ) from None


def _navigator_world(name: str) -> World:
    """The world ``--world`` names, refused as ``mazesim train`` refuses it when the navigator
    cannot drive it (no goal, a goal out of reach, no checkpoints), saying what to change."""
    from mazesim.learn.train import refuse_unlearnable

    world = _world_or_random(name)
    refuse_unlearnable(world, name, "drive")
    return world


def register(commands: Any) -> None:
    """Adds ``eval`` to the ``mazesim`` command's subparsers."""
    from mazesim.learn.evaluate import ADAPT_EPISODES, EvalSettings

    evaluate = commands.add_parser(
        "eval",
        help="measure a trained navigator: success, collisions, steps, decisions",
        description=(
            "Drive greedy episodes with a trained navigator (by default the one shipped for "
            "seed-maze) with sensor noise and a random start jitter of up to 2 cm and 10 degrees, "
            "and report the success rate, collisions, steps against the shortest path and the "
            "sub-tasks chosen at each checkpoint. In a world the navigator's higher level did "
            "not learn (a file, or 'random': unseen generated 5 x 5 mazes), only the higher level "
            f"is trained there first, for at most {ADAPT_EPISODES} episodes per maze. A navigator "
            "trained by 'mazesim train --world FILE' is evaluated in that file's world."
        ),
        epilog=examples(
            "mazesim eval",
            "mazesim eval --policy my-navigator",
            "mazesim eval --world random --mazes 10 --episodes 100",
            "mazesim eval --policy randomised --episodes 100 --events robust",
            "mazesim eval --episodes 1 --html run.html --trace trace.txt",
        ),
    )
    add_setting_options(
        evaluate,
        EvalSettings(),
        {"seed": seed_argument},  # the counts take their fields' declared ranges
    )
    evaluate.add_argument(
        "--json",
        action="store_true",
        help='print one JSON object: {"episodes", "success_rate", "mean_collisions", '
        '"mean_steps", "mean_path_ratio", ..., "measured": {"navigator", "world", "seed", ...}}',
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
        type=figure_file,
        default=None,
        metavar="FILE",
        help="draw the first episodes' trajectories on the maze into a PNG, or a PDF or SVG "
        "by its suffix (Fig. 4.6 / 4.8)",
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
    add_progress_option(evaluate)
    evaluate.set_defaults(run=lambda args: run_eval(args, sys.stdout))


def run_eval(args: argparse.Namespace, out: TextIO) -> int:
    """Runs ``mazesim eval``."""
    from mazesim.learn import EvaluationRecord, evaluate_navigator
    from mazesim.learn.evaluate import ADAPT_EPISODES, EvalSettings
    from mazesim.learn.evaluation_text import summary_text
    from mazesim.learn.tables import load_policy

    policy_files = [
        (f"the navigator's {name}", Path(args.policy) / name)
        for name in ("policy.json", "tables.npz")
        if args.policy is not None
    ]
    refuse_overwriting_inputs(
        [("--trace", args.trace), ("--plot", args.plot), *viewing_outputs(args)],
        [*policy_files, ("--world", args.world), ("--robot", args.robot)],
    )
    policy = load_policy(args.policy)
    if args.world == RANDOM_WORLD:
        from mazesim.learn.evaluate import unseen_mazes

        worlds = unseen_mazes(args.mazes, args.seed)
        per_world = max(1, math.ceil(args.episodes / len(worlds)))
        label = f"{len(worlds)} unseen generated 5 x 5 mazes"
    else:
        worlds = [_navigator_world(args.world) if args.world else policy.learned_world()]
        per_world = args.episodes
        label = worlds[0].name
    settings = EvalSettings(**{f.name: getattr(args, f.name) for f in fields(EvalSettings)})
    sources = settings.sources
    units = {"adapt": "episodes", "evaluate": "episodes", "evaluate robust": "episodes"}
    record = EvaluationRecord(
        paths=PLOTTED_EPISODES if args.plot is not None else 0,
        trace=args.trace is not None,
        recorder=(
            Recording(min(per_world, RECORDED_EPISODES)) if recording_requested(args) else None
        ),
    )
    with contextlib.ExitStack() as ray, progress_display(args, units=units) as progress:
        if args.address is not None:
            from mazesim.distributed.cluster import ray_session
            from mazesim.distributed.episodes import ray_spreader

            ray.enter_context(ray_session(args.address))  # one Ray session for every source
        summaries = evaluate_navigator(
            policy,
            worlds,
            per_world,
            seed=args.seed,
            sources=sources,
            max_steps=args.max_steps,
            record=record,
            spread=None if args.address is None else ray_spreader(args.address),
            progress=progress,
            robot=args.robot,
        )
    first = summaries[sources[0]]
    written = _write_trace_and_plot(args, record, first, worlds[0], sources[0], policy.kind)
    if record.run is not None:
        written += write_views(
            args, record.run, f"{label}: {policy.kind} navigator, seed {args.seed}"
        )
    if args.json:
        values: dict[str, Any] = first.as_json()
        for source in sources[1:]:
            values[f"{source}_decoder"] = summaries[source].as_json()
        # What was measured, so that results of several seeds or navigators compare side by side.
        values["measured"] = {
            "navigator": str(policy.source),
            "kind": policy.kind,
            "world": label,
            "seed": args.seed,
            "max_steps": args.max_steps,
            "robot": args.robot,
        }
        out.write(json.dumps(values) + "\n")
        return 0
    source_names = {
        "truth": "checkpoint events from the ground truth",
        "robust": ("checkpoint events read by the robust barcode decoder"),
    }
    out.write(f"navigator {policy.source} ({policy.kind}) in {label}, seed {args.seed}\n")
    if first.adapted:
        out.write(
            "  the higher level was trained here first (lower-level tables kept, "
            f"at most {ADAPT_EPISODES} episodes per maze)\n"
        )
    for source in sources:
        out.write(summary_text(summaries[source], source_names[source]))
    for path in written:
        out.write(f"wrote {path}\n")
    return 0
