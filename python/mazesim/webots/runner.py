"""Running an unmodified Webots controller file headless on mazesim.

:func:`run_controller` prepares a simulation, installs :mod:`mazesim.webots.controller` as the
package ``controller`` (its submodules as ``controller.robot``...) and executes the file as Webots
does (as ``__main__``, from its own folder, with that folder on ``sys.path``, ``WEBOTS_HOME`` set
if it was not) until the controller returns or ``Robot.step`` reports the end.
"""

from __future__ import annotations

import contextlib
import io
import os
import sys
import threading
import time
import tokenize
import traceback
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import ModuleType, TracebackType
from typing import Any, NoReturn

from mazesim._callers import users_code
from mazesim._core import RobotProfile, World
from mazesim._paths import MAX_TEXT_CHARACTERS, read_input
from mazesim.errors import InvalidArgumentError, MazesimError, MazesimIOError, _shown
from mazesim.webots import controller as controller_module
from mazesim.webots import native_controller, termination
from mazesim.webots import simulation as simulations
from mazesim.webots.controller_makefile import makefile_main
from mazesim.webots.keyboard import KeyScript
from mazesim.webots.last_commands import WheelCommand
from mazesim.webots.requirements import (
    PreparedController,
    prepare_controller,
    runtime_python_paths,
)
from mazesim.webots.scene import Scene
from mazesim.webots.virtual_display import virtual_display, window_environment

__all__ = [
    "EXIT_CONTROLLER_ERROR",
    "EXIT_INTERRUPTED",
    "ControllerRun",
    "controller_file",
    "process_status",
    "run_controller",
]

#: Exit status of a run whose controller raised an exception.
EXIT_CONTROLLER_ERROR = 1
#: Exit status of a run interrupted by Ctrl-C.
EXIT_INTERRUPTED = 130


@dataclass
class ControllerRun:
    """What a controller run did.

    Attributes:
        world: The world it ran in, as a supervisor left it (with the nodes it imported, without
            those it removed).
        controller: The controller file.
        simulated_seconds: Simulated time at the end.
        steps: Basic time steps simulated.
        distance_m: Distance the robot travelled.
        collisions: Contacts with walls that began during the run.
        longest_stop_s: Longest time the robot stood still (moved under 0.1 mm per step).
        reached_end: Whether ``Robot.step`` returned -1 (the time was up) before the controller
            ended.
        wall_clock_seconds: Real time the run took.
        xs: The robot's x after each step, the start first.
        ys: The robot's y after each step, the start first.
        exit_status: 0 when the controller ended normally; its ``sys.exit`` status, a
            supervisor's ``simulationQuit`` status, :data:`EXIT_CONTROLLER_ERROR` when it
            raised, :data:`EXIT_INTERRUPTED` on Ctrl-C.
        error: The traceback of the controller's exception (its own frames first), or "".
        quit_requested: Whether a supervisor called ``simulationQuit``.
        final_pose: The robot's x, y, yaw at the end.
        robot_model: The robot profile that ran.
        wheel_commands: The wheel motors' commands as the controller left them (left wheel
            first; none when it made no robot), which a world run goes on applying
            (:mod:`mazesim.webots.last_commands`).
        stopped: Whether the controller went on for more than
            :data:`~mazesim.webots.termination.GRACE_SECONDS` of real time after ``Robot.step``
            returned -1 and was stopped, as Webots ends such a controller.
        stalled: Whether the controller took no step for ``stall_seconds`` of real time before
            the end (a loop that never calls ``Robot.step``) and was stopped; ``error`` says so
            and ``exit_status`` is :data:`EXIT_CONTROLLER_ERROR`.
    """

    world: World
    controller: str
    simulated_seconds: float
    steps: int
    distance_m: float
    collisions: int
    longest_stop_s: float
    reached_end: bool
    wall_clock_seconds: float
    xs: list[float] = field(repr=False)
    ys: list[float] = field(repr=False)
    exit_status: int = 0
    error: str = field(default="", repr=False)
    quit_requested: bool = False
    final_pose: tuple[float, float, float] = (0.0, 0.0, 0.0)
    robot_model: str = "e-puck"
    stopped: bool = False
    stalled: bool = False
    wheel_commands: tuple[WheelCommand, ...] = ()


