"""The ``mazesim`` command line.

:func:`main` is the ``mazesim`` entry point; :func:`build_parser` builds its parser from the
command modules of this package (:data:`COMMANDS`), each adding its subcommand(s). Building
the parsers imports only light modules: a command imports what it needs when it runs. Errors are
printed as one line, ``mazesim: error: <message>``, with exit code 2.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import os
import stat
import sys
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any, NoReturn

import mazesim
from mazesim._error_tree import io_error
from mazesim.cli._help import CommandParser, examples
from mazesim.cli.crash_guard import CrashWatch, runs_a_controller_here
from mazesim.errors import MazesimError, _closest_name, _command_line, _plain, _shown

__all__ = ["COMMANDS", "build_parser", "main"]

#: The commands in the order ``mazesim --help`` lists them: the module that adds each, and its
#: one-line summary (the module's own, checked by the tests). A module has ``register(commands)``,
#: which adds its parser(s) to the ``argparse`` subparsers object and sets
#: ``run=<function(args) -> int>`` as the parser default.
COMMANDS: dict[str, tuple[str, str]] = {
    "worlds": (
        "mazesim.cli.worlds",
        "list the built-in worlds, or export one to a world file to edit",
    ),
    "demo": (
        "mazesim.cli.demo",
        "drive the robot (avoid-collision or the shipped navigator) and plot its path",
    ),
    "bench": (
        "mazesim.cli.bench",
        "measure steady-state env-steps per second, contact share and memory per env",
    ),
    "ros": ("mazesim.cli.ros", "run the ROS 1 bridge and controller nodes (needs ROS 1)"),
    "ros2": (
        "mazesim.cli.ros2",
        "run the ROS 2 bridge and controller nodes over DDS (needs mazesim[ros2])",
    ),
    "barcode-study": (
        "mazesim.cli.barcode",
        "measure barcode reading (right / wrong / missed) by threshold and by speed",
    ),
    "transfer-study": (
        "mazesim.cli.transfer",
        "measure a navigator on a grid of robot perturbations (sim-to-real transfer)",
    ),
    "import-wbt": (
        "mazesim.cli.webots",
        "import a Webots .wbt world (obstacles, robot pose, time step)",
    ),
    "webots": ("mazesim.cli.webots", "run Webots-style e-puck controllers on mazesim"),
    "sweep": (
        "mazesim.cli.sweep",
        "train a grid of settings (seeds, rates, mazes) as Ray tasks; summarise them",
    ),
    "train": (
        "mazesim.cli.train",
        "train the hierarchical navigator (lower level on generated mazes, higher level on the "
        "world)",
    ),
    "eval": (
        "mazesim.cli.evaluate",
        "measure a trained navigator: success, collisions, steps, decisions",
    ),
    "replay": ("mazesim.cli.replay", "turn a recorded run into an HTML replay or a video"),
    "show": (
        "mazesim.cli.show",
        "draw a world (built-in, .toml or .wbt) into a PNG with a legend",
    ),
    "info": (
        "mazesim.cli.info",
        "print what a bug report needs: versions, platform, installed packages",
    ),
}

#: Exit code of a run that failed on an error of the user's input or of the file system.
EXIT_ERROR = 2
#: Exit code of a run stopped with Ctrl-C (128 + SIGINT), as shells report it.
EXIT_INTERRUPTED = 130
#: Exit code of a run whose output pipe was closed by its reader (128 + SIGPIPE), as shells report
#: a command that a closed pipe ended (``mazesim worlds | head -1``).
EXIT_BROKEN_PIPE = 141


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """Builds the argument parser of the ``mazesim`` command.

    Args:
        command: The command to build in full; the others are listed by name and summary only,
            which is enough for ``mazesim --help`` and imports none of their modules. None
            builds every command in full; a name that is not a command builds none.
    """
    parser = CommandParser(
        prog="mazesim",
        description=(
            "mazesim: a fast, deterministic simulator of the e-puck robot in mazes. "
            "Run 'mazesim COMMAND --help' for the options of a command."
        ),
        epilog=examples(
            "mazesim worlds",
            "mazesim demo --controller hrl",
            "mazesim eval --episodes 20",
            "mazesim COMMAND --help",
        ),
    )
    parser.add_argument("--version", action="version", version=f"mazesim {mazesim.__version__}")
    commands = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    registered: set[str] = set()
    for name, (module_name, summary) in COMMANDS.items():
        if command is None or COMMANDS.get(command, ("",))[0] == module_name:
            if module_name not in registered:
                importlib.import_module(module_name).register(commands)
                registered.add(module_name)
        else:
            commands.add_parser(name, help=summary)
    return parser


#: The controllers mazesim has built in, by name, and where each runs: a stray word close to one
#: (`mazesim webots run WORLD braitenburg`) is told the name and where to give it.
BUILT_IN_CONTROLLERS = {
    "braitenberg": "BatchSimulator.run(controller='braitenberg') and mazesim bench --workload",
    "avoid-collision": "mazesim demo --controller and BatchSimulator.run(controller=...)",
    "random": "BatchSimulator.run(controller='random') and mazesim bench --workload",
    "hrl": "mazesim demo --controller",
    "e-puck_avoid_obstacles": (
        "mazesim webots run, for a world's E-puck that names no controller (its PROTO's default)"
    ),
}


def _built_in_meant(words: list[str]) -> list[str]:
    """For each word of ``words`` that is not an option and is close to the name of a controller
    mazesim has built in (:data:`BUILT_IN_CONTROLLERS`): that name and where it runs."""
    meant = []
    for word in words:
        if word.startswith("-"):
            continue
        closest = _closest_name(word, list(BUILT_IN_CONTROLLERS), 0.8)
        if closest is not None:
            meant.append(
                f"did you mean the built-in controller {_shown(closest)}? it runs in "
                f"{BUILT_IN_CONTROLLERS[closest]}"
            )
    return meant


def _command_run(
    parser: argparse.ArgumentParser, args: argparse.Namespace
) -> argparse.ArgumentParser:
    """The parser of the command ``args`` run (``mazesim demo``, ``mazesim webots run``)."""
    while True:
        commands = next(
            (a for a in parser._actions if isinstance(a, argparse._SubParsersAction)), None
        )
        chosen = None if commands is None else getattr(args, commands.dest, None)
        if commands is None or chosen not in commands.choices:
            return parser
        parser = commands.choices[chosen]


def _refuse_dashless_options(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """Refuses a word taken as an argument without an option (``mazesim show seed-maze out
    x.png``: 'out' taken as a WORLD) that is the name of one of the command's options and names
    no file and no built-in world, robot profile or controller: an option typed without its
    dashes, told the option."""
    parser = _command_run(parser, args)
    options = {
        _plain(option.lstrip("-")): option
        for action in parser._actions
        for option in action.option_strings
    }
    for action in parser._actions:
        if action.option_strings or isinstance(action, argparse._SubParsersAction):
            continue
        given = getattr(args, action.dest, None)
        for word in given if isinstance(given, list) else [given]:
            if (
                isinstance(word, str)
                and _plain(word) in options
                and not os.path.lexists(word)
                and word not in _built_in_names()
            ):
                parser.error(
                    f"argument {action.metavar or action.dest}: {_shown(word)} is no file; did "
                    f"you mean the option {_shown(options[_plain(word)])}?"
                )


def _built_in_names() -> set[str]:
    """The names of the built-in worlds, robot profiles and controllers: what a word given
    without an option may name besides a file."""
    from mazesim._core import builtin_world_names, robot_profile_names

    return {*builtin_world_names(), *robot_profile_names(), *BUILT_IN_CONTROLLERS}


def _refuse_unknown(
    parser: argparse.ArgumentParser, args: argparse.Namespace, unknown: list[str]
) -> NoReturn:
    """Refuses arguments the command does not take with the usage of the command run (``mazesim
    demo``, ``mazesim webots run``), not mazesim's, and, for a mistyped option, the one meant."""
    parser = _command_run(parser, args)
    # Compared without their dashes, and closer than names must be: short words look alike. The
    # start of one option's name (`demo --sec`) is told that name: options are taken whole.
    options = {
        option.lstrip("-"): option for action in parser._actions for option in action.option_strings
    }
    typed = [word.partition("=")[0] for word in unknown if word.startswith("-")]
    # A slip of one of this command's own options (`eval --episode`) is told that option, even
    # when another command takes the word as typed (replay's --episode); an option no closer to
    # one of this command's is named as another command's (`demo --policy`).
    closest_of = {word: _closest_name(word.lstrip("-"), list(options), 0.8) for word in typed}
    meant = [
        f"{_shown(options[closest])} for {_shown(word)}"
        for word, closest in closest_of.items()
        if closest is not None
    ]
    # An option typed without its dashes (`worlds export seed-maze`, `eval json`, `demo seconds
    # 5`): a word no argument takes that is, or nearly is, the name of one of the command's
    # options is told that option, whichever option it is.
    bare = [word.partition("=")[0] for word in unknown if word[:1].isalpha()]
    meant += [
        f"{_shown(options[closest])} for {_shown(word)}"
        for word in bare
        if (closest := _closest_name(word, list(options), 0.8)) is not None
    ]
    elsewhere = {
        word: taken
        for word, taken in _commands_taking(typed, parser.prog).items()
        if closest_of[word] is None
    }
    # An argument the command takes without an option, given with one (`show --world X`).
    positional = {
        name: str(action.metavar or action.dest)
        for action in parser._actions
        if not action.option_strings
        for name in [str(action.dest), *str(action.metavar or "").lower().split("|")]
    }
    given = [
        f"{positional[name]} is given without {_shown(word)}: {parser.prog} {positional[name]}"
        for word in typed
        if (name := word.lstrip("-").replace("-", "_")) in positional
    ]
    if meant or given:
        elsewhere = {}
    parser.error(
        f"unrecognized arguments: {' '.join(unknown)}"
        + (f"; did you mean {', '.join(meant)}?" if meant else "")
        + "".join(f"; {each}" for each in given)
        + "".join(f"; {each}" for each in elsewhere.values())
        + "".join(f"; {each}" for each in _built_in_meant(unknown))
    )


