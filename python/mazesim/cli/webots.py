"""The ``mazesim import-wbt`` and ``mazesim webots run`` commands."""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import sys
from typing import Any, TextIO

from mazesim._atomic import atomic_file
from mazesim._paths import (
    make_output_folder,
    output_files,
    output_path,
    refuse_overwriting_inputs,
    refuse_replacing_world_file,
)
from mazesim.cli._args import add_out_folder, add_seed_option, positive_seconds
from mazesim.cli._help import examples
from mazesim.cli.progress import ProgressDisplay, add_progress_option, progress_display
from mazesim.errors import InvalidArgumentError, _shown
from mazesim.replay.views import (
    DeferredWatch,
    add_viewing_options,
    viewing_outputs,
    viewing_requested,
    written_lines,
)

__all__: list[str] = []


#: The world of a controller's run without --world.
DEFAULT_WORLD = "arena"


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
        epilog=examples(
            "mazesim import-wbt Maze.wbt",
            "mazesim import-wbt Maze.wbt --out maze.toml",
            "mazesim import-wbt Maze.wbt --json",
        ),
    )
    importer.add_argument("file", metavar="FILE", help="the .wbt world file")
    importer.add_argument(
        "--out",
        type=output_path,
        metavar="WORLD_FILE",
        help="also write the imported world as a mazesim world file (.toml; refused if it "
        "exists, unless --force)",
    )
    importer.add_argument(
        "--force", action="store_true", help="with --out: overwrite WORLD_FILE if it exists"
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
        description="Run Webots-style e-puck controllers (Python, C or C++) on mazesim.",
        epilog=examples("mazesim webots run my_controller.py --world Maze.wbt"),
    )
    actions = webots.add_subparsers(dest="webots_command", metavar="COMMAND", required=True)
    run = actions.add_parser(
        "run",
        help="run an unmodified Webots controller file headless",
        description=(
            "Run an unmodified Webots e-puck controller (its 'from controller import Robot' "
            "gets mazesim's controller module) headless until 'robot.step' returns -1 after "
            "--seconds, then print a summary and write DIR/trajectory.png, DIR/summary.json and "
            "DIR/trajectory.csv "
            "(also when the controller raises, exits or is interrupted). The importer's "
            "warnings about a .wbt world are printed on stderr, each line prefixed with "
            "'mazesim: warning: ', and what the controller needs that is missing (a Webots "
            "feature, a Python package) with 'mazesim: missing: '. A C or C++ controller is "
            "built with gcc or g++ against mazesim's Webots C API (cached in "
            "~/.cache/mazesim/controllers) and run in lockstep."
        ),
        epilog=examples(
            "mazesim webots run my_controller.py",
            "mazesim webots run my_controller.py --world Maze.wbt --seconds 120 --strict",
            "mazesim webots run my_controller.py --keys keys.txt --html run.html",
            "mazesim webots run my_controller.py --world my-maze.toml --robot my-epuck.toml",
            "mazesim webots run worlds/swarm.wbt --robot-controller leader=my_leader.py",
            notes="exit status: 0 the controller ended (or robot.step returned -1); N the "
            "controller's sys.exit(N) or a supervisor's simulationQuit(N); 1 the controller "
            "raised an exception or, in Python, does not compile; a C/C++ controller crashed or "
            "could not be started (what it lacks is printed); 2 a mazesim error before the run "
            "(unreadable controller, world or key script, a C/C++ controller that does not "
            "compile, "
            "--strict with import warnings); 130 interrupted (Ctrl-C).",
        ),
    )
    run.add_argument(
        "controller",
        metavar="CONTROLLER|WORLD.wbt",
        help="the controller's Python, C or C++ file, or its Webots folder controllers/NAME "
        "(NAME.py, NAME.c or NAME.cpp in it); or a Webots world, whose robots all run, each with "
        "the controller its 'controller' field names (controllers/NAME/NAME.py of the world's "
        "project), each in its own process, in lockstep",
    )
    run.add_argument(
        "--robot-controller",
        action="append",
        metavar="NAME=FILE",
        help="with WORLD.wbt: the robot whose name, DEF name or controller field is NAME runs "
        "FILE (for an <extern> controller, or instead of its own); repeat for several robots",
    )
    run.add_argument(
        "--world",
        default=DEFAULT_WORLD,
        metavar="NAME|PATH|FILE.wbt",
        help="a built-in world, a mazesim world file or a Webots world (default: %(default)s)",
    )
    run.add_argument(
        "--robot",
        metavar="NAME|FILE",
        help="robot profile the controller drives instead of the world's: a built-in name or a "
        "profile file, as in mazesim demo (default: the world's robot, else e-puck); a run of "
        "one controller only (refused with WORLD.wbt, whose robots are its own)",
    )
    run.add_argument(
        "--seconds",
        type=positive_seconds,
        default=60.0,
        metavar="S",
        help="simulated seconds before robot.step returns -1 (default: %(default)s)",
    )
    add_seed_option(run, "the sensor noise")
    add_out_folder(run, "mazesim-webots", "trajectory.png, summary.json and trajectory.csv")
    run.add_argument("--no-noise", action="store_true", help="noise-free sensors")
    add_viewing_options(run, live=True)
    run.add_argument(
        "--keys",
        metavar="FILE",
        help="key script for the Keyboard: lines of 'time_s key [duration_s]' (key: one "
        "character, a Webots key name such as UP, DOWN, LEFT, RIGHT, with modifiers such "
        "as SHIFT+A, or '-' to release); without it getKey() returns -1; with WORLD.wbt "
        "every controller's Keyboard plays it, as Webots types to every robot when none is "
        "selected",
    )
    run.add_argument(
        "--strict",
        action="store_true",
        help="refuse a .wbt world with import warnings (a non-e-puck robot, dropped "
        "objects...): exit 2 before running",
    )
    add_progress_option(run)
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
        refuse_replacing_world_file(args.out, args.force)
    elif args.force:
        raise InvalidArgumentError("expected --force with --out WORLD_FILE, found it alone")
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
        f"movable bodies     {len(report['bodies'])}\n"
        f"sensed only        {len(report['sensed_only'])} (seen by the infra-red sensors and "
        "the camera, met by nothing else)\n"
        f"robot start        {_pose(report['robot'])}\n"
        f"robot              {report['robot_model'] or 'none'} "
        f"(simulated as {report['robot_profile']})\n"
        f"extension devices  {len(report['extension_devices'])}\n"
        f"floor paint        {report['floor_paint']} regions (rectangles, discs, lines) from "
        f"{len(report['floor_textures'])} floor textures\n"
        f"basic time step    {report['basic_time_step_ms']:g} ms\n"
        f"warnings           {len(report['warnings'])}\n"
    )
    for warning in report["warnings"]:
        out.write(f"  - {warning}\n")
    if args.out:
        out.write(f"wrote              {args.out}\n")
    return 0


