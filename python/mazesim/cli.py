"""The ``mazesim`` command line.

``mazesim worlds`` lists the built-in worlds; ``mazesim demo`` drives the e-puck with the report's
avoid-collision controller (Alg. 1), or the seed robot with the shipped hierarchical navigator
(``--controller hrl``), headless, prints a summary and writes a trajectory picture and a JSON
summary. The other commands come from the modules in :data:`COMMAND_MODULES`. Errors are printed
as one line, ``mazesim: error: <message>``, with exit code 2.
"""

from __future__ import annotations

import argparse
import importlib
import json
import math
import os
import stat
import sys
import time
from collections.abc import Sequence
from typing import Any, TextIO

import numpy as np

import mazesim
from mazesim._atomic import atomic_file
from mazesim._paths import output_files, output_path, refuse_overwriting_inputs
from mazesim.controllers import AvoidCollision
from mazesim.errors import InvalidArgumentError, MazesimError
from mazesim.replay.options import SimulatorWatch, add_viewing_options

__all__ = [
    "main",
    "non_negative_int",
    "output_path",
    "positive_int",
    "positive_number",
    "positive_seconds",
    "seed_argument",
    "whole_number",
]

#: Modules that add subcommands: each has ``register(commands)``, which adds its parser(s) to the
#: ``argparse`` subparsers object and sets ``run=<function(args) -> int>`` as the parser default.
COMMAND_MODULES: tuple[str, ...] = (
    "mazesim.bench",
    "mazesim.ros.cli",
    "mazesim.barcode.command",
    "mazesim.webots.cli",
    "mazesim.distributed.command",
    "mazesim.hrl.command",
    "mazesim.replay.command",
    "mazesim.replay.show",
)

#: Exit code of a run that failed on an error of the user's input or of the file system.
EXIT_ERROR = 2
#: Exit code of a run stopped with Ctrl-C (128 + SIGINT), as shells report it.
EXIT_INTERRUPTED = 130
#: Exit code of a run whose output pipe was closed by its reader (128 + SIGPIPE), as shells report
#: a command that a closed pipe ended (``mazesim worlds | head -1``).
EXIT_BROKEN_PIPE = 141
#: Wall-clock seconds after which a run starts showing its progress on a terminal.
PROGRESS_AFTER_S = 1.0
#: The most simulated seconds a command runs for (11.6 days).
MAX_SECONDS = 1e6
#: The largest number a positive-number option takes.
MAX_NUMBER = 1e9
#: The largest count (of readings, episodes, envs, CPUs...) an option takes.
MAX_COUNT = 2**31 - 1