def _commands_taking(typed: list[str], prog: str) -> dict[str, str]:
    """For each option of ``typed`` that the command ``prog`` lacks but others take (``mazesim
    demo --policy``): which commands take it (``--policy is an option of mazesim eval, ...``),
    so that a user who reached for the wrong command is told the right one."""
    if not typed:
        return {}
    taking: dict[str, list[str]] = {word: [] for word in typed}

    def walk(parser: argparse.ArgumentParser) -> None:
        for action in parser._actions:
            if isinstance(action, argparse._SubParsersAction):
                for chosen in dict.fromkeys(action.choices.values()):
                    walk(chosen)
            for word in taking:
                if word in action.option_strings and parser.prog != prog:
                    taking[word].append(parser.prog)

    walk(build_parser())
    return {
        word: f"{word} is an option of {', '.join(sorted(set(progs)))}"
        + (" (see its --help)" if len(set(progs)) == 1 else "")
        for word, progs in taking.items()
        if progs
    }


def _command_word(arguments: Sequence[str]) -> str:
    """The command a command line runs: its first word that is not an option ("" if none)."""
    return next((word for word in arguments if not word.startswith("-")), "")


def _one_line(message: str) -> str:
    """Joins a possibly multi-line message into one line."""
    parts = [line.strip() for line in message.splitlines() if line.strip()]
    return "; ".join(parts) if parts else "unknown error"