#: The files a Webots controller folder ``controllers/NAME`` may run, ``NAME`` and one of these
#: suffixes, in the order Webots looks for them: Python, then C and C++ sources as its default
#: Makefile compiles them, then a BotStudio automaton (:mod:`mazesim.webots.botstudio`).
CONTROLLER_SUFFIXES = (
    ".py",
    *native_controller.C_SUFFIXES,
    *native_controller.CPP_SUFFIXES,
    ".bsg",
)
#: The program that runs a BotStudio automaton as the controller (``__file__`` its ``.bsg``).
BOTSTUDIO_PROGRAM = """\
import sys
from mazesim.errors import MazesimError
from mazesim.webots.botstudio import run_automaton
try:
    run_automaton(__file__)
except MazesimError as error:
    print(f"BotStudio: {error}", file=sys.stderr)
    raise SystemExit(1) from None
"""


#: The other languages Webots runs controllers in, by file suffix: mazesim runs none of them.
OTHER_LANGUAGES = {
    ".java": "Java",
    ".class": "Java",
    ".jar": "Java",
    ".m": "MATLAB",
}
#: Files that are no controller in any language, by suffix, with where they are given instead:
#: run as Python, a world file ended in a NameError on its first table.
NOT_CONTROLLERS = {
    ".toml": (
        "a TOML file (a mazesim world, given as --world; a robot profile, given as --robot: "
        "mazesim webots run CONTROLLER --robot FILE)"
    ),
    ".json": "a JSON file (a recorded run, replayed with mazesim replay)",
    ".proto": "a Webots PROTO file (a world that uses it is run: give the .wbt world)",
}


def folder_controller(folder: str) -> str | None:
    """The controller file of the Webots controller folder ``folder`` (``controllers/NAME``), as
    Webots finds its program: ``NAME.py``, ``NAME.c``, ``NAME.cpp``, ``NAME.cc`` or ``NAME.cxx``
    (:data:`CONTROLLER_SUFFIXES`), else the source defining ``main`` among those its Makefile
    builds into the program ``NAME`` (:func:`~mazesim.webots.controller_makefile.makefile_main`:
    a ``main.cpp`` its ``CXX_SOURCES`` lists); None when there is neither."""
    name = os.path.basename(os.path.normpath(folder))
    for suffix in CONTROLLER_SUFFIXES:
        inside = os.path.join(folder, f"{name}{suffix}")
        if os.path.isfile(inside):
            return inside
    main = makefile_main(Path(folder)) if os.path.isdir(folder) else None
    return None if main is None else str(main)


def controller_file(path: str | os.PathLike[str]) -> str:
    """The controller file to run: ``path`` itself, or for a Webots controller folder
    ``controllers/NAME`` the ``NAME.py``, ``NAME.c``, ``NAME.cpp``, ``NAME.cc`` or ``NAME.cxx`` in
    it (:data:`CONTROLLER_SUFFIXES`), as Webots looks for them.

    Raises:
        MazesimIOError: ``path`` is a folder without such a file.
        InvalidArgumentError: ``path`` is a controller in a language mazesim does not run
            (:data:`OTHER_LANGUAGES`: Java, MATLAB), or no controller at all
            (:data:`NOT_CONTROLLERS`: a world file, a run, a PROTO).
    """
    file = os.path.abspath(os.fspath(path))
    expected = f"a Python, C, C++ or BotStudio controller ({', '.join(CONTROLLER_SUFFIXES)})"
    if not os.path.isdir(file):
        suffix = os.path.splitext(file)[1].lower()
        if suffix in NOT_CONTROLLERS:
            raise InvalidArgumentError(
                f"{file}: expected {expected} or a .wbt world, found {NOT_CONTROLLERS[suffix]}"
            )
        language = OTHER_LANGUAGES.get(suffix)
        if language is not None:
            raise InvalidArgumentError(
                f"{file}: expected {expected}, found a {language} controller, which mazesim "
                f"does not run"
            )
        return file
    inside = folder_controller(file)
    if inside is not None:
        return inside
    name = os.path.basename(file)
    others = [
        f"{name}{suffix} ({language})"
        for suffix, language in OTHER_LANGUAGES.items()
        if os.path.isfile(os.path.join(file, f"{name}{suffix}"))
    ]
    failure = MazesimIOError(
        f"{file}: expected a controller file, or a Webots controller folder holding "
        f"{name}{', '.join(CONTROLLER_SUFFIXES)} (Webots runs controllers/NAME/NAME.*), found a "
        + (
            f"folder with {', '.join(others)}, which mazesim does not run"
            if others
            else "folder without them"
        )
    )
    failure.filename = file
    raise failure


