"""``mazesim demo``: the robot driven headless, its path plotted.

By default the e-puck runs the report's avoid-collision controller (Alg. 1) for ``--seconds``;
``--controller hrl`` hands the run to :mod:`mazesim.cli.demo_hrl`, the shipped hierarchical
navigator driving the seed robot to the goal. Both print a summary and write
``DIR/trajectory.png`` and ``DIR/summary.json``. A world of several robots runs every robot
(:mod:`mazesim.cli.demo_robots`).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from typing import Any, TextIO

from mazesim._paths import make_output_folder, output_files, refuse_overwriting_inputs
from mazesim._sizes import number_array
from mazesim.cli._args import add_out_folder, add_seed_option, positive_seconds
from mazesim.cli._help import examples
from mazesim.cli.progress import add_progress_option, progress_display
from mazesim.replay.views import add_viewing_options, viewing_outputs

__all__ = ["DEFAULT_SECONDS", "HRL_DEFAULT_SECONDS", "run_demo"]

#: Simulated seconds a demo runs without ``--seconds``.
DEFAULT_SECONDS = 60.0
#: The same for ``--controller hrl``: an evaluation episode's 4,000 control steps of 64 ms
#: (:data:`mazesim.episodes.MAX_STEPS`), so the demo gives up where an evaluation would.
HRL_DEFAULT_SECONDS = 256.0


def speed_summary(simulated_seconds: float, wall_clock: float) -> dict[str, Any]:
    """The summary entries of a run's speed: its wall-clock seconds, the simulated seconds per
    wall-clock second (None when no time could be measured) and the mazesim version that ran."""
    import mazesim

    return {
        "wall_clock_seconds": wall_clock,
        "real_time_factor": simulated_seconds / wall_clock if wall_clock > 0 else None,
        "mazesim_version": mazesim.__version__,
    }


def goal_summary(world: Any, xs: Any, ys: Any, step_s: float) -> dict[str, Any]:
    """The summary entries of whether a run's path (``xs``, ``ys``: the start, then a point every
    ``step_s`` seconds) entered ``world``'s goal disc: ``goal_reached`` and ``goal_time_s``, the
    simulated time it first did (both None in a world without a goal; the time None when it
    never did)."""
    import numpy as np

    if world.goal is None:
        return {"goal_reached": None, "goal_time_s": None}
    goal_x, goal_y, radius = world.goal
    inside = np.flatnonzero(
        np.hypot(number_array(xs, "xs") - goal_x, number_array(ys, "ys") - goal_y) <= radius
    )
    first = float(inside[0] * step_s) if inside.size else None
    return {"goal_reached": first is not None, "goal_time_s": first}


def goal_line(summary: dict[str, Any]) -> str:
    """The summary's printed line about the goal ("" in a world without one)."""
    if summary["goal_reached"] is None:
        return ""
    if not summary["goal_reached"]:
        return "goal reached       no\n"
    return f"goal reached       yes, at {summary['goal_time_s']:.2f} s\n"


def register(commands: Any) -> None:
    """Adds ``demo`` to the ``mazesim`` command's subparsers."""
    demo = commands.add_parser(
        "demo",
        help="drive the robot (avoid-collision or the shipped navigator) and plot its path",
        description=(
            "Drive the robot headless with the avoid-collision controller of the source report "
            "(Alg. 1: turn away when a front proximity sensor reads above 80), print a summary, "
            "and write DIR/trajectory.png and DIR/summary.json. With --controller hrl the "
            "shipped hierarchical navigator drives the report's seed robot to the goal instead "
            "(a maze world with a goal), and DIR/trace.txt lists its steps as the report's "
            "Fig. 4.7. On a world of several robots ([[robots]]) every robot runs the "
            "avoid-collision controller, and the summary, the picture, --html, --video, --live and "
            "--record cover them all."
        ),
        epilog=examples(
            "mazesim demo",
            "mazesim demo --controller hrl --html mazesim-demo/replay.html",
            "mazesim demo --world arena --seconds 120 --seed 3 --out runs/arena",
            "mazesim demo --world my-maze.toml --robot e-puck2 --video demo.mp4",
        ),
    )
    demo.add_argument(
        "--world",
        default="seed-maze",
        metavar="NAME|PATH",
        help="a built-in world name or a world file (default: %(default)s)",
    )
    demo.add_argument(
        "--seconds",
        type=positive_seconds,
        default=None,
        metavar="S",
        help=f"simulated seconds to run (default: {DEFAULT_SECONDS:.0f}; with --controller hrl: "
        f"{HRL_DEFAULT_SECONDS:.0f}, the 4,000 control steps an evaluation episode may take)",
    )
    add_seed_option(demo, "the sensor noise")
    add_out_folder(demo, "mazesim-demo", "trajectory.png and summary.json")
    demo.add_argument(
        "--robot",
        default=None,
        metavar="NAME",
        help="robot profile; the controller needs the e-puck's 8 proximity sensors "
        "(default: e-puck; --controller hrl drives the seed robot it was trained for)",
    )
    demo.add_argument(
        "--controller",
        choices=("avoid-collision", "hrl"),
        default="avoid-collision",
        help="avoid-collision (Alg. 1), or hrl: the shipped hierarchical navigator (Alg. 5) "
        "driving the report's seed robot to the goal, also writing DIR/trace.txt "
        "(default: %(default)s)",
    )
    add_viewing_options(demo, live=True)
    add_progress_option(demo)
    demo.set_defaults(run=lambda args: run_demo(args, sys.stdout))