def _stdout_is_a_pipe() -> bool:
    """Whether standard output is a pipe (whose reader may close it early)."""
    try:
        return stat.S_ISFIFO(os.fstat(sys.stdout.fileno()).st_mode)
    except (OSError, ValueError, AttributeError):
        return False


def _printable_output() -> None:
    """Lets stdout print any file name: under a locale whose encoding cannot show a character
    (a file name of non-UTF-8 bytes, say, or ``PYTHONIOENCODING=ascii``) the character is
    written escaped (``\\udcff``) instead of failing the command after its work is done."""
    for stream in (sys.stdout, sys.stderr):
        reconfigure = getattr(stream, "reconfigure", None)
        if reconfigure is not None and getattr(stream, "errors", None) == "strict":
            reconfigure(errors="backslashreplace")


class _NamedOutput:
    """The standard output while a command runs: a write or flush that fails names it (the
    system names no file for it: "No space left on device" alone, under ``> /dev/full``).
    Everything else is the stream's own."""

    def __init__(self, stream: Any) -> None:
        self._stream = stream

    def __getattr__(self, name: str) -> Any:
        return getattr(self._stream, name)

    def write(self, text: str) -> int:
        try:
            return int(self._stream.write(text))
        except OSError as error:
            raise _named(error) from None

    def writelines(self, lines: Any) -> None:
        for line in lines:
            self.write(line)

    def flush(self) -> None:
        try:
            self._stream.flush()
        except OSError as error:
            raise _named(error) from None


