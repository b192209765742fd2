"""The package's layers import one way: nothing imports a layer above it, lazily or not."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import mazesim

ROOT = Path(mazesim.__file__).parent

#: Each lower layer and the packages it must never import (its callers, directly or not).
FORBIDDEN = {
    "transfer": ("mazesim.distributed", "mazesim.cli", "mazesim.ros", "mazesim.replay",
                 "mazesim.hrl"),
    "learn": ("mazesim.distributed", "mazesim.cli", "mazesim.ros", "mazesim.replay", "mazesim.hrl"),
    "envs": ("mazesim.distributed", "mazesim.cli", "mazesim.ros", "mazesim.learn", "mazesim.hrl"),
    "episodes.py": ("mazesim.distributed", "mazesim.cli", "mazesim.ros", "mazesim.learn",
                    "mazesim.envs", "mazesim.replay", "mazesim.hrl"),
    "batch.py": ("mazesim.distributed", "mazesim.cli", "mazesim.ros", "mazesim.learn",
                 "mazesim.envs", "mazesim.episodes", "mazesim.replay", "mazesim.hrl"),
    "maze.py": ("mazesim.distributed", "mazesim.cli", "mazesim.ros", "mazesim.learn",
                "mazesim.envs", "mazesim.episodes", "mazesim.batch", "mazesim.replay",
                "mazesim.hrl"),
    "odometry.py": ("mazesim.distributed", "mazesim.cli", "mazesim.ros", "mazesim.learn",
                    "mazesim.envs", "mazesim.episodes", "mazesim.batch", "mazesim.maze",
                    "mazesim.transfer", "mazesim.replay", "mazesim.hrl"),
    "_seeding.py": ("mazesim.distributed", "mazesim.cli", "mazesim.ros", "mazesim.learn",
                    "mazesim.envs", "mazesim.episodes", "mazesim.batch", "mazesim.maze",
                    "mazesim.replay", "mazesim.hrl"),
}  # fmt: skip


def imported_modules(path: Path, package: str) -> list[tuple[int, str]]:
    """Every module a file of ``package`` imports, anywhere in it: ``import``, ``from ...
    import`` (relative ones resolved), and ``importlib.import_module("...")`` /
    ``__import__("...")`` calls."""
    tree = ast.parse(path.read_text(), filename=str(path))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                module = ".".join([*base, *([node.module] if node.module else [])])
            else:
                module = node.module or ""
            found.append((node.lineno, module))
            found += [(node.lineno, f"{module}.{alias.name}") for alias in node.names]
        elif isinstance(node, ast.Call) and node.args:
            name = getattr(node.func, "attr", getattr(node.func, "id", ""))
            first = node.args[0]
            if name in ("import_module", "__import__") and isinstance(first, ast.Constant):
                found.append((node.lineno, str(first.value)))
    return found


def _package_of(path: Path) -> str:
    return ".".join(("mazesim", *path.relative_to(ROOT).parts[:-1]))


def _files(layer: str) -> list[Path]:
    target = ROOT / layer
    return sorted(target.rglob("*.py")) if target.is_dir() else [target]


@pytest.mark.parametrize("layer", sorted(FORBIDDEN))
def test_no_layer_imports_upwards(layer: str) -> None:
    files = _files(layer)
    assert files and all(path.exists() for path in files)
    wrong = [
        f"{path.relative_to(ROOT)}:{line} imports {module}"
        for path in files
        for line, module in imported_modules(path, _package_of(path))
        if any(module == bad or module.startswith(bad + ".") for bad in FORBIDDEN[layer])
    ]
    assert not wrong, "\n".join(wrong)


def test_the_import_reader_sees_lazy_imports(tmp_path: Path) -> None:
    sample = tmp_path / "sample.py"
    sample.write_text(
        "def f():\n    from mazesim.distributed import tasks\n"
        "    import importlib\n    importlib.import_module('mazesim.cli')\n"
        "    from ..ros import bridge\n"
    )
    modules = [module for _, module in imported_modules(sample, "mazesim.learn")]
    assert "mazesim.distributed.tasks" in modules
    assert "mazesim.cli" in modules
    assert "mazesim.ros.bridge" in modules
