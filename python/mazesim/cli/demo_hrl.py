"""``mazesim demo --controller hrl``: the shipped navigator driving a maze to its goal.

One episode from the world's start (sensor noise from ``--seed``, no start jitter) with the
navigator shipped for the world; it writes ``DIR/trajectory.png`` (the path, numbered where the
higher level chose a sub-task), ``DIR/trace.txt`` (the report's Fig. 4.7 style, step by step)
and ``DIR/summary.json``, and prints a summary.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time
from typing import Any, TextIO

import numpy as np
import numpy.typing as npt

import mazesim
from mazesim import InvalidArgumentError
from mazesim._atomic import atomic_file
from mazesim._paths import make_output_folder, shell_command
from mazesim.cli.demo import HRL_DEFAULT_SECONDS, speed_summary
from mazesim.cli.progress import progress_display
from mazesim.episodes import StartJitter, shortest_path_steps
from mazesim.learn.evaluate import ADAPT_EPISODES, EvaluationRecord, evaluate, navigator_for
from mazesim.learn.evaluation_text import trace_text
from mazesim.learn.figures import save_episodes_png
from mazesim.learn.policy import HierarchicalPolicy
from mazesim.learn.subtasks import CONTROL_STEP_MS, SUBTASK_NAMES
from mazesim.learn.summary import summarise
from mazesim.learn.tables import load_policy
from mazesim.learn.train import refuse_unlearnable
from mazesim.maze import world_hash
from mazesim.replay.navigator import Recording
from mazesim.replay.views import play_live, recording_requested, write_views, written_lines

__all__ = ["run_hrl_demo"]


def run_hrl_demo(args: argparse.Namespace, out: TextIO) -> int:
    """Runs the navigator demo (``args``: world, seconds, seed, out)."""
    if getattr(args, "robot", None) is not None:
        raise InvalidArgumentError(
            f"--robot {args.robot}: mazesim demo --controller hrl drives the shipped navigator "
            "on the seed robot it was trained for, and takes no other robot; to watch the "
            f"navigator drive {args.robot}: "
            + shell_command("mazesim", "eval", "--robot", args.robot, "--episodes", "1")
            + " --html run.html"
        )
    world = mazesim.load_world(args.world)
    refuse_unlearnable(world, args.world, "drive")
    policy = load_policy()
    make_output_folder(args.out)
    adapt_seconds = None
    if world_hash(world) != policy.world_sha256:
        out.write(
            f"training the higher level in {world.name} first (at most {ADAPT_EPISODES} "
            "episodes; the shipped lower level is kept)\n"
        )
        out.flush()
        adapting = time.perf_counter()
        with progress_display(args, units={"adapt": "episodes"}) as progress:
            level, adapted = navigator_for(policy, [world], seed=args.seed, progress=progress)
        adapt_seconds = time.perf_counter() - adapting
    else:
        level, adapted = navigator_for(policy, [world], seed=args.seed)
    lower_q = policy.lower_q
    assert lower_q is not None

    def make_navigator(world_of_env: npt.NDArray[np.int64]) -> HierarchicalPolicy:
        return HierarchicalPolicy(lower_q, level, world_of_env, hold_heading=policy.hold_heading)

    seconds = HRL_DEFAULT_SECONDS if args.seconds is None else args.seconds
    steps = max(1, math.ceil(seconds * 1000.0 / CONTROL_STEP_MS - 1e-9))
    started = time.perf_counter()
    live = getattr(args, "live", False)
    record = EvaluationRecord(
        paths=1, trace=True, recorder=Recording(1) if recording_requested(args) or live else None
    )
    evaluate(
        make_navigator,
        [world],
        1,
        seed=args.seed,
        jitter=StartJitter(0.0, 0.0),
        max_steps=steps,
        record=record,
        controller="hrl (shipped navigator)",
    )
    wall_clock = time.perf_counter() - started
    result = record.outcomes[0]
    path = record.episode_paths.get(0, np.zeros((0, 2)))
    distance = float(np.sum(np.hypot(*np.diff(path, axis=0).T))) if len(path) > 1 else 0.0
    simulated = result.steps * CONTROL_STEP_MS / 1000.0
    decisions = [
        {"event": event, "subtask": SUBTASK_NAMES[option]} for event, option in result.decisions
    ]
    summary: dict[str, Any] = {
        "world": world.name,
        "robot": "seed",
        "seed": args.seed,
        "controller": "hrl",
        "navigator": "shipped" if not adapted else "shipped lower level, higher level trained here",
        "simulated_seconds": simulated,
        "steps": result.steps,
        "distance_m": distance,
        "collisions": result.bumps,
        "goal_reached": result.arrived,
        "path_ratio": summarise([result], [shortest_path_steps(world)]).mean_path_ratio,
        "decisions": decisions,
        **speed_summary(simulated, wall_clock),
    }
    picture = os.path.join(args.out, "trajectory.png")
    cut = not result.arrived and result.steps >= steps
    outcome = (
        "reached the goal"
        if result.arrived
        else f"stopped by the time limit ({seconds:g} s) before the goal"
        if cut
        else "did not reach the goal"
    )
    save_episodes_png(
        world,
        record.episode_paths,
        record.marks,
        picture,
        title=f"{world.name}: hierarchical navigator, seed {args.seed}, {outcome} "
        f"in {simulated:.1f} s",
        arrived={0: result.arrived},
    )
    trace = os.path.join(args.out, "trace.txt")
    with atomic_file(trace) as handle:
        handle.write(trace_text(record.trace_lines, world, args.seed, "truth").encode("utf-8"))
    summary_path = os.path.join(args.out, "summary.json")
    with atomic_file(summary_path) as handle:
        handle.write((json.dumps(summary, indent=2) + "\n").encode("utf-8"))
    title = f"{world.name}: the hierarchical navigator, seed {args.seed}, {outcome}"
    views = [] if record.run is None else write_views(args, record.run, title)
    if live and record.run is not None:
        play_live(record.run, title)
    limit = (
        f": the time limit of {seconds:g} simulated seconds ended the run first; "
        f"give it longer with --seconds {2 * seconds:g}"
        if cut
        else ""
    )
    adapt = (
        "" if adapt_seconds is None else f", and {adapt_seconds:.1f} s training the higher level"
    )
    chosen = ", ".join(f"{d['event']:+d}: {d['subtask']}" for d in decisions)
    if chosen:  # what the numbers are, where a newcomer first meets them
        chosen += (
            " (the sub-task chosen at each barcode: +N arriving at checkpoint N, -N leaving it)"
        )
    else:
        chosen = "none"
    out.write(
        f"world              {world.name} (robot seed, hierarchical navigator, seed {args.seed})\n"
        f"simulated time     {simulated:.2f} s ({result.steps} steps of {CONTROL_STEP_MS:.0f} ms)\n"
        f"distance travelled {distance:.2f} m\n"
        f"collisions         {result.bumps}\n"
        f"goal reached       {'yes' if result.arrived else 'no'}{limit}\n"
        f"decisions          {chosen}\n"
        f"wall-clock time    {wall_clock:.3f} s (the run){adapt}\n"
        + written_lines(args, picture, [picture, trace, summary_path, *views])
    )
    return 0