def _read_source(path: str) -> str:
    """The controller's source text, decoded as Python decodes a source file (UTF-8, or the
    encoding its coding comment declares)."""
    source = read_input(path, MAX_TEXT_CHARACTERS, "the controller")
    if len(source) > MAX_TEXT_CHARACTERS:
        raise InvalidArgumentError(
            f"{path}: expected a controller of at most {MAX_TEXT_CHARACTERS} bytes, found more"
        )
    try:
        encoding, _ = tokenize.detect_encoding(io.BytesIO(source).readline)
        with io.TextIOWrapper(io.BytesIO(source), encoding) as handle:
            return handle.read()
    except (UnicodeDecodeError, SyntaxError, LookupError) as error:
        raise InvalidArgumentError(
            f"{path}: expected a Python controller file (text in UTF-8 or the encoding its "
            f"coding comment names), found bytes that are not: {error}"
        ) from None


#: The threads a controller run in this process started and left running, not daemons (a socket
#: server's, a GUI's): Python would wait for them at exit, and the command never ended. Webots
#: ends a controller's process with its run; the command ends without them
#: (:func:`mazesim.cli.main`).
LEFT_RUNNING: list[threading.Thread] = []


def run_controller(
    path: str | os.PathLike[str],
    world: World,
    *,
    seconds: float = 60.0,
    seed: int = 0,
    noise: bool = True,
    report: Mapping[str, Any] | None = None,
    keys: KeyScript | None = None,
    scene: Scene | None = None,
    prepared: PreparedController | None = None,
    stall_seconds: float = termination.STALL_SECONDS,
    robot: str | RobotProfile | None = None,
    **world_of_several: Any,
) -> ControllerRun:
    """Runs a Webots-style controller file on the robot in ``world``.

    Whatever the controller does (returns, raises, calls ``sys.exit``, is interrupted), the run
    is returned: its exception becomes ``error`` and ``exit_status``.

    Args:
        path: The controller's Python file (``from controller import Robot`` and the usual
            loop), or its Webots controller folder (``controllers/NAME``, holding ``NAME.py``).
        world: The world to run in.
        seconds: Simulated seconds after which ``Robot.step`` returns -1.
        seed: Seed of the sensor noise.
        noise: Whether the sensors are noisy.
        report: The import report of a ``.wbt`` world (robot profile, extension devices).
        keys: The keyboard script.
        scene: DEF names, supervisor flag, camera fields and controller arguments of the world
            file (``sys.argv[1:]`` of the controller).
        prepared: The controller as :func:`~mazesim.webots.requirements.prepare_controller`
            prepared it (a C or C++ controller built); prepared here when not given. A
            controller that cannot run (C or C++ needing Webots headers or functions mazesim
            lacks, Tk windows and no display) is not started: the run has no steps and its
            error says what is missing.
        stall_seconds: Real seconds the controller may run without taking a step before the
            run's end (its set-up before the first step included) before it is stopped; after
            the end it is stopped :data:`~mazesim.webots.termination.GRACE_SECONDS` later, as
            Webots does, whether it calls ``Robot.step`` or not.
        robot: The robot profile to simulate instead of the world's: a built-in name, a profile
            file's path or a :class:`~mazesim.RobotProfile` (``mazesim webots run --robot``).
        **world_of_several: For a robot of a world with several robots, whose process owns
            the world: ``simulator``, ``radio``, ``fleet`` and ``robot_index`` (see
            :class:`~mazesim.webots.simulation.RobotSimulation`).

    Returns:
        What the run did.

    Raises:
        MazesimIOError: The file cannot be read.
        InvalidArgumentError: ``seconds`` or ``stall_seconds`` is not positive.
        ControllerBuildError: A C controller does not compile.
        MissingDependencyError: A C controller and no C compiler.
    """
    if not (isinstance(stall_seconds, (int, float)) and 0.0 < stall_seconds <= 1e9):
        raise InvalidArgumentError(
            "expected stall_seconds to be a number of seconds in (0, 1e9], found "
            f"{_shown(stall_seconds)}"
        )
    file = controller_file(path)
    if prepared is None or prepared.file != file:
        prepared = prepare_controller(file)
    native = prepared.language not in ("python", "botstudio") or not prepared.runnable
    if prepared.language == "botstudio":
        source = BOTSTUDIO_PROGRAM
    else:
        source = "" if native else _read_source(file)
    simulation = simulations.prepare(
        world,
        seconds=seconds,
        seed=seed,
        noise=noise,
        report=report,
        keys=keys,
        scene=scene,
        robot=robot,
        **world_of_several,
    )
    if native:
        return _run_native(prepared, world, simulation, report, scene)
    controller_module.Robot.created = None
    folder = os.path.dirname(file)
    saved_modules = _install_controller_package()
    saved_argv, saved_path, saved_cwd = sys.argv, list(sys.path), os.getcwd()
    saved_module_names = set(sys.modules)
    sys.argv = [file, *(scene.controller_args if scene else [])]
    # Its folder first, then what its runtime.ini's PYTHONPATH adds, as Webots starts it.
    sys.path[0:0] = [folder, *runtime_python_paths(file)]
    # Controllers written to run outside Webots too look Webots up through WEBOTS_HOME.
    saved_home = os.environ.get("WEBOTS_HOME")
    if saved_home is None:
        os.environ["WEBOTS_HOME"] = os.path.dirname(os.path.dirname(controller_module.__file__))
    started = time.perf_counter()
    status, error = 0, ""
    watchdog = termination.Watchdog(simulation, controller_module.ControllerStopped, stall_seconds)
    streams = _standard_streams()
    running = set(threading.enumerate())
    display = contextlib.ExitStack()
    try:
        if prepared.virtual_display:
            display.enter_context(virtual_display())
        display.enter_context(window_environment(prepared.environment))
        os.chdir(folder)
        # Compiled with its real file name, so that tracebacks show its own lines.
        code = compile(source, "<botstudio>" if source is BOTSTUDIO_PROGRAM else file, "exec")
        try:
            watchdog.start()
            with users_code(), _process_exit_as_system_exit():
                exec(code, {"__name__": "__main__", "__file__": file, "__builtins__": __builtins__})
        finally:
            try:
                watchdog.stop()
            finally:
                termination.end_unwinding()
    except controller_module.ControllerStopped as stop:
        if watchdog.stalled:
            status, error = EXIT_CONTROLLER_ERROR, f"{stop}\n"
    except SystemExit as request:
        status, error = _exit_status(request)
    except KeyboardInterrupt:
        status = EXIT_INTERRUPTED
    except BaseException as failure:  # noqa: BLE001 - the controller's error is reported
        status = EXIT_CONTROLLER_ERROR
        error = _controller_traceback(failure)
    finally:
        # Once the controller's code is unwound (no line of this module runs under its stop),
        # however it ended.
        LEFT_RUNNING.extend(
            thread
            for thread in threading.enumerate()
            if thread not in running and thread.is_alive() and not thread.daemon
        )
        _reopen_closed(streams)
        display.close()
        if saved_home is None:
            os.environ.pop("WEBOTS_HOME", None)
        _forget_own_modules(saved_module_names, sys.path, saved_path, folder, saved_cwd)
        os.chdir(saved_cwd)
        sys.path[:] = saved_path
        sys.argv = saved_argv
        _restore_modules(saved_modules)
        controller_module.Robot.created = None
        simulations.release()
    return _outcome(world, file, simulation, started, status, error, stalled=watchdog.stalled)


