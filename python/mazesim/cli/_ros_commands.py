"""What ``mazesim ros`` and ``mazesim ros2`` share: their commands written as tables.

Each of :mod:`mazesim.cli.ros` and :mod:`mazesim.cli.ros2` lists its commands as
:class:`Command` rows (help texts, examples, options as ``add_argument``'s words, the runner);
:func:`register_commands` builds the parsers of either from its table. The options both demos
take (the world, the robot profile, the controller, the output folder) and the demos' check that
no output overwrites an input are written here once.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from mazesim._paths import output_path
from mazesim.cli._help import examples

__all__ = [
    "Command",
    "Option",
    "demo_options",
    "option",
    "register_commands",
    "refuse_demo_overwrites",
    "wants_check",
]

#: One option: its flags and the keywords of ``argparse.ArgumentParser.add_argument``.
Option = tuple[tuple[str, ...], dict[str, Any]]


def option(*flags: str, **keywords: Any) -> Option:
    """An :data:`Option`: what ``add_argument(*flags, **keywords)`` would add."""
    return flags, keywords


@dataclass(frozen=True)
class Command:
    """One ``mazesim ros``/``ros2`` command: its help, examples, options and runner; ``extra``
    adds what a table does not hold (such as the viewing options), after the options."""

    name: str
    help: str
    description: str
    examples: tuple[str, ...]
    options: tuple[Option, ...]
    run: Callable[[argparse.Namespace], int]
    extra: tuple[Callable[[argparse.ArgumentParser], None], ...] = ()


def register_commands(
    commands: Any,
    name: str,
    about: tuple[str, str, tuple[str, ...]],
    table: Sequence[Command],
    metavar: str,
) -> None:
    """Adds ``mazesim NAME`` (``about``: its help, description and examples) and one subcommand
    per row of ``table`` to the ``mazesim`` command's subparsers."""
    help_text, description, example_lines = about
    parser = commands.add_parser(
        name, help=help_text, description=description, epilog=examples(*example_lines)
    )
    sub = parser.add_subparsers(dest=f"{name}_command", metavar=metavar, required=True)
    for command in table:
        command_parser = sub.add_parser(
            command.name,
            help=command.help,
            description=command.description,
            epilog=examples(*command.examples),
        )
        for flags, keywords in command.options:
            command_parser.add_argument(*flags, **keywords)
        for add in command.extra:
            add(command_parser)
        command_parser.set_defaults(run=command.run)


def demo_options(controller_help: str, out: str) -> dict[str, Option]:
    """The options both demos take, by name: ``--world``, ``--robot``, ``--controller``
    (``controller_help`` its help) and ``--out`` (``out`` its default)."""
    return {
        "world": option(
            "--world",
            default="seed-maze",
            metavar="NAME|PATH",
            help="built-in world or world file (default: %(default)s)",
        ),
        "robot": option(
            "--robot",
            metavar="NAME|PATH",
            help="built-in robot profile or profile file, with the sensors the controller "
            "reads (default: seed for hrl, e-puck for avoid-collision)",
        ),
        "controller": option(
            "--controller", choices=("hrl", "avoid-collision"), default="hrl", help=controller_help
        ),
        "out": option(
            "--out",
            type=output_path,
            default=out,
            metavar="DIR",
            help="output folder, created if missing (default: %(default)s)",
        ),
    }


def refuse_demo_overwrites(
    args: argparse.Namespace, names: Sequence[str], more: Sequence[tuple[str, str | None]] = ()
) -> None:
    """Refuses a demo whose outputs (``names`` in ``--out``, and ``more``) would overwrite its
    ``--world`` or ``--robot`` file.

    Raises:
        InvalidArgumentError: an output is an input.
    """
    from mazesim._paths import output_files, refuse_overwriting_inputs

    refuse_overwriting_inputs(
        [*output_files(args.out, names), *more], [("--world", args.world), ("--robot", args.robot)]
    )


def wants_check(arguments: Sequence[str], command: str) -> bool:
    """Whether ``arguments`` run ``mazesim COMMAND SUBCOMMAND`` (not its help), so that what
    the command needs installed is checked before the command line is parsed."""
    return len(arguments) >= 2 and arguments[0] == command and not {"-h", "--help"} & set(arguments)
