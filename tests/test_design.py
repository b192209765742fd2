"""``docs/design.md``, the map of the project, agrees with the code: its core table names every
module of ``crates/mazesim-core/src`` (and ``lib.rs`` declares each), and its layer table is the
one ``tests/test_layers.py`` enforces."""

from __future__ import annotations

import re
from pathlib import Path

from test_layers import LAYERS

ROOT = Path(__file__).resolve().parents[1]
CORE = ROOT / "crates" / "mazesim-core" / "src"


def table_rows(heading: str) -> list[list[str]]:
    """The body rows of the first table under ``## heading``, each a list of its cells."""
    text = (ROOT / "docs" / "design.md").read_text(encoding="utf-8")
    section = text.split(f"## {heading}\n", 1)[1].split("\n## ", 1)[0]
    lines = [line for line in section.splitlines() if line.startswith("|")]
    return [[cell.strip() for cell in line.strip("|").split("|")] for line in lines[2:]]


def named(cell: str) -> list[str]:
    """The names a cell writes in backticks."""
    return re.findall(r"`([^`]+)`", cell)


def test_the_core_table_names_every_module_of_the_core() -> None:
    documented = [named(row[0])[0] for row in table_rows("The core crate, module by module")]
    present = {path.stem for path in CORE.iterdir() if path.name != "lib.rs"}
    assert len(documented) == len(set(documented)), "a module is listed twice"
    assert set(documented) == present, (
        f"missing from docs/design.md: {sorted(present - set(documented))}, "
        f"listed but absent: {sorted(set(documented) - present)}"
    )
    declared = set(re.findall(r"^(?:pub )?mod (\w+);", (CORE / "lib.rs").read_text(), re.M))
    assert declared == present, f"lib.rs declares {sorted(declared ^ present)} differently"


def test_the_layer_table_is_the_enforced_one() -> None:
    rows = table_rows("The Python package, layer by layer")
    assert [int(row[0]) for row in rows] == list(range(1, len(rows) + 1))
    assert [tuple(named(row[1])) for row in rows] == [tuple(layer) for layer in LAYERS]