def _load_world(
    spec: str, strict: bool, controller: str | None = None
) -> tuple[Any, dict[str, Any] | None, Any]:
    """The world, its import report (for a .wbt file) and its scene; warnings printed. Of
    several e-pucks, the one whose ``controller`` field names ``controller`` runs."""
    import mazesim
    from mazesim.errors import WorldFormatError
    from mazesim.webots.importer import import_summary, import_wbt, robot_warnings
    from mazesim.webots.scene import read_scene, read_world_text

    if not spec.lower().endswith(".wbt"):
        return mazesim.load_world(spec), None, None
    world, imported = import_wbt(spec, controller=controller)
    report: dict[str, Any] = dict(imported)
    report["path"] = os.path.abspath(spec)
    warnings = [*report.get("warnings", []), *robot_warnings(report)]
    report["import_summary"] = import_summary(spec, report, warnings)
    print(f"mazesim: {report['import_summary']['sentence']}", file=sys.stderr)
    for warning in warnings:
        print(f"mazesim: warning: {warning}", file=sys.stderr)
    if strict and warnings:
        raise WorldFormatError(
            f"{spec}: --strict expects a world imported without warnings, found "
            f"{len(warnings)} (listed above)",
            source=spec,
        )
    # The import has checked the file's size; it is read again only for the scene's fields.
    scene = read_scene(read_world_text(spec), report.get("robot_model"), report.get("robot_line"))
    return world, report, scene


def _refuse_robot_in_world_run(args: argparse.Namespace) -> None:
    if args.robot is not None:
        raise InvalidArgumentError(
            "--robot chooses the robot profile of one controller's run; found it "
            f"({_shown(args.robot)}) "
            "with a run of a whole world, whose robots are the world's: leave --robot out, or "
            "give each robot its profile in the world"
        )


