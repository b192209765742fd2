"""The README's layout section matches the tree: every path it names exists, and every module and
package of ``python/mazesim`` is named in it."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "python" / "mazesim"
#: Files of the package that are not modules a reader looks for.
#: Where the descriptions start: a line indented this far continues the one above.
DESCRIPTION_COLUMN = 20
UNLISTED = {"__init__.py", "__main__.py", "py.typed", "_core.pyi", "__pycache__"}


def layout_block() -> str:
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = text.split("## Layout\n", 1)[1].split("\n## ", 1)[0]
    found = re.search(r"```text\n(.*?)```", section, flags=re.S)
    assert found, "the layout section has no text block"
    return found[1]


def named_paths() -> list[Path]:
    """The paths the block names, each resolved against its parent folder."""
    paths = []
    parent = ROOT
    for line in layout_block().splitlines():
        indent = len(line) - len(line.lstrip())
        if indent >= DESCRIPTION_COLUMN:
            continue  # a description's second line
        names = line.strip().split("  ")[0]
        for name in (n.strip() for n in names.split(",")):
            if not name or " " in name:
                continue
            base = ROOT if indent == 0 else PACKAGE
            paths.append(base / name)
        if indent == 0 and names.rstrip("/").endswith("python/mazesim"):
            parent = PACKAGE
    assert parent == PACKAGE, "the block does not open python/mazesim/"
    return paths


def test_every_path_of_the_layout_exists() -> None:
    missing = [str(p.relative_to(ROOT)) for p in named_paths() if not p.exists()]
    assert not missing, f"the README's layout names paths that do not exist: {missing}"


def test_every_module_of_the_package_is_in_the_layout() -> None:
    named = {p for p in named_paths() if p.parent == PACKAGE}
    present = {
        p
        for p in PACKAGE.iterdir()
        if p.name not in UNLISTED and not p.name.startswith("_core.") and not p.name.endswith(".so")
    }
    unlisted = sorted(p.name for p in present - named)
    assert not unlisted, f"modules of python/mazesim missing from the README's layout: {unlisted}"