def _standard_streams() -> dict[str, int]:
    """The file descriptor of ``sys.stdout`` and ``sys.stderr``, by name (those that have one)."""
    found = {}
    for name in ("stdout", "stderr"):
        try:
            found[name] = int(getattr(sys, name).fileno())
        except (AttributeError, OSError, ValueError):
            continue  # a stream in memory (a test's capture) or none
    return found


def _reopen_closed(streams: dict[str, int]) -> None:
    """Opens anew, on the same file descriptor, each standard stream of ``streams`` that the
    controller closed (``sys.stdout.close()``), so that what is written after its run (the
    run's summary, its report to the world's process) is not lost."""
    for name, fd in streams.items():
        stream = getattr(sys, name)
        if not getattr(stream, "closed", False):
            continue
        with contextlib.suppress(OSError):
            os.fstat(fd)  # still open: only the stream was closed
            reopened = io.TextIOWrapper(
                io.BufferedWriter(io.FileIO(fd, "w", closefd=False)),
                encoding=getattr(stream, "encoding", None) or "utf-8",
                errors="backslashreplace",
                line_buffering=True,
            )
            setattr(sys, name, reopened)


def _run_native(
    prepared: PreparedController,
    world: World,
    simulation: simulations.RobotSimulation,
    report: Mapping[str, Any] | None,
    scene: Scene | None,
) -> ControllerRun:
    """Runs a compiled controller as a child process on ``simulation`` (or, when it cannot run,
    says why)."""
    controller_module.Robot.created = None
    started = time.perf_counter()
    status, error = EXIT_CONTROLLER_ERROR, ""
    try:
        if not prepared.runnable or prepared.program is None:
            error = "controller not run: " + "; ".join(prepared.missing) + "\n"
        else:
            robot = native_controller.native_robot()
            folder = os.path.dirname(prepared.file)
            name = os.path.basename(folder)
            world_path = str((report or {}).get("path") or "")
            project = os.path.join(os.path.dirname(os.path.dirname(folder)), "")
            arguments = list(scene.controller_args) if scene else []
            status, error, _ = native_controller.drive(
                prepared.program,
                robot,
                arguments,
                (name, project, world_path),
                folder,
                native_controller.language_name(prepared.file),
            )
    except KeyboardInterrupt:
        status = EXIT_INTERRUPTED
    finally:
        controller_module.Robot.created = None
        simulations.release()
    return _outcome(world, prepared.file, simulation, started, status, error)


