"""The ``mazesim`` command line.

:func:`main` is the ``mazesim`` entry point; :func:`build_parser` builds its parser from the
command modules of this package (:data:`COMMAND_MODULES`), each adding its subcommand(s). Building
the parsers imports only light modules: a command imports what it needs when it runs. Errors are
printed as one line, ``mazesim: error: <message>``, with exit code 2.
"""

from __future__ import annotations

import argparse
import importlib
import os
import stat
import sys
from collections.abc import Sequence

import mazesim
from mazesim.errors import MazesimError

__all__ = ["COMMAND_MODULES", "build_parser", "main"]

#: Modules that add subcommands, in the order ``mazesim --help`` lists them: each has
#: ``register(commands)``, which adds its parser(s) to the ``argparse`` subparsers object and sets
#: ``run=<function(args) -> int>`` as the parser default.
COMMAND_MODULES: tuple[str, ...] = (
    "mazesim.cli.worlds",
    "mazesim.cli.demo",
    "mazesim.cli.bench",
    "mazesim.cli.ros",
    "mazesim.cli.barcode",
    "mazesim.cli.webots",
    "mazesim.cli.sweep",
    "mazesim.cli.train",
    "mazesim.cli.evaluate",
    "mazesim.cli.replay",
    "mazesim.cli.show",
)

#: Exit code of a run that failed on an error of the user's input or of the file system.
EXIT_ERROR = 2
#: Exit code of a run stopped with Ctrl-C (128 + SIGINT), as shells report it.
EXIT_INTERRUPTED = 130
#: Exit code of a run whose output pipe was closed by its reader (128 + SIGPIPE), as shells report
#: a command that a closed pipe ended (``mazesim worlds | head -1``).
EXIT_BROKEN_PIPE = 141


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
    for module_name in COMMAND_MODULES:
        importlib.import_module(module_name).register(commands)
    return parser


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


def main(argv: Sequence[str] | None = None) -> int:
    """Runs the ``mazesim`` command.

    Args:
        argv: The arguments after the program name; by default ``sys.argv[1:]``.

    Returns:
        The exit code: 0 on success, 2 on an error (printed as one line on stderr), 130 on Ctrl-C.
    """
    arguments = list(sys.argv[1:] if argv is None else argv)
    try:
        from mazesim.cli.ros import check_before_parsing

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
