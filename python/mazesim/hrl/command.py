"""``mazesim train`` and ``mazesim eval``: training and evaluating the hierarchical navigator.

``mazesim train`` trains from scratch (or, with ``--resume``, continues a stopped run) and saves
the navigator into ``--out``; ``--flat`` trains the flat baseline instead, for the same budget.
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
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any, TextIO

from mazesim import load_world
from mazesim._paths import output_files, output_path, refuse_overwriting_inputs
from mazesim.cli import positive_int, seed_argument
from mazesim.episodes import EVENT_SOURCES
from mazesim.episodes import MAX_STEPS as EPISODE_STEP_LIMIT
from mazesim.errors import InvalidArgumentError
from mazesim.replay.navigator import Recording
from mazesim.replay.options import add_viewing_options, recording_requested, write_views

__all__ = ["register", "run_eval", "run_train", "step_count"]

DEFAULT_OUT = "mazesim-policy"
#: Episodes that ``eval --html/--video/--record`` records (the first ones of the first world).
RECORDED_EPISODES = 3


#: The most env-steps a training run takes (the shipped navigator took 3.6e7).
MAX_STEPS = 10**12


class ProgressLine:
    """A one-line progress display with an ETA, redrawn in place: ``progress(stage, done, total)``.

    Args:
        stream: Where the line goes (a terminal).
    """

    def __init__(self, stream: TextIO) -> None:
        self.stream = stream
        self.stage = ""
        self.started = time.perf_counter()
        self.shown = False

    def __call__(self, stage: str, done: int, total: int) -> None:
        now = time.perf_counter()
        if stage != self.stage:
            self.stage, self.started = stage, now
        share = done / total if total else 1.0
        elapsed = now - self.started
        eta = f"ETA {elapsed * (1.0 - share) / share:4.0f} s" if share > 0 else "ETA    ? s"
        filled = int(round(24 * share))
        self.stream.write(
            f"\r\033[K{stage} [{'#' * filled}{'.' * (24 - filled)}] {100 * share:3.0f}% "
            f"{done}/{total}  {elapsed:4.0f} s  {eta}"
        )
        self.stream.flush()
        self.shown = True

    def close(self) -> None:
        """Clears the line."""
        if self.shown:
            self.stream.write("\r\033[K")
            self.stream.flush()
            self.shown = False


@contextlib.contextmanager
def progress_display(stream: TextIO | None = None) -> Iterator[ProgressLine | None]:
    """A :class:`ProgressLine` on ``stream`` (standard error by default) when it is a terminal,
    else None; the line is cleared at the end."""
    target = sys.stderr if stream is None else stream
    line = ProgressLine(target) if target.isatty() else None
    try:
        yield line
    finally:
        if line is not None:
            line.close()


def step_count(text: str) -> int:
    """A number of env-steps: a whole number, optionally with a k or M suffix (``36M``)."""
    cleaned = text.strip().replace("_", "")
    scale = 1
    if cleaned[-1:] in ("k", "K"):
        scale, cleaned = 1_000, cleaned[:-1]
    elif cleaned[-1:] in ("m", "M"):
        scale, cleaned = 1_000_000, cleaned[:-1]
    try:
        value = float(cleaned) * scale
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected a number of env-steps such as 36000000, 36M or 500k, found {text!r}"
        ) from None
    if not math.isfinite(value) or not 1 <= value <= MAX_STEPS:
        raise argparse.ArgumentTypeError(
            f"expected a number of env-steps in [1, {MAX_STEPS:.0e}], found {text!r}"
        )
    return int(value)


def register(commands: Any) -> None:
    """Adds ``train`` and ``eval`` to the ``mazesim`` command's subparsers."""
    from mazesim.learn.train import TrainSettings

    defaults = TrainSettings()
    train = commands.add_parser(
        "train",
        help="train the hierarchical navigator (lower level on generated mazes, higher level on "
        "the world)",
        description=(
            "Train the hierarchical Q-learning navigator from scratch: the four sub-tasks on "
            "generated mazes with many robots at once, then the higher level on --world. "
            "Checkpoints are written to --out as it goes; --resume continues a stopped run to the "
            "same tables as an uninterrupted one. The navigator is saved as "
            "--out/tables.npz and --out/policy.json. A progress line with an ETA "
            "shows on a terminal."
        ),
    )
    train.add_argument(
        "--world",
        default=defaults.world,
        metavar="NAME|PATH",
        help="the world the higher level learns: a built-in name or a world file "
        "(default: %(default)s)",
    )
    train.add_argument(
        "--envs",
        type=positive_int,
        default=defaults.envs,
        metavar="N",
        help="robots stepped at once while training the lower level (default: %(default)s)",
    )
    train.add_argument(
        "--steps",
        type=step_count,
        default=defaults.steps,
        metavar="K",
        help="env-steps of lower-level training, e.g. 36M or 500k (default: %(default)s)",
    )
    train.add_argument(
        "--seed",
        type=seed_argument,
        default=defaults.seed,
        metavar="S",
        help="seed of everything random in the run (default: %(default)s)",
    )
    train.add_argument(
        "--out",
        type=output_path,
        default=DEFAULT_OUT,
        metavar="DIR",
        help="folder for the checkpoint and the navigator (default: %(default)s)",
    )
    train.add_argument(
        "--resume",
        action="store_true",
        help="continue the run whose checkpoint is in --out (same settings)",
    )
    train.add_argument(
        "--flat",
        action="store_true",
        help="train the flat Q-learning baseline on --world instead, for --steps env-steps",
    )
    train.set_defaults(run=lambda args: run_train(args, sys.stdout))

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
        default=EPISODE_STEP_LIMIT,
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