def _named(error: OSError) -> OSError:
    if error.filename is None and not isinstance(error, BrokenPipeError):
        error.filename = "the standard output"
    return error


@contextlib.contextmanager
def _named_output() -> Iterator[None]:
    """Makes ``sys.stdout`` a :class:`_NamedOutput` while the block runs, as it was after."""
    before = sys.stdout
    sys.stdout = _NamedOutput(before) if before is not None else before
    try:
        yield
    finally:
        sys.stdout = before


def main(argv: Sequence[str] | None = None) -> int:
    """Runs the ``mazesim`` command.

    Args:
        argv: The arguments after the program name; by default ``sys.argv[1:]`` (the command
            line itself: a controller's threads left running then end with it).

    Returns:
        The exit code: 0 on success, 2 on an error (printed as one line on stderr), 130 on Ctrl-C.
    """
    # A controller run in this process could crash it: a watcher says so if it does.
    watch = CrashWatch() if argv is None and runs_a_controller_here(sys.argv[1:]) else None
    try:
        code = _main(argv)
    finally:
        if watch is not None:
            watch.ended()
    if argv is None:
        _end_without_controller_threads(code)
    return code


def _end_without_controller_threads(code: int) -> None:
    """Ends the process now, with ``code``, when a controller run in it left threads running
    (``mazesim.webots.runner.LEFT_RUNNING``): Python would wait for them at exit for ever, where
    Webots ends a controller's process with its run. Its outputs are written already."""
    runner = sys.modules.get("mazesim.webots.runner")
    left = [t for t in getattr(runner, "LEFT_RUNNING", []) if t.is_alive()]
    if not left:
        return
    names = ", ".join(_shown(thread.name) for thread in left[:5])
    print(
        f"mazesim: warning: the controller left {len(left)} thread(s) running ({names}); the "
        "command ends without waiting for them, as Webots ends a controller's process with its "
        "run (make such a thread a daemon, or end it when step() returns -1)",
        file=sys.stderr,
    )
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(Exception):
            stream.flush()
    os._exit(code)


