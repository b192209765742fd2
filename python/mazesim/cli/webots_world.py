"""``mazesim webots run WORLD.wbt``: every robot of a Webots world with its own controller."""

from __future__ import annotations

import argparse
import json
import os
import sys
from typing import Any, TextIO

from mazesim._atomic import atomic_file
from mazesim.errors import InvalidArgumentError

__all__ = ["robot_controllers", "run_world_command"]


def robot_controllers(pairs: list[str] | None) -> dict[str, str]:
    """The ``--robot-controller NAME=FILE`` arguments as {robot: controller file}.

    Raises:
        InvalidArgumentError: An argument is not NAME=FILE.
    """
    given: dict[str, str] = {}
    for pair in pairs or []:
        name, _, file = pair.partition("=")
        if not name or not file:
            raise InvalidArgumentError(
                f"--robot-controller expects NAME=FILE (a robot's name, DEF name or controller "
                f"field, then a controller file or folder), found {pair!r}"
            )
        given[name] = file
    return given


def run_world_command(args: argparse.Namespace, out: TextIO) -> int:
    """Runs every robot of a ``.wbt`` world and writes the picture and summary of all of them.

    Returns:
        A supervisor's quit status, else the first controller's non-zero exit status, else 0.
    """
    import mazesim
    from mazesim._paths import open_input
    from mazesim.plotting import save_robot_paths_png
    from mazesim.webots.lockstep import run_world
    from mazesim.webots.runner import controller_file

    asked = [
        f"--{name}" for name in ("html", "video", "record", "live", "keys") if getattr(args, name)
    ]
    if asked:  # a world run writes no replay yet: refused rather than silently not written
        raise InvalidArgumentError(
            f"{', '.join(asked)}: expected a run of one controller, found a run of the world "
            f"{args.controller!r}, which writes only DIR/trajectory.png, DIR/summary.json and "
            f"DIR/trajectory.csv; for a replay, run one robot's controller with --world"
        )
    given = {
        name: controller_file(file)
        for name, file in robot_controllers(args.robot_controller).items()
    }
    for file in given.values():
        open_input(file, "the controller").close()  # a regular file, readable, before any run
    out_dir = os.path.abspath(args.out)
    os.makedirs(out_dir, exist_ok=True)
    run = run_world(
        args.controller,
        seconds=args.seconds,
        seed=args.seed,
        noise=not args.no_noise,
        controllers=given,
    )
    for robot in run.robots:
        if robot.note:
            print(
                f"mazesim: warning: robot {robot.name!r}: {robot.note}: it stands still",
                file=sys.stderr,
            )
        if robot.error:
            sys.stderr.write(robot.error)
    robots: list[dict[str, Any]] = [
        {
            "name": robot.name,
            "model": robot.model,
            "controller": robot.controller,
            "note": robot.note or None,
            "distance_m": robot.distance_m,
            "collisions": robot.collisions,
            "final_pose": list(robot.final_pose),
            "exit_status": robot.exit_status,
            "controller_error": robot.error.strip().splitlines()[-1] if robot.error else None,
            "reached_end": robot.reached_end,
            "stopped_after_end": robot.stopped,
            "quit_requested": robot.quit_requested,
        }
        for robot in run.robots
    ]
    summary = {
        "world": run.world.name,
        "seed": args.seed,
        "simulated_seconds": run.simulated_seconds,
        "steps": run.steps,
        "robots": robots,
        "exit_status": run.exit_status,
        "wall_clock_seconds": run.wall_clock_seconds,
        "mazesim_version": mazesim.__version__,
    }
    picture = os.path.join(out_dir, "trajectory.png")
    save_robot_paths_png(
        run.world,
        [(robot.name, robot.xs, robot.ys) for robot in run.robots],
        picture,
        title=f"{run.world.name}: {len(run.robots)} robots, {run.simulated_seconds:.0f} s, "
        f"seed {args.seed}",
    )
    summary_path = os.path.join(out_dir, "summary.json")
    with atomic_file(summary_path) as handle:
        handle.write((json.dumps(summary, indent=2) + "\n").encode("utf-8"))
    table = os.path.join(out_dir, "trajectory.csv")
    step_s = run.simulated_seconds / run.steps if run.steps else 0.0
    with atomic_file(table) as handle:
        rows = [
            f"{robot.name},{i * step_s:.3f},{x:.5f},{y:.5f}"
            for robot in run.robots
            for i, (x, y) in enumerate(zip(robot.xs, robot.ys))
        ]
        handle.write(("robot,time_s,x_m,y_m\n" + "\n".join(rows) + "\n").encode("utf-8"))
    out.write(
        f"world              {run.world.name} (seed {args.seed}, {len(run.robots)} robots)\n"
        f"simulated time     {run.simulated_seconds:.2f} s ({run.steps} steps)\n"
    )
    for robot in run.robots:
        ran = os.path.basename(robot.controller) if robot.controller else robot.note
        out.write(
            f"  {robot.name:<16} {ran}: {robot.distance_m:.2f} m, "
            f"{robot.collisions} collisions, exit {robot.exit_status}\n"
        )
    out.write(f"wrote              {', '.join([picture, summary_path, table])}\n")
    return run.exit_status
