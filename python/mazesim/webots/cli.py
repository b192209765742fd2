"""The ``mazesim import-wbt`` and ``mazesim webots run`` commands."""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
from typing import Any, TextIO

from mazesim._atomic import atomic_file
from mazesim._paths import output_files, refuse_overwriting_inputs
from mazesim.cli import output_path, positive_seconds, seed_argument

__all__ = ["register"]


def register(commands: Any) -> None:
    """Adds ``import-wbt`` and ``webots run`` to the command line."""
    importer = commands.add_parser(
        "import-wbt",
        help="import a Webots .wbt world (obstacles, robot pose, time step)",
        description=(
            "Import a Webots world file (any version from V8.5 to R2025a, NUE or ENU): every "
            "collision shape that meets the e-puck's height becomes a wall, the e-puck's pose "
            "the start, WorldInfo.basicTimeStep the time step. Prints a summary with the "
            "warnings (what was not imported or was approximated); --json prints the import as "
            "one JSON object instead. Lengths in metres, angles in radians, world frame, z up."
        ),
    )
    importer.add_argument("file", metavar="FILE", help="the .wbt world file")
    importer.add_argument(
        "--out",
        type=output_path,
        metavar="WORLD_FILE",
        help="also write the imported world as a mazesim world file (.toml)",
    )
    importer.add_argument(
        "--json",
        action="store_true",
        help='print {"obstacles": [...], "robot": {...} | null, "basic_time_step_ms": t, '
        '"warnings": [...]} and nothing else',
    )
    importer.set_defaults(run=lambda args: run_import(args, sys.stdout))

    webots = commands.add_parser(
        "webots",
        help="run Webots-style e-puck controllers on mazesim",
        description="Run Webots-style Python controllers of the e-puck on mazesim.",
    )
    actions = webots.add_subparsers(dest="webots_command", metavar="COMMAND", required=True)
    run = actions.add_parser(
        "run",
        help="run an unmodified Webots controller file headless",
        description=(
            "Run an unmodified Webots e-puck controller (its 'from controller import Robot' "
            "gets mazesim's controller module) headless until 'robot.step' returns -1 after "
            "--seconds, then print a summary and write DIR/trajectory.png and DIR/summary.json."
        ),
    )
    run.add_argument("controller", metavar="CONTROLLER.py", help="the controller's Python file")
    run.add_argument(
        "--world",
        default="arena",
        metavar="NAME|PATH|FILE.wbt",
        help="a built-in world, a mazesim world file or a Webots world (default: %(default)s)",
    )
    run.add_argument(
        "--seconds",
        type=positive_seconds,
        default=60.0,
        metavar="S",
        help="simulated seconds before robot.step returns -1 (default: %(default)s)",
    )
    run.add_argument(
        "--seed",
        type=seed_argument,
        default=0,
        metavar="N",
        help="seed of the sensor noise (default: %(default)s)",
    )
    run.add_argument(
        "--out",
        type=output_path,
        default="mazesim-webots",
        metavar="DIR",
        help="folder for trajectory.png and summary.json, created if missing "
        "(default: %(default)s)",
    )
    run.add_argument("--no-noise", action="store_true", help="noise-free sensors")
    run.set_defaults(run=lambda args: run_webots(args, sys.stdout))


def _pose(robot: Any) -> str:
    if robot is None:
        return "none (the robot starts at the origin facing +x)"
    return f"x {robot['x']:.4f} m, y {robot['y']:.4f} m, yaw {robot['yaw']:.4f} rad"


def run_import(args: argparse.Namespace, out: TextIO) -> int:
    """Imports a .wbt file, prints the summary or the JSON, writes the world if asked."""
    from mazesim.webots.importer import import_wbt

    if args.out:
        refuse_overwriting_inputs([("--out", args.out)], [("the Webots world", args.file)])
    world, report = import_wbt(args.file)
    if args.out:
        world.save(args.out)
    if args.json:
        out.write(json.dumps(report) + "\n")
        return 0
    kinds = [obstacle["kind"] for obstacle in report["obstacles"]]
    out.write(
        f"world              {world.name} (from {args.file})\n"
        f"obstacles          {kinds.count('box')} boxes, {kinds.count('circle')} circles "
        f"({len(world.wall_boxes())} walls in the mazesim world)\n"
        f"robot start        {_pose(report['robot'])}\n"
        f"basic time step    {report['basic_time_step_ms']:g} ms\n"
        f"warnings           {len(report['warnings'])}\n"
    )
    for warning in report["warnings"]:
        out.write(f"  - {warning}\n")
    if args.out:
        out.write(f"wrote              {args.out}\n")
    return 0


def run_webots(args: argparse.Namespace, out: TextIO) -> int:
    """Runs a controller file and writes its trajectory picture and summary."""
    import mazesim
    from mazesim.plotting import save_trajectory_png
    from mazesim.webots.runner import run_controller

    world = mazesim.load_world(args.world)
    out_dir = os.path.abspath(args.out)
    refuse_overwriting_inputs(
        output_files(out_dir, ("trajectory.png", "summary.json")),
        [("the controller", args.controller), ("--world", args.world)],
    )
    # Fail before the run, not after it, if the output folder cannot be made.
    os.makedirs(out_dir, exist_ok=True)
    result = run_controller(
        args.controller, world, seconds=args.seconds, seed=args.seed, noise=not args.no_noise
    )
    name = os.path.basename(result.controller)
    wall_clock = result.wall_clock_seconds
    summary: dict[str, Any] = {
        "world": world.name,
        "controller": result.controller,
        "seed": args.seed,
        "simulated_seconds": result.simulated_seconds,
        "steps": result.steps,
        "distance_m": result.distance_m,
        "collisions": result.collisions,
        "longest_stop_s": result.longest_stop_s,
        "reached_end": result.reached_end,
        "wall_clock_seconds": wall_clock,
        "real_time_factor": result.simulated_seconds / wall_clock if wall_clock > 0 else None,
        "mazesim_version": mazesim.__version__,
    }
    picture = os.path.join(out_dir, "trajectory.png")
    save_trajectory_png(
        world,
        result.xs,
        result.ys,
        picture,
        title=f"{world.name}: {name}, {result.simulated_seconds:.0f} s, seed {args.seed}",
    )
    summary_path = os.path.join(out_dir, "summary.json")
    with atomic_file(summary_path) as handle:
        handle.write((json.dumps(summary, indent=2) + "\n").encode("utf-8"))
    factor = summary["real_time_factor"]
    speed = "n/a" if factor is None or not math.isfinite(factor) else f"{factor:.0f}x"
    ending = "robot.step returned -1" if result.reached_end else "the controller returned"
    out.write(
        f"world              {world.name} (seed {args.seed})\n"
        f"controller         {name} ({ending})\n"
        f"simulated time     {result.simulated_seconds:.2f} s ({result.steps} steps)\n"
        f"distance travelled {result.distance_m:.2f} m\n"
        f"collisions         {result.collisions}\n"
        f"longest stop       {result.longest_stop_s:.2f} s\n"
        f"wall-clock time    {wall_clock:.3f} s ({speed} real time)\n"
        f"wrote              {picture}, {summary_path}\n"
    )
    return 0