def _main(argv: Sequence[str] | None) -> int:
    """:func:`main` but for the end of a controller's threads."""
    arguments = list(sys.argv[1:] if argv is None else argv)
    _printable_output()
    # No shell passes a NUL character (it ends a C string); from Python it would reach a path
    # or a name as "embedded null byte". Refused here, once, for every command.
    with_nul = [i for i, word in enumerate(arguments) if "\x00" in str(word)]
    if with_nul:
        word = str(arguments[with_nul[0]])
        print(
            f"mazesim: error: argument {with_nul[0] + 1} ({_shown(word[:40])}) "
            "holds a NUL character, which no file name or value has; remove it",
            file=sys.stderr,
        )
        return EXIT_ERROR
    command = _command_word(arguments)
    ros_arguments: Any = None
    if command in ("ros", "ros2"):
        try:
            if command == "ros":
                from mazesim.cli.ros import check_before_parsing
            else:
                from mazesim.cli.ros2 import check_before_parsing

            check_before_parsing(arguments)
            if command == "ros2":
                from mazesim.cli.ros2 import take_ros_arguments

                arguments, ros_arguments = take_ros_arguments(arguments)
        except MazesimError as error:
            print(f"mazesim: error: {_one_line(str(error))}", file=sys.stderr)
            return EXIT_ERROR
    parser = build_parser(command)
    try:
        args, unknown = parser.parse_known_args(arguments)
        if unknown:
            _refuse_unknown(parser, args, unknown)
        _refuse_dashless_options(parser, args)
    except SystemExit as exit_request:
        # --help and --version exit with None (success); usage errors with 2.
        code = exit_request.code
        return code if isinstance(code, int) else (0 if code is None else EXIT_ERROR)
    if command == "ros2":
        args.ros_arguments = ros_arguments
    try:
        # Messages name the options (--out), not Python's parameters, and the standard output.
        with _command_line(), _named_output():
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
        if isinstance(error, OSError) and not isinstance(error, MazesimError):
            # The file and the system's reason, not "[Errno 17] ..."; the package's own errors
            # that are also OSErrors (ClusterConnectionError...) say what to do themselves.
            error = io_error(error)
        print(f"mazesim: error: {_one_line(str(error))}", file=sys.stderr)
        return EXIT_ERROR
    except MemoryError:
        print(
            "mazesim: error: out of memory; ask for less (fewer envs, episodes, steps or seconds)",
            file=sys.stderr,
        )
        return EXIT_ERROR
    except KeyboardInterrupt as interrupted:
        # A command may say what to do next (how to continue): the interrupt's message.
        then = f"; {interrupted}" if str(interrupted) else ""
        print(f"mazesim: interrupted{then}", file=sys.stderr)
        return EXIT_INTERRUPTED
    except BaseException as error:
        # A bug, not the user's doing: one line and how to report it, not a traceback. (pyo3's
        # PanicException derives from BaseException; SystemExit and GeneratorExit pass.)
        if isinstance(error, (SystemExit, GeneratorExit)):
            raise
        missing = _missing_package(error)
        if missing is not None:
            print(f"mazesim: error: {missing}", file=sys.stderr)
            return EXIT_ERROR
        print(
            f"mazesim: error: internal error, please report it with the command that caused "
            f"it: {type(error).__name__}: {_one_line(str(error))}",
            file=sys.stderr,
        )
        return EXIT_ERROR


#: The name pip installs a package by, where it differs from the name it is imported by.
_PIP_NAMES = {"PIL": "pillow"}


def _missing_package(error: BaseException) -> str | None:
    """What to do when ``error`` says a package outside mazesim is not installed (a dependency
    left out or removed: install it), or is installed but cannot be loaded (its compiled part
    failed to load: too little memory for it, or a broken install); None for any other error, a
    module of mazesim's own included (a broken installation: a bug to report)."""
    if not isinstance(error, ImportError):
        return None
    module = _package_of(error)
    if module is None or module == "mazesim":
        return None
    package = _PIP_NAMES.get(module, module)
    if isinstance(error, ModuleNotFoundError):
        return (
            f"this command needs the Python package {_shown(package)}, which is not installed "
            f"for {sys.executable}: install it with {sys.executable} -m pip install {package}"
        )
    return (
        f"this command needs the Python package {_shown(package)}, which is installed but could "
        f"not be loaded ({_one_line(str(error))}): if memory is short (a ulimit), allow more; "
        f"else reinstall it with {sys.executable} -m pip install --force-reinstall {package}"
    )


def _package_of(error: ImportError) -> str | None:
    """The top-level package an import failed on: its module's name, else the folder under
    ``site-packages`` of the file that failed to load."""
    if error.name:
        return error.name.partition(".")[0]
    parts = Path(error.path).parts if error.path else ()
    if "site-packages" in parts and parts.index("site-packages") + 1 < len(parts):
        return parts[parts.index("site-packages") + 1].partition(".")[0]
    return None
