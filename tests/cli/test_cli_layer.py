"""The command line is the top layer: no module outside ``mazesim.cli`` imports it."""

from __future__ import annotations

import ast
from pathlib import Path

import mazesim

PACKAGE = Path(mazesim.__file__).resolve().parent


def _imported_modules(source: str) -> list[tuple[int, str]]:
    """Every module a source imports, at any depth (functions included), with its line."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            found += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module is not None and node.level == 0:
            found += [(node.lineno, node.module)]
            found += [(node.lineno, f"{node.module}.{alias.name}") for alias in node.names]
        elif isinstance(node, ast.Constant) and isinstance(node.value, str):
            if node.value.startswith("mazesim.cli"):  # importlib.import_module("mazesim.cli...")
                found.append((node.lineno, node.value))
    return found


def test_nothing_outside_the_cli_imports_it() -> None:
    upward = [
        f"{path.relative_to(PACKAGE.parent)}:{line}: {module}"
        for path in sorted(PACKAGE.rglob("*.py"))
        if "cli" not in path.relative_to(PACKAGE).parts[:1] and path.name != "__main__.py"
        for line, module in _imported_modules(path.read_text(encoding="utf-8"))
        if module == "mazesim.cli" or module.startswith("mazesim.cli.")
    ]
    assert upward == []


def test_the_scan_sees_a_lazy_import() -> None:
    source = "def f():\n    from mazesim.cli._args import positive_int\n"
    assert (2, "mazesim.cli._args.positive_int") in _imported_modules(source)
