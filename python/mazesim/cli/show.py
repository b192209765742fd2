"""``mazesim show WORLD``: a labelled PNG of a world, written or opened.

WORLD is a built-in world's name, a mazesim world file (``.toml``) or a Webots world (``.wbt``,
imported; what the import left out or approximated is listed beside the picture).
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import webbrowser
from pathlib import Path
from typing import Any, TextIO

from mazesim._figures import figure_file
from mazesim._paths import file_name_of, refuse_overwriting_inputs, shell_command
from mazesim.cli._help import examples

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
            "NAME.png in this folder), or opens the picture with --open."
        ),
        epilog=examples(
            "mazesim show seed-maze",
            "mazesim show my-maze.toml -o my-maze.png",
            "mazesim show Maze.wbt --open",
        ),
    )
    show.add_argument("world", metavar="WORLD", help="a built-in world name, a .toml or a .wbt")
    show.add_argument(
        "-o", "--out", type=figure_file, default=None, metavar="FILE.png", help="the PNG to write"
    )
    show.add_argument(
        "--open",
        action="store_true",
        help="open the picture with the system's viewer (written to a temporary file unless -o)",
    )
    show.set_defaults(run=lambda args: run_show(args, sys.stdout))


def run_show(args: argparse.Namespace, out: TextIO) -> int:
    """Runs ``mazesim show``."""
    from mazesim.replay.preview import load_with_warnings, save_world_preview

    if args.out is not None:
        refuse_overwriting_inputs([("-o", args.out)], [("the world", args.world)])
    world, warnings = load_with_warnings(args.world)
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
            f"learn it ({shell_command('mazesim', 'train', '--world', args.world)})\n"
        )
    if args.open and not webbrowser.open(Path(path).resolve().as_uri()):
        out.write(f"no viewer could be started here; open {path} yourself\n")
    return 0
