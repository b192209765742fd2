"""Compiled Webots controllers in the tests: the compilers they need, their sources written
into controller folders and the build cache they share."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

__all__ = ["NEEDS_COMPILERS", "write_source"]

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