def run_demo(args: argparse.Namespace, out: TextIO) -> int:
    """Runs the demo and writes its picture and summary."""
    refuse_overwriting_inputs(
        [
            *output_files(args.out, ("trajectory.png", "summary.json", "trace.txt")),
            *viewing_outputs(args),
        ],
        [("--world", args.world)],
    )
    if getattr(args, "controller", "avoid-collision") == "hrl":
        from mazesim.cli.demo_hrl import run_hrl_demo

        return run_hrl_demo(args, out)
    return run_avoid_collision_demo(args, out)


def run_avoid_collision_demo(args: argparse.Namespace, out: TextIO) -> int:
    """Runs the avoid-collision demo and writes its picture and summary."""
    import numpy as np

    import mazesim
    from mazesim._atomic import atomic_file
    from mazesim.cli.demo_robots import proximity_columns, run_robots_demo
    from mazesim.controllers import AvoidCollision
    from mazesim.maze import refuse_blocked_start
    from mazesim.plotting import save_trajectory_png
    from mazesim.replay.views import SimulatorWatch, written_lines

    world = mazesim.load_world(args.world)
    robot_name = "e-puck" if args.robot is None else args.robot
    refuse_blocked_start(world, args.world, robot_name)
    simulator = mazesim.Simulator(world, robot=robot_name, seed=args.seed)
    seconds = DEFAULT_SECONDS if args.seconds is None else args.seconds
    if simulator.num_robots > 1:
        return run_robots_demo(args, out, simulator, seconds)
    robot = simulator.robot
    # A profile file is named with its file: a copy of the e-puck's, edited, still says
    # name = "e-puck" inside, and the run must not read as the built-in robot's.
    robot_label = (
        robot.name
        if robot_name in mazesim.robot_profile_names()
        else f"{robot.name} from {robot_name}"
    )
    # ps0-ps7, wherever the profile lists them (the e-puck2 has its ToF beside them).
    columns = proximity_columns(robot)
    controller = AvoidCollision(max_speed=robot.max_wheel_speed)
    # Fail before the run, not after it, if the output folder cannot be made.
    make_output_folder(args.out)
    steps = max(1, math.ceil(seconds * 1000.0 / simulator.control_step_ms - 1e-9))

    xs = np.empty(steps + 1, dtype=np.float64)
    ys = np.empty(steps + 1, dtype=np.float64)
    xs[0], ys[0], _ = simulator.pose
    watch = SimulatorWatch(args, simulator, "avoid-collision", args.seed)
    contacts: list[tuple[float, float]] = []
    started = time.perf_counter()
    with progress_display(args, unit="steps") as progress:
        for step in range(1, steps + 1):
            left, right = controller(simulator.distance_sensors()[columns])
            watch.before_step(left, right)
            simulator.step(left, right)
            xs[step], ys[step], _ = simulator.pose
            if simulator.colliding:
                contacts.append((xs[step], ys[step]))
            progress("simulating", step, steps)
    wall_clock = time.perf_counter() - started

    goal = goal_summary(world, xs, ys, simulator.time / max(simulator.steps, 1))
    goal_reached = goal["goal_reached"]
    summary: dict[str, Any] = {
        "world": world.name,
        "robot": robot.name,
        "seed": args.seed,
        "controller": "avoid-collision",
        "simulated_seconds": simulator.time,
        "steps": simulator.steps,
        "distance_m": simulator.distance_travelled,
        "collisions": simulator.collisions,
        **goal,
        **speed_summary(simulator.time, wall_clock),
    }
    if robot_label != robot.name:  # the profile's own name, and the file it came from
        summary["robot_file"] = robot_name

    picture = os.path.join(args.out, "trajectory.png")
    save_trajectory_png(
        world,
        xs,
        ys,
        picture,
        title=f"{world.name}: avoid-collision, {simulator.time:.0f} s, seed {args.seed}",
        collisions=contacts,
    )
    summary_path = os.path.join(args.out, "summary.json")
    with atomic_file(summary_path) as handle:
        handle.write((json.dumps(summary, indent=2) + "\n").encode("utf-8"))
    views = watch.finish("goal reached" if goal_reached else f"{simulator.time:.0f} s up")

    speed = "n/a" if summary["real_time_factor"] is None else f"{summary['real_time_factor']:.0f}x"
    out.write(
        f"world              {world.name} (robot {robot_label}, seed {args.seed})\n"
        f"simulated time     {simulator.time:.2f} s ({simulator.steps} steps)\n"
        f"distance travelled {simulator.distance_travelled:.2f} m\n"
        f"collisions         {simulator.collisions}\n"
    )
    out.write(goal_line(summary))
    out.write(
        f"wall-clock time    {wall_clock:.3f} s ({speed} real time)\n"
        + written_lines(args, picture, [picture, summary_path, *views])
    )
    return 0
