"""``mazesim worlds``: the built-in worlds, one line each, and the export of one to a world file
to edit (``--export NAME [--out FILE]``)."""

from __future__ import annotations

import argparse
import os
import sys
from typing import Any, TextIO

from mazesim._paths import output_file, refuse_replacing_world_file, shell_command
from mazesim.cli._help import examples
from mazesim.errors import InvalidArgumentError, MazesimIOError, _shown

__all__ = ["export_world", "run_worlds"]


def register(commands: Any) -> None:
    """Adds ``worlds`` to the ``mazesim`` command's subparsers."""
    worlds = commands.add_parser(
        "worlds",
        help="list the built-in worlds, or export one to a world file to edit",
        description="List the built-in worlds: name, size and number of barcode checkpoints, "
        "and whether the world has a goal. Any command's --world takes these names, or the path "
        "of a world file: --export NAME writes a built-in world to a world file to edit "
        "(docs/own-maze.md).",
        epilog=examples(
            "mazesim worlds",
            "mazesim worlds --export seed-maze --out my-maze.toml",
        ),
    )
    worlds.add_argument(
        "--export", metavar="NAME", help="write the built-in world NAME to a world file to edit"
    )
    worlds.add_argument(
        "-o",
        "--out",
        metavar="WORLD_FILE",
        help="with --export: the world file to write (default: NAME.toml in the current "
        "folder; refused if it exists, unless --force)",
    )
    worlds.add_argument(
        "--force", action="store_true", help="with --export: overwrite WORLD_FILE if it exists"
    )
    worlds.set_defaults(run=_run)


def _run(args: argparse.Namespace) -> int:
    if args.export is None:
        for given, option in ((args.force, "--force"), (args.out, "--out")):
            if given:
                raise InvalidArgumentError(
                    f"expected {option} with --export NAME (it names the file to write), found "
                    "it alone"
                )
        return run_worlds(sys.stdout)
    name = args.export
    file = args.out if args.out is not None else f"{name}.toml"
    export_world(name, file, force=args.force)
    # Into a device or a pipe (``--out /dev/stdout``) the world is the output: the status line
    # goes to stderr so that what is piped on stays a world file.
    status = sys.stdout if os.path.isfile(file) else sys.stderr
    print(
        f"wrote {file} (the built-in world {name}); edit it, then: "
        f"{shell_command('mazesim', 'show', file)}",
        file=status,
    )
    return 0


def export_world(name: str, file: str, *, force: bool = False) -> None:
    """Writes the built-in world ``name`` to the world file ``file``.

    Raises:
        UnknownNameError: ``name`` is not a built-in world (the message lists them).
        InvalidArgumentError: ``file`` does not end in ``.toml`` (refused by
            :meth:`mazesim.World.save`, as any world saved under such a name).
        MazesimIOError: ``file`` is an existing file and ``force`` is False
            (:func:`~mazesim._paths.refuse_replacing_world_file`), or it cannot be written.
    """
    import mazesim

    if name not in mazesim.builtin_world_names():
        mazesim.load_world(name)  # not a built-in world: its error lists them
        available = ", ".join(sorted(mazesim.builtin_world_names()))
        raise MazesimIOError(
            f"expected the name of a built-in world to export, found the file {_shown(name)}; "
            f"built-in worlds: {available} (a world file is edited where it is)"
        )
    try:
        output_file(file)
    except argparse.ArgumentTypeError as refused:
        raise MazesimIOError(str(refused)) from None
    refuse_replacing_world_file(file, force)
    mazesim.World.builtin(name).save(file)


def run_worlds(out: TextIO) -> int:
    """Prints one line per built-in world: name, size, checkpoints and goal."""
    import mazesim

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
