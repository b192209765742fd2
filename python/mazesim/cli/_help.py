"""How the commands' ``--help`` reads: wrapped paragraphs, and examples kept as written.

The ``mazesim`` parser is a :class:`CommandParser`, and so is every command's parser (argparse
makes subparsers of their parent's class): each formats its help with :class:`HelpFormatter`.
:func:`examples` makes the ``examples:`` section of a command's epilog.
"""

from __future__ import annotations

import argparse
import textwrap
from typing import Any, NoReturn

from mazesim._arguments import BoundedParser
from mazesim.errors import _closest_name, _shown

__all__ = ["CommandParser", "HelpFormatter", "examples"]


class HelpFormatter(argparse.HelpFormatter):
    """argparse's formatter, but a description or epilog is paragraphs (split at blank lines),
    each wrapped to the terminal, and lines indented by two spaces (examples) are kept as
    written."""

    def _fill_text(self, text: str, width: int, indent: str) -> str:
        paragraphs = []
        for paragraph in text.strip("\n").split("\n\n"):
            first, *rest = paragraph.splitlines() or [""]
            if rest and not all(line.startswith("  ") for line in rest):
                first, rest = paragraph, []
            head = textwrap.fill(
                " ".join(first.split()), width, initial_indent=indent, subsequent_indent=indent
            )
            paragraphs.append("\n".join([head, *(indent + line for line in rest)]))
        return "\n\n".join(paragraphs)


class CommandParser(BoundedParser):
    """An argument parser whose help is formatted by :class:`HelpFormatter` unless told
    otherwise, and which takes each option by its whole name only (a :class:`BoundedParser`:
    argparse's abbreviations made ``mazesim webots run C.py --robot FILE`` the prefix of
    ``--robot-controller``, a message about an option never typed); an option the command lacks
    is refused, naming the commands that take it."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("formatter_class", HelpFormatter)
        super().__init__(*args, **kwargs)

    def error(self, message: str) -> NoReturn:
        """argparse's usage error; a command run without its subcommand (``mazesim``, ``mazesim
        webots``) also lists the subcommands and where their options are."""
        commands = next(
            (a for a in self._actions if isinstance(a, argparse._SubParsersAction)), None
        )
        if commands is not None and message.endswith(f"required: {commands.metavar}"):
            message += (
                f" (one of: {', '.join(commands.choices)}; "
                f"'{self.prog} {commands.metavar} --help' gives its options)"
            )
        # The base class shortens a word typed too long.
        super().error(message)

    def _check_value(self, action: argparse.Action, value: Any) -> None:
        """argparse's check of a value against the option's choices (or the commands), with the
        choice meant for a typo: ``invalid choice: 'trian' (...); did you mean 'train'?``."""
        try:
            super()._check_value(action, value)
        except argparse.ArgumentError as error:
            meant = _closest_name(str(value), [str(choice) for choice in action.choices or ()])
            if meant is None:
                raise
            raise argparse.ArgumentError(
                action, f"{error.message}; did you mean {_shown(meant)}?"
            ) from None


def examples(*command_lines: str, notes: str = "") -> str:
    """An epilog: ``notes`` (wrapped), then ``examples:`` and one command line per line.

    Args:
        command_lines: Whole command lines, each starting with ``mazesim``.
        notes: A paragraph shown before the examples.
    """
    listed = "examples:\n" + "\n".join(f"  {line}" for line in command_lines)
    return f"{notes}\n\n{listed}" if notes else listed
