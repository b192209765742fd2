"""``docs/design.md``, the map of the project, agrees with the code: its core table names every
module of ``crates/mazesim-core/src`` (and ``lib.rs`` declares each), its layer table is the
one ``tests/test_layers.py`` enforces, and every module, function, class or constant of the
package it names in backticks (``learn.tables.load_policy``) and every path of the core
(``navigator::door``, ``Batch::run_steps``) exists."""

from __future__ import annotations

import re
from pathlib import Path

from test_layers import LAYERS
from test_module_references import resolves

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


def page_names() -> list[str]:
    """The names the page writes in backticks (calls' ``()`` dropped)."""
    text = (ROOT / "docs" / "design.md").read_text(encoding="utf-8")
    return sorted({name.removesuffix("()") for name in re.findall(r"`([^`\s]+)`", text)})


def package_name(name: str) -> str | None:
    """``name`` written out from ``mazesim.`` when it starts with a module or package of it
    (``learn.tables.load_policy``, ``batch.py``), else None (a file of another kind, a folder of
    the package that holds no Python such as ``webots.capi``, a word)."""
    package = ROOT / "python" / "mazesim"
    dotted = name.removesuffix(".py")
    first = dotted.split(".")[0]
    if not first or re.search(r"\.(rs|md|toml|wbt|txt)$", name):
        return None
    if (package / dotted.replace(".", "/")).is_dir() and not list(
        (package / dotted.replace(".", "/")).glob("*.py")
    ):
        return None
    if (package / f"{first}.py").is_file() or (package / first / "__init__.py").is_file():
        return "mazesim." + dotted
    return None


def test_the_python_names_of_the_page_exist() -> None:
    written = {name: package_name(name) for name in page_names()}
    missing = [name for name, full in written.items() if full and not resolves(full)]
    assert not missing, f"docs/design.md names what the package does not hold: {missing}"
    assert "mazesim.learn.core_episodes.StretchReplay" in written.values()


def test_the_core_paths_of_the_page_exist() -> None:
    paths = [name for name in page_names() if re.fullmatch(r"\w+(::\w+)+", name)]
    missing = [
        path
        for path in paths
        if not (CORE / path.replace("::", "/")).with_suffix(".rs").exists()
        and not (CORE / path.replace("::", "/") / "mod.rs").exists()
        and not resolves_in_core(path)
    ]
    assert paths and not missing, f"docs/design.md names core modules that do not exist: {missing}"


def resolves_in_core(path: str) -> bool:
    """Whether ``Type::item`` (``Rewards::NAVIGATOR``, ``Batch::run_steps``) is an item of an
    ``impl`` of that type in some file of the core."""
    owner, item = path.rsplit("::", 1)
    pattern = re.compile(rf"\bimpl(?:<[^>]*>)? {owner}\b.*?\b(?:const|fn) {item}\b", re.S)
    return any(pattern.search(file.read_text()) for file in CORE.rglob("*.rs"))
