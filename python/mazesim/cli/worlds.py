"""``mazesim worlds``: the built-in worlds, one line each."""

from __future__ import annotations

import sys
from typing import Any, TextIO

from mazesim.cli._help import examples

__all__ = ["run_worlds"]


def register(commands: Any) -> None:
    """Adds ``worlds`` to the ``mazesim`` command's subparsers."""
    worlds = commands.add_parser(
        "worlds",
        help="list the built-in worlds",
        description="List the built-in worlds: name, size and number of barcode checkpoints, "
        "and whether the world has a goal. Any command's --world takes these names.",
        epilog=examples("mazesim worlds"),
    )
    worlds.set_defaults(run=lambda args: run_worlds(sys.stdout))


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