def _positive_float(text: str, what: str, largest: float) -> float:
    """A finite number in (0, largest]; ``what`` names it in the message ("number of seconds")."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a {what}, found {text!r}") from None
    if not math.isfinite(value) or not 0.0 < value <= largest:
        raise argparse.ArgumentTypeError(
            f"expected a positive {what} of at most {largest:g}, found {text!r}"
        )
    return value


def positive_seconds(text: str) -> float:
    """A positive number of seconds, at most :data:`MAX_SECONDS`."""
    return _positive_float(text, "number of seconds", MAX_SECONDS)


def positive_number(text: str) -> float:
    """A finite number above 0, at most :data:`MAX_NUMBER`."""
    return _positive_float(text, "number", MAX_NUMBER)


def whole_number(text: str, smallest: int, largest: int = MAX_COUNT) -> int:
    """A whole number in ``[smallest, largest]``.

    Raises:
        argparse.ArgumentTypeError: ``text`` is not such a number (argparse prints the message).
    """
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number, found {text!r}") from None
    if value < smallest:
        raise argparse.ArgumentTypeError(
            f"expected a whole number of at least {smallest}, found {text!r}"
        )
    if value > largest:
        raise argparse.ArgumentTypeError(
            f"expected a whole number of at most {largest}, found {text!r}"
        )
    return value


def positive_int(text: str) -> int:
    """A whole number of at least 1 and at most :data:`MAX_COUNT` (a count of readings,
    episodes, envs, CPUs...)."""
    return whole_number(text, 1)


def non_negative_int(text: str) -> int:
    """A whole number of at least 0 and at most :data:`MAX_COUNT` (0 often means "automatic")."""
    return whole_number(text, 0)


def seed_argument(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number, found {text!r}") from None
    if value < 0 or value >= 2**64:
        raise argparse.ArgumentTypeError(f"expected a seed in [0, 2^64), found {text!r}")
    return value


def build_parser() -> argparse.ArgumentParser:
    """Builds the argument parser of the ``mazesim`` command."""
    parser = argparse.ArgumentParser(
        prog="mazesim",
        description=(
            "mazesim: a fast, deterministic simulator of the e-puck robot in mazes. "
            "Run 'mazesim COMMAND --help' for the options of a command."
        ),
    )
    parser.add_argument("--version", action="version", version=f"mazesim {mazesim.__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)

    worlds = commands.add_parser(
        "worlds",
        help="list the built-in worlds",
        description="List the built-in worlds: name, size and number of barcode checkpoints.",
    )
    worlds.set_defaults(run=lambda args: run_worlds(sys.stdout))

    demo = commands.add_parser(
        "demo",
        help="drive the robot (avoid-collision or the shipped navigator) and plot its path",
        description=(
            "Drive the robot headless with the avoid-collision controller of the source report "
            "(Alg. 1: turn away when a front proximity sensor reads above 80), print a summary, "
            "and write DIR/trajectory.png and DIR/summary.json."
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
        default=60.0,
        metavar="S",
        help="simulated seconds to run (default: %(default)s)",
    )
    demo.add_argument(
        "--seed",
        type=seed_argument,
        default=0,
        metavar="N",
        help="seed of the sensor noise (default: %(default)s)",
    )
    demo.add_argument(
        "--out",
        type=output_path,
        default="mazesim-demo",
        metavar="DIR",
        help="folder for trajectory.png and summary.json, created if missing "
        "(default: %(default)s)",
    )
    demo.add_argument(
        "--robot",
        default="e-puck",
        metavar="NAME",
        help="robot profile; the controller needs the e-puck's 8 proximity sensors "
        "(default: %(default)s)",
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
    demo.set_defaults(run=lambda args: run_demo(args, sys.stdout))
    for module_name in COMMAND_MODULES:
        importlib.import_module(module_name).register(commands)
    return parser


def _one_line(message: str) -> str:
    """Joins a possibly multi-line message into one line."""
    parts = [line.strip() for line in message.splitlines() if line.strip()]
    return "; ".join(parts) if parts else "unknown error"


def run_worlds(out: TextIO) -> int:
    """Prints one line per built-in world: name, size, checkpoints and goal."""
    names = sorted(mazesim.builtin_world_names())
    width = max((len(name) for name in names), default=0)
    for name in names:
        world = mazesim.World.builtin(name)
        xmin, ymin, xmax, ymax = world.bounds
        count = len(world.checkpoints())
        noun = "checkpoint" if count == 1 else "checkpoints"
        goal = ", goal" if world.goal is not None else ""
        out.write(
            f"{name:<{width}}  {xmax - xmin:.2f} x {ymax - ymin:.2f} m  {count} {noun}{goal}\n"
        )
    return 0


class _Progress:
    """A one-line progress indication on stderr, shown only on a terminal and for long runs."""

    def __init__(self, total_seconds: float, stream: TextIO) -> None:
        self.total_seconds = total_seconds
        self.stream = stream
        self.enabled = stream.isatty()
        self.started = time.perf_counter()
        self.next_update = self.started + PROGRESS_AFTER_S
        self.shown = False

    def update(self, simulated_seconds: float) -> None:
        if not self.enabled:
            return
        now = time.perf_counter()
        if now < self.next_update:
            return
        self.next_update = now + 0.2
        percent = 100.0 * min(simulated_seconds / self.total_seconds, 1.0)
        self.stream.write(
            f"\rsimulating: {simulated_seconds:7.1f} / {self.total_seconds:.1f} s ({percent:3.0f}%)"
        )
        self.stream.flush()
        self.shown = True

    def close(self) -> None:
        if self.shown:
            self.stream.write("\r\033[K")
            self.stream.flush()


def run_demo(args: argparse.Namespace, out: TextIO) -> int:
    """Runs the avoid-collision demo and writes its picture and summary."""
    from mazesim.plotting import save_trajectory_png

    refuse_overwriting_inputs(
        output_files(args.out, ("trajectory.png", "summary.json", "trace.txt")),
        [("--world", args.world)],
    )
    if getattr(args, "controller", "avoid-collision") == "hrl":
        from mazesim.hrl.demo import run_hrl_demo

        return run_hrl_demo(args, out)

    world = mazesim.load_world(args.world)
    simulator = mazesim.Simulator(world, robot=args.robot, seed=args.seed)
    robot = simulator.robot
    proximity = [f"ps{i}" for i in range(8)]
    names = list(robot.distance_sensor_names)
    if robot.distance_sensor_unit != "raw" or not set(proximity) <= set(names):
        raise InvalidArgumentError(
            f"the demo's avoid-collision controller needs the e-puck's 8 raw proximity sensors "
            f"ps0-ps7; robot {robot.name!r} has {', '.join(names)} "
            f"in {robot.distance_sensor_unit!r}"
        )
    # ps0-ps7, wherever the profile lists them (the e-puck2 has its ToF beside them).
    columns = [names.index(name) for name in proximity]
    controller = AvoidCollision(max_speed=robot.max_wheel_speed)
    # Fail before the run, not after it, if the output folder cannot be made.
    os.makedirs(args.out, exist_ok=True)
    steps = max(1, math.ceil(args.seconds * 1000.0 / simulator.control_step_ms - 1e-9))

    xs = np.empty(steps + 1, dtype=np.float64)
    ys = np.empty(steps + 1, dtype=np.float64)
    xs[0], ys[0], _ = simulator.pose
    progress = _Progress(args.seconds, sys.stderr)
    watch = SimulatorWatch(args, simulator, "avoid-collision", args.seed)
    contacts: list[tuple[float, float]] = []
    started = time.perf_counter()
    try:
        for step in range(1, steps + 1):
            left, right = controller(simulator.distance_sensors()[columns])
            watch.before_step(left, right)
            simulator.step(left, right)
            xs[step], ys[step], _ = simulator.pose
            if simulator.colliding:
                contacts.append((xs[step], ys[step]))
            progress.update(simulator.time)
    finally:
        progress.close()
    wall_clock = time.perf_counter() - started

    goal_reached: bool | None = None
    if world.goal is not None:
        goal_x, goal_y, radius = world.goal
        goal_reached = bool(np.any(np.hypot(xs - goal_x, ys - goal_y) <= radius))
    summary: dict[str, Any] = {
        "world": world.name,
        "robot": robot.name,
        "seed": args.seed,
        "controller": "avoid-collision",
        "simulated_seconds": simulator.time,
        "steps": simulator.steps,
        "distance_m": simulator.distance_travelled,
        "collisions": simulator.collisions,
        "goal_reached": goal_reached,
        "wall_clock_seconds": wall_clock,
        "real_time_factor": simulator.time / wall_clock if wall_clock > 0 else None,
        "mazesim_version": mazesim.__version__,
    }

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
        f"world              {world.name} (robot {robot.name}, seed {args.seed})\n"
        f"simulated time     {simulator.time:.2f} s ({simulator.steps} steps)\n"
        f"distance travelled {simulator.distance_travelled:.2f} m\n"
        f"collisions         {simulator.collisions}\n"
    )
    if goal_reached is not None:
        out.write(f"goal reached       {'yes' if goal_reached else 'no'}\n")
    out.write(
        f"wall-clock time    {wall_clock:.3f} s ({speed} real time)\n"
        f"wrote              {', '.join([picture, summary_path, *views])}\n"
    )
    return 0


def _stdout_is_a_pipe() -> bool:
    """Whether standard output is a pipe (whose reader may close it early)."""
    try:
        return stat.S_ISFIFO(os.fstat(sys.stdout.fileno()).st_mode)
    except (OSError, ValueError, AttributeError):
        return False


def main(argv: Sequence[str] | None = None) -> int:
    """Runs the ``mazesim`` command.

    Args:
        argv: The arguments after the program name; by default ``sys.argv[1:]``.

    Returns:
        The exit code: 0 on success, 2 on an error (printed as one line on stderr), 130 on Ctrl-C.
    """
    arguments = list(sys.argv[1:] if argv is None else argv)
    try:
        from mazesim.ros.cli import check_before_parsing

        check_before_parsing(arguments)
    except MazesimError as error:
        print(f"mazesim: error: {_one_line(str(error))}", file=sys.stderr)
        return EXIT_ERROR
    parser = build_parser()
    try:
        args = parser.parse_args(arguments)
    except SystemExit as exit_request:
        # --help and --version exit with None (success); usage errors with 2.
        code = exit_request.code
        return code if isinstance(code, int) else (0 if code is None else EXIT_ERROR)
    try:
        return int(args.run(args))
    except BrokenPipeError as error:
        if not _stdout_is_a_pipe():
            print(f"mazesim: error: {_one_line(str(error))}", file=sys.stderr)
            return EXIT_ERROR
        # The reader of the output went away: stop quietly, as Unix tools do, and keep Python
        # from failing again when it flushes the closed pipe at exit.
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return EXIT_BROKEN_PIPE
    except (MazesimError, OSError) as error:
        print(f"mazesim: error: {_one_line(str(error))}", file=sys.stderr)
        return EXIT_ERROR
    except MemoryError:
        print(
            "mazesim: error: out of memory; ask for less (fewer envs, episodes, steps or seconds)",
            file=sys.stderr,
        )
        return EXIT_ERROR
    except KeyboardInterrupt:
        print("mazesim: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except BaseException as error:
        # A bug, not the user's doing: one line and how to report it, not a traceback. (pyo3's
        # PanicException derives from BaseException; SystemExit and GeneratorExit pass.)
        if isinstance(error, (SystemExit, GeneratorExit)):
            raise
        print(
            f"mazesim: error: internal error, please report it with the command that caused "
            f"it: {type(error).__name__}: {_one_line(str(error))}",
            file=sys.stderr,
        )
        return EXIT_ERROR
