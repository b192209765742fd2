"""Compiled Webots controllers in the tests: the compilers they need, their sources written
into controller folders and the build cache they share."""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Any

import pytest

import mazesim
from mazesim.webots import ControllerRun, run_controller

__all__ = ["NEEDS_COMPILERS", "run_twins", "write_source"]

#: Marks the tests that build C and C++ controllers.
NEEDS_COMPILERS = pytest.mark.skipif(
    shutil.which("gcc") is None or shutil.which("g++") is None, reason="needs gcc and g++"
)


def write_source(folder: Path, name: str, text: str, suffix: str = ".c") -> Path:
    """A controller ``folder/name/name.c`` (or ``.cpp``) of ``text``."""
    source = folder / name / f"{name}{suffix}"
    source.parent.mkdir(parents=True)
    source.write_text(text)
    return source


def run_twins(
    capfd: pytest.CaptureFixture[str], *controllers: str | Path, **options: Any
) -> tuple[list[ControllerRun], list[str]]:
    """Each controller run with the same options (a compiled one and its twin in another
    language) on the world ``world`` (the arena by default), and what each printed."""
    world = options.pop("world", None) or mazesim.load_world("arena")
    runs, outputs = [], []
    for controller in controllers:
        runs.append(run_controller(controller, world, **options))
        outputs.append(capfd.readouterr().out)
    return runs, outputs
