"""Docstrings name modules that exist: each ``:mod:`` reference to mazesim is a file of the tree."""

from __future__ import annotations

import re
from pathlib import Path

import mazesim

ROOT = Path(mazesim.__file__).parent
MODULE_REFERENCE = re.compile(r":mod:`~?(mazesim(?:\.\w+)*)`")


def module_exists(name: str, root: Path = ROOT) -> bool:
    """Whether the dotted ``name`` (``mazesim.x.y``) is a module or package under ``root``."""
    parts = name.split(".")[1:]
    base = root.joinpath(*parts)
    return (
        not parts
        or base.with_suffix(".py").is_file()
        or base.with_suffix(".pyi").is_file()
        or (base / "__init__.py").is_file()
    )


def missing_modules(root: Path = ROOT) -> list[str]:
    """The references of the tree's files to modules that do not exist, as ``file: name``."""
    return [
        f"{path.relative_to(root)}: {name}"
        for path in sorted(root.rglob("*.py"))
        for name in MODULE_REFERENCE.findall(path.read_text(encoding="utf-8"))
        if not module_exists(name, root)
    ]


def test_docstrings_name_only_modules_that_exist() -> None:
    assert not missing_modules(), "docstrings name modules that do not exist:\n" + "\n".join(
        missing_modules()
    )


def test_the_reader_finds_a_missing_module(tmp_path: Path) -> None:
    (tmp_path / "distributed").mkdir()
    (tmp_path / "distributed" / "__init__.py").write_text(
        '"""Trainers: :mod:`mazesim.distributed.flat_q`, :mod:`mazesim.distributed`."""\n'
    )
    (tmp_path / "distributed" / "episodes.py").write_text(
        '"""See :mod:`~mazesim.distributed.episodes`."""\n'
    )
    assert missing_modules(tmp_path) == ["distributed/__init__.py: mazesim.distributed.flat_q"]