def run_webots(args: argparse.Namespace, out: TextIO) -> int:
    """Runs a controller file and writes its trajectory picture and summary.

    Returns:
        The run's exit status (see the command's epilog).
    """
    from mazesim.cli.demo import goal_line, goal_summary, speed_summary
    from mazesim.cli.webots_world import RobotPaths, write_paths_table
    from mazesim.plotting import save_robot_paths_png, save_trajectory_png
    from mazesim.webots.importer import undownloaded_textures
    from mazesim.webots.keyboard import read_keys
    from mazesim.webots.requirements import prepare_controller
    from mazesim.webots.runner import controller_file, run_controller

    if args.controller.lower().endswith(".wbt"):
        from mazesim.cli.webots_world import run_world_command

        if args.world != DEFAULT_WORLD:
            raise InvalidArgumentError(
                "--world chooses the world of a controller's run; found it "
                f"({_shown(args.world)}) with "
                f"the world file {_shown(args.controller)} as the first argument, which is the "
                "world of "
                "this run: leave --world out, or give a controller file first"
            )
        _refuse_robot_in_world_run(args)
        return run_world_command(args, out)

    if args.robot_controller:
        raise InvalidArgumentError(
            "--robot-controller NAME=FILE chooses a robot's controller in a world run "
            "(mazesim webots run WORLD.wbt ...); found it with the controller file "
            f"{_shown(args.controller)}: give the world as the first argument, or leave the "
            "option out"
        )
    file = controller_file(args.controller)
    from mazesim.cli.webots_world import run_world_command, whole_world_run

    whole = whole_world_run(args, file)
    if whole is not None:
        _refuse_robot_in_world_run(args)
        return run_world_command(whole, out)
    controller = os.path.splitext(os.path.basename(file))[0]
    world, report, scene = _load_world(args.world, args.strict, controller)
    prepared = prepare_controller(file)
    if report is not None:
        prepared.missing += undownloaded_textures(list(report.get("warnings", [])))
    for note in prepared.notes:
        print(f"mazesim: {note}", file=sys.stderr)
    for missing in prepared.missing:
        print(f"mazesim: missing: {missing}", file=sys.stderr)
    keys = read_keys(args.keys) if args.keys else None
    out_dir = os.path.abspath(args.out)
    refuse_overwriting_inputs(
        [
            *output_files(out_dir, ("trajectory.png", "summary.json", "trajectory.csv")),
            *viewing_outputs(args),
        ],
        [
            ("the controller", args.controller),
            ("--world", args.world),
            ("--keys", args.keys),
            ("--robot", args.robot),
        ],
    )
    # Fail before the run, not after it, if the output folder cannot be made.
    make_output_folder(out_dir)
    from mazesim.webots.simulation import observing_steps

    watch = DeferredWatch(args, os.path.basename(args.controller), args.seed)
    fleet = RobotPaths(world)
    with contextlib.ExitStack() as viewing:
        if viewing_requested(args):
            viewing.enter_context(observing_steps(watch))
        viewing.enter_context(observing_steps(fleet))
        display = viewing.enter_context(progress_display(args, unit="steps"))
        steps = _StepProgress(display, args.seconds)
        viewing.enter_context(observing_steps(steps))
        result = run_controller(
            args.controller,
            world,
            seconds=args.seconds,
            seed=args.seed,
            noise=not args.no_noise,
            report=report,
            keys=keys,
            scene=scene,
            prepared=prepared,
            robot=args.robot,
        )
        if result.reached_end:
            steps.finish()
    if getattr(out, "closed", False):
        out = sys.stdout  # the controller closed it: the run opened it anew
    name = os.path.basename(result.controller)
    wall_clock = result.wall_clock_seconds
    step_s = result.simulated_seconds / result.steps if result.steps else 0.0
    summary: dict[str, Any] = {
        "world": world.name,
        "controller": result.controller,
        "robot": str(result.robot_model),
        "seed": args.seed,
        "simulated_seconds": result.simulated_seconds,
        "steps": result.steps,
        "distance_m": result.distance_m,
        "collisions": result.collisions,
        "longest_stop_s": result.longest_stop_s,
        "reached_end": result.reached_end,
        "exit_status": result.exit_status,
        "controller_error": result.error.strip().splitlines()[-1] if result.error else None,
        "quit_requested": result.quit_requested,
        "stopped_after_end": result.stopped,
        "stalled": result.stalled,
        "final_pose": list(result.final_pose),
        **goal_summary(result.world, result.xs, result.ys, step_s),
        **speed_summary(result.simulated_seconds, wall_clock),
        "missing_features": list(prepared.missing),
    }
    if report is not None and "import_summary" in report:
        summary["import"] = {
            key: value for key, value in report["import_summary"].items() if key != "sentence"
        }
    ran = f"{result.simulated_seconds:.0f} s, seed {args.seed}"
    title = f"{world.name}: {name}, {ran}"
    picture = os.path.join(out_dir, "trajectory.png")
    table = os.path.join(out_dir, "trajectory.csv")
    if fleet.several:
        # A mazesim world of several robots: the controller drove robot 0, the others stood.
        summary["robots"], paths = fleet.robots(
            result.controller, str(result.robot_model), result.xs, result.ys
        )
        title = f"{world.name}: {name} on {paths[0][0]}, {len(paths)} robots, {ran}"
        save_robot_paths_png(world, paths, picture, title=title)
        write_paths_table(table, paths, step_s)
    else:
        save_trajectory_png(result.world, result.xs, result.ys, picture, title=title)
        with atomic_file(table) as handle:
            points = enumerate(zip(result.xs, result.ys))
            rows = (f"{i * step_s:.3f},{x:.5f},{y:.5f}" for i, (x, y) in points)
            handle.write(("time_s,x_m,y_m\n" + "\n".join(rows) + "\n").encode("utf-8"))
    summary_path = os.path.join(out_dir, "summary.json")
    with atomic_file(summary_path) as handle:
        handle.write((json.dumps(summary, indent=2) + "\n").encode("utf-8"))
    if result.error:
        sys.stderr.write(result.error)
    views = watch.finish(
        f"{result.simulated_seconds:.0f} s", f"{world.name}: {name}, seed {args.seed}"
    )
    factor = summary["real_time_factor"]
    speed = "n/a" if factor is None or not math.isfinite(factor) else f"{factor:.0f}x"
    out.write(
        f"world              {world.name} (seed {args.seed})\n"
        f"controller         {name} ({_ending(result)})\n"
        f"simulated time     {result.simulated_seconds:.2f} s ({result.steps} steps)\n"
        f"distance travelled {result.distance_m:.2f} m\n"
        f"collisions         {result.collisions}\n"
        f"longest stop       {result.longest_stop_s:.2f} s\n"
        f"{goal_line(summary)}"
        f"wall-clock time    {wall_clock:.3f} s ({speed} real time)\n"
    )
    for robot in summary.get("robots", [])[1:]:
        out.write(
            f"  {robot['name']:<16} no controller: {robot['distance_m']:.2f} m, "
            f"{robot['collisions']} collisions\n"
        )
    out.write(written_lines(args, picture, [picture, summary_path, table, *views]))
    return result.exit_status


