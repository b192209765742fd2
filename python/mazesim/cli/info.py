"""``mazesim info``: what a bug report needs about this installation, in one block to paste.

It prints mazesim's version and where it is installed, the compiled core's file, Python, the
operating system and its C library, the processor cores, and the versions of the packages
mazesim uses (read from the installed packages' metadata: nothing is imported, so it stays quick
with torch installed, and works when one of them is broken).
"""

from __future__ import annotations

import argparse
import os
import platform
import sys
from importlib import metadata
from typing import Any, TextIO

import mazesim
from mazesim.cli._help import examples

__all__ = ["OPTIONAL_PACKAGES", "installation_report", "run_info"]

#: The packages whose versions a report lists: mazesim's dependencies, then its extras' (a
#: missing one is listed as "not installed").
OPTIONAL_PACKAGES = (
    "numpy",
    "matplotlib",
    "pillow",
    "tqdm",
    "gymnasium",
    "pettingzoo",
    "stable-baselines3",
    "sb3-contrib",
    "torch",
    "ray",
    "imageio",
    "moviepy",
    "tensorboardX",
    "selenium",
)


def register(commands: Any) -> None:
    """Adds ``info`` to the ``mazesim`` command's subparsers."""
    info = commands.add_parser(
        "info",
        help="print what a bug report needs: versions, platform, installed packages",
        description=(
            "Print mazesim's version and where it is installed, Python, the operating system and "
            "its C library, the cores, and the versions of the packages mazesim uses (not "
            "installed ones say so). Paste it into a bug report, with the command that failed "
            "and its full output."
        ),
        epilog=examples("mazesim info"),
    )
    info.set_defaults(run=lambda args: run_info(args, sys.stdout))


def installation_report() -> list[tuple[str, str]]:
    """The report's lines as (what, value) pairs, in the order printed."""
    core = getattr(sys.modules.get("mazesim._core"), "__file__", None) or "?"
    libc, libc_version = platform.libc_ver()
    lines = [
        ("mazesim", mazesim.__version__),
        ("installed at", os.path.dirname(os.path.abspath(mazesim.__file__))),
        ("compiled core", core),
        ("python", f"{platform.python_version()} ({sys.executable})"),
        ("platform", platform.platform()),
        ("machine", platform.machine() or "?"),
        ("C library", f"{libc} {libc_version}".strip() or "?"),
        ("cores", str(os.cpu_count() or "?")),
    ]
    for package in OPTIONAL_PACKAGES:
        try:
            version = metadata.version(package)
        except metadata.PackageNotFoundError:
            version = "not installed"
        lines.append((package, version))
    return lines


def run_info(args: argparse.Namespace, out: TextIO) -> int:
    """Runs ``mazesim info``."""
    del args
    lines = installation_report()
    width = max(len(what) for what, _ in lines)
    for what, value in lines:
        out.write(f"{what:<{width}}  {value}\n")
    return 0
