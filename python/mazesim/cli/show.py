"""``mazesim show WORLD...``: a labelled PNG of each world, written or opened.

WORLD is a built-in world's name, a mazesim world file (``.toml``) or a Webots world (``.wbt``,
imported; what the import left out or approximated is listed beside the picture). Several worlds
(``mazesim show mazes/*.toml``) each get their own picture, ``NAME.png`` after the world's name.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import webbrowser
from pathlib import Path
from typing import TYPE_CHECKING, Any, TextIO

from mazesim._figures import figure_file
from mazesim._paths import file_name_of, refuse_overwriting_inputs, shell_command
from mazesim.cli._help import examples
from mazesim.errors import InvalidArgumentError, _shown

if TYPE_CHECKING:
    from mazesim import World

__all__ = ["run_show"]


def register(commands: Any) -> None:
    """Adds ``show`` to the ``mazesim`` command's subparsers."""
    show = commands.add_parser(
        "show",
        help="draw a world (built-in, .toml or .wbt) into a PNG with a legend",
        description=(
            "Draw a world with a legend: walls, floor paint, checkpoints with their codes and "
            "reading directions, start, goal and the maze grid when there is one; for a .wbt "
            "world the importer's warnings are listed beside it. For a cell maze it says whether "
            "the navigator can learn it (a goal in reach, barcode checkpoints). Writes -o FILE "
            "(default: "
            "NAME.png in this folder, NAME being the world's name), or opens the picture with "
            "--open. Several worlds each get their own NAME.png."
        ),
        epilog=examples(
            "mazesim show seed-maze",
            "mazesim show my-maze.toml -o my-maze.png",
            "mazesim show Maze.wbt --open",
            "mazesim show mazes/*.toml",
        ),
    )
    show.add_argument(
        "world",
        metavar="WORLD",
        nargs="+",
        help="a built-in world name, a .toml or a .wbt; several: a picture each",
    )
    show.add_argument(
        "-o",
        "--out",
        type=figure_file,
        default=None,
        metavar="FILE.png",
        help="the picture to write: PNG, or PDF or SVG by its suffix (FILE.pdf, FILE.svg)",
    )
    show.add_argument(
        "--open",
        action="store_true",
        help="open the picture with the system's viewer (written to a temporary file unless -o)",
    )
    show.set_defaults(run=lambda args: run_show(args, sys.stdout))


def run_show(args: argparse.Namespace, out: TextIO) -> int:
    """Runs ``mazesim show``: every world is loaded (and its picture's file named) before any
    picture is written, so a bad world or two worlds of one name write nothing."""
    from mazesim.replay.preview import load_with_warnings

    names: list[str] = list(args.world)
    if args.out is not None and len(names) > 1:
        raise InvalidArgumentError(
            f"expected one WORLD with -o (it names one picture), found {len(names)} worlds: "
            "leave -o out to write each to NAME.png after its world's name, or show them one "
            "at a time"
        )
    if args.out is not None:
        refuse_overwriting_inputs([("-o", args.out)], [("the world", names[0])])
    loaded = [(name, *load_with_warnings(name)) for name in names]
    if args.out is None and not args.open:
        _refuse_shared_picture_names([(name, world.name) for name, world, _ in loaded])
    for name, world, warnings in loaded:
        _show_one(args, name, world, warnings, out)
    return 0


def _refuse_shared_picture_names(worlds: list[tuple[str, str]]) -> None:
    """Refuses worlds (given as, world name) whose pictures would be one file ``NAME.png``."""
    given_as: dict[str, str] = {}
    for name, world_name in worlds:
        picture = file_name_of(world_name, ".png")
        if picture in given_as:
            raise InvalidArgumentError(
                f"expected worlds of different names (each is drawn to NAME.png), found "
                f"{given_as[picture]} and {name} both named {_shown(world_name)}: show them one "
                "at a time with -o, or give one of them another `name` in its file"
            )
        given_as[picture] = name


def _show_one(
    args: argparse.Namespace, name: str, world: World, warnings: list[str] | None, out: TextIO
) -> None:
    """Draws one loaded world (``name`` as given on the command line) and says what it wrote."""
    from mazesim.replay.preview import save_world_preview

    path = args.out
    if path is None:
        # The world's name is the file's to choose: it names a file here, never a folder.
        if args.open:
            handle, path = tempfile.mkstemp(prefix=file_name_of(world.name, "-"), suffix=".png")
            os.close(handle)
        else:
            path = file_name_of(world.name, ".png")
    save_world_preview(world, path, warnings)
    imported = f" ({len(warnings)} importer warnings)" if warnings is not None else ""
    out.write(f"wrote {path}{imported}\n")
    if world.cell_maze() is not None:
        from mazesim.episodes import learning_problems

        problems = learning_problems(world)
        out.write(
            f"the navigator cannot learn it: {'; '.join(problems)}\n"
            if problems
            else f"{len(world.checkpoints())} checkpoints and a goal in reach: the navigator can "
            f"learn it ({shell_command('mazesim', 'train', '--world', name)})\n"
        )
    if args.open and not webbrowser.open(Path(path).resolve().as_uri()):
        out.write(f"no viewer could be started here; open {shell_command(path)} yourself\n")