class _StepProgress:
    """A step observer that shows the simulator's steps against those ``--seconds`` take."""

    def __init__(self, display: ProgressDisplay, seconds: float) -> None:
        self.display = display
        self.seconds = seconds
        self.total = 0

    def __call__(self, simulation: Any, left: float, right: float) -> None:
        """Shows the steps taken before a step of ``simulation``."""
        simulator = simulation.simulator
        if not self.total:
            self.total = max(1, math.ceil(self.seconds * 1000.0 / simulator.control_step_ms - 1e-9))
        self.display("simulating", simulator.steps, self.total)

    def finish(self) -> None:
        """Shows the run's end: ``--seconds`` were simulated."""
        if self.total:
            self.display("simulating", self.total, self.total)


def _ending(result: Any) -> str:
    """How the controller's run ended, in words."""
    from mazesim.webots.runner import EXIT_CONTROLLER_ERROR, EXIT_INTERRUPTED

    if result.quit_requested:
        return f"simulationQuit({result.exit_status})"
    if result.stalled:
        return "stopped: the controller took no step for too long"
    if result.exit_status == EXIT_INTERRUPTED:
        return "interrupted"
    if result.error and result.exit_status == EXIT_CONTROLLER_ERROR:
        return "the controller raised an exception"
    if result.exit_status:
        return f"the controller exited with status {result.exit_status}"
    if result.stopped:
        return "stopped 1 s after robot.step returned -1, as Webots stops it"
    return "robot.step returned -1" if result.reached_end else "the controller returned"