def run_train(args: argparse.Namespace, out: TextIO) -> int:
    """Runs ``mazesim train``."""
    from mazesim.learn.train import TrainSettings, train, train_flat_policy

    refuse_overwriting_inputs(
        output_files(args.out, ("tables.npz", "policy.json", "checkpoint.npz")),
        [("--world", args.world)],
    )
    settings = TrainSettings(world=args.world, envs=args.envs, steps=args.steps, seed=args.seed)
    started = time.perf_counter()
    if args.flat:
        if args.resume:
            raise InvalidArgumentError("--resume continues hierarchical runs only, not --flat")
        with progress_display() as progress:
            policy = train_flat_policy(settings, args.out, progress=progress)
        seconds = time.perf_counter() - started
        out.write(
            f"trained the flat baseline for {policy.world_name} in {seconds:.0f} s "
            f"({settings.steps} env-steps)\nwrote {Path(args.out) / 'tables.npz'}, "
            f"{Path(args.out) / 'policy.json'}\n"
        )
        return 0
    with progress_display() as progress:
        result = train(settings, args.out, resume=args.resume, progress=progress)
    if result is None:
        return 0
    seconds = time.perf_counter() - started
    info = result.training
    out.write(
        f"trained a navigator for {result.world_name} in {seconds:.0f} s "
        f"(lower level {info['lower_seconds']:.0f} s, {info['lower_env_steps']} env-steps; "
        f"higher level {info['higher_seconds']:.0f} s)\n"
        f"higher-level training: {100 * info['higher_success_last_100']:.0f}% of the last 100 "
        f"episodes reached the goal\n"
        f"wrote {Path(args.out) / 'tables.npz'}, {Path(args.out) / 'policy.json'}\n"
        f"evaluate it with: mazesim eval --policy {args.out}\n"
    )
    return 0


def run_eval(args: argparse.Namespace, out: TextIO) -> int:
    """Runs ``mazesim eval``."""
    from mazesim.learn.evaluate import (
        evaluate_navigator,
        print_summary,
    )
    from mazesim.learn.tables import load_policy

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
        from mazesim.learn.evaluate import unseen_mazes

        worlds = unseen_mazes(args.mazes, args.seed)
        per_world = max(1, math.ceil(args.episodes / len(worlds)))
        label = f"{len(worlds)} unseen generated 5 x 5 mazes"
    else:
        worlds = [load_world(args.world if args.world is not None else policy.world_name)]
        per_world = args.episodes
        label = worlds[0].name
    sources = list(EVENT_SOURCES) if args.events == "both" else [args.events]
    with contextlib.ExitStack() as ray, progress_display() as progress:
        if args.address is not None:
            from mazesim.distributed.cluster import ray_session
            from mazesim.distributed.episodes import ray_spreader

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
            spread=None if args.address is None else ray_spreader(args.address),
            recorder=(
                Recording(min(per_world, RECORDED_EPISODES)) if recording_requested(args) else None
            ),
            progress=progress,
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