def _outcome(
    world: World,
    file: str,
    simulation: simulations.RobotSimulation,
    started: float,
    status: int,
    error: str,
    stalled: bool = False,
) -> ControllerRun:
    """The run's :class:`ControllerRun` (``stalled``: the watchdog stopped a controller that took
    no step)."""
    simulator = simulation.simulator
    motors = simulation.wheel_motors
    angles = simulation.wheel_angles() if motors else ()
    return ControllerRun(
        world=simulation.world if simulation.scene_edits is not None else world,
        controller=file,
        simulated_seconds=float(simulator.time),
        steps=simulation.steps,
        distance_m=float(simulator.distance_travelled),
        collisions=int(simulator.collisions),
        longest_stop_s=simulation.longest_stop_steps * simulation.basic_time_step_ms / 1000.0,
        reached_end=simulation.ended,
        stopped=simulation.stopped,
        stalled=stalled,
        wall_clock_seconds=time.perf_counter() - started,
        xs=simulation.xs,
        ys=simulation.ys,
        exit_status=status if simulation.quit_status is None else simulation.quit_status,
        error=error,
        quit_requested=simulation.quit_status is not None,
        final_pose=simulator.pose,
        robot_model=str(simulator.robot.name),
        wheel_commands=tuple(motor._last_command(a) for motor, a in zip(motors, angles)),
    )


def _forget_own_modules(
    before: set[str], path: list[str], saved_path: list[str], folder: str, saved_cwd: str
) -> None:
    """Removes from ``sys.modules`` the modules the controller imported from its own folder or
    from a folder it put on ``sys.path`` (its helper modules, a project's ``libraries/``).

    Webots starts each controller in a new process, so a controller always imports its own
    helpers; without this, a second run in the same process (of another controller with a
    ``settings.py`` of its own, or of the same one after an edit) would get the first run's.
    Modules found through the interpreter's own path stay loaded (numpy...), also from a
    virtual environment inside the controller's folder: the most specific folder decides.
    """

    def root(entry: str, base: str) -> str:
        return os.path.join(os.path.abspath(os.path.join(base, entry)), "")

    own = {root(p, folder) for p in [folder, *(p for p in path if p not in saved_path)]}
    roots = sorted(own | {root(p, saved_cwd) for p in saved_path}, key=len, reverse=True)
    for name in [n for n in sys.modules if n not in before]:
        file = getattr(sys.modules[name], "__file__", None)
        if not isinstance(file, str):
            continue
        found = next((r for r in roots if os.path.abspath(file).startswith(r)), None)
        if found in own:
            del sys.modules[name]


def _controller_module_names() -> dict[str, ModuleType]:
    """The modules a controller imports: ``controller`` and its submodules."""
    modules = {"controller": controller_module}
    for name in controller_module.SUBMODULES:
        modules[f"controller.{name}"] = getattr(controller_module, name)
    return modules


def _install_controller_package() -> dict[str, ModuleType]:
    """Installs :mod:`mazesim.webots.controller` as the package ``controller``, its submodules
    as ``controller.<name>``; returns the ``controller`` entries of ``sys.modules`` it
    replaced."""
    saved = {
        name: module
        for name, module in sys.modules.items()
        if name == "controller" or name.startswith("controller.")
    }
    for name in saved:
        del sys.modules[name]
    sys.modules.update(_controller_module_names())
    return saved


def _restore_modules(saved: dict[str, ModuleType]) -> None:
    """Removes every ``controller`` entry of ``sys.modules`` (the run's, and any the
    controller added) and puts back those :func:`_install_controller_package` replaced."""
    for name in [n for n in sys.modules if n == "controller" or n.startswith("controller.")]:
        del sys.modules[name]
    sys.modules.update(saved)


#: Whether this process runs one controller of a world run (a controller process,
#: :mod:`mazesim.webots.controller_process`), whose ``os._exit`` ends it alone, as in Webots.
OWN_PROCESS = False


@contextlib.contextmanager
def _process_exit_as_system_exit() -> Iterator[None]:
    """While a controller runs in mazesim's own process, its ``os._exit(status)`` ends the
    controller with that status, as a ``sys.exit(status)``, not mazesim with it: in Webots it
    ends the controller's process alone, and here the run's outputs (summary.json, the
    trajectory) and a notebook's kernel outlive it. (A crash of the interpreter itself, a
    segmentation fault, still ends the process: a C controller's runs apart.) In a process of
    the controller's own (:data:`OWN_PROCESS`) it ends that process, as in Webots."""
    if OWN_PROCESS:
        yield
        return
    process_exit = os._exit

    def controller_exit(status: int) -> NoReturn:
        raise SystemExit(status)

    os._exit = controller_exit
    try:
        yield
    finally:
        os._exit = process_exit


def _exit_status(request: SystemExit) -> tuple[int, str]:
    """The exit status and message of a controller's ``sys.exit``."""
    code = request.code
    if code is None:
        return 0, ""
    if isinstance(code, int):
        # sys.exit(True) ends Python with status 1: a number, not a bool, in the summary.
        return process_status(int(code)), ""
    return EXIT_CONTROLLER_ERROR, f"{code}\n"


def process_status(code: int) -> int:
    """The exit status a process ended by ``sys.exit(code)`` has: Python hands the system a C
    ``long`` (255 for a number outside one), of which the system keeps the low 8 bits
    (``sys.exit(256)`` ends with 0, ``sys.exit(-1)`` with 255)."""
    if not -(2**63) <= code < 2**63:
        return 255
    return code & 0xFF


#: The folder of the package's own modules (a controller's frames are outside it).
_PACKAGE_FOLDER = os.path.dirname(os.path.dirname(os.path.abspath(__file__))) + os.sep


def _controller_traceback(failure: BaseException) -> str:
    """The traceback of a controller's exception, from the controller's own first frame."""
    if isinstance(failure, SyntaxError):
        return "".join(traceback.format_exception_only(type(failure), failure))
    trace: TracebackType | None = failure.__traceback__
    # The first frame is the runner's exec; the controller's file comes next.
    if trace is not None and trace.tb_next is not None:
        trace = trace.tb_next
    if isinstance(failure, MazesimError):
        # A call the package refused: the trace ends at the controller's own line, not in the
        # package's frames that checked the call.
        frames = traceback.extract_tb(trace)
        while len(frames) > 1 and frames[-1].filename.startswith(_PACKAGE_FOLDER):
            frames.pop()
        return "".join(
            [
                "Traceback (most recent call last):\n",
                *traceback.format_list(frames),
                *traceback.format_exception_only(type(failure), failure),
            ]
        )
    text = "".join(traceback.format_exception(type(failure), failure, trace))
    robot = controller_module.Robot.created
    if isinstance(failure, AttributeError) and getattr(failure, "obj", 0) is None and robot:
        # A method called on the None of a device the robot does not have.
        text += robot._missing_devices_line()  # noqa: SLF001 - the run's own robot
    return text
