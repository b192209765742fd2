"""The package's layers import one way: nothing imports a layer above it, lazily or not."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import mazesim

ROOT = Path(mazesim.__file__).parent

#: Every module and package of ``mazesim``, in layers from the top down: a module imports only
#: layers below its own, never one beside it or above (``docs/design.md`` shows this table; the
#: package's ``__init__`` is the public door and is not a layer).
LAYERS: tuple[tuple[str, ...], ...] = (
    ("__main__.py",),
    ("cli",),
    ("ros2",),
    ("ros", "distributed", "hrl"),
    ("transfer", "replay"),
    ("learn",),
    ("episodes.py", "integrations", "marl", "_gym_registration.py"),
    ("envs", "batch.py", "barcode"),
    ("maze.py", "odometry.py", "_seeding.py", "plotting.py", "webots", "benchmark",
     "controllers.py", "actions.py", "_checks.py", "_pickling.py", "_display.py"),
    ("render", "_figures.py"),
    ("sensor_rays.py", "_arguments.py", "_atomic.py", "_closing.py", "_paths.py", "_sizes.py",
     "_toml.py", "_error_tree.py", "_callers.py", "_hot_paths.py", "_settings.py"),
    ("errors.py", "_core.pyi"),
)  # fmt: skip
#: The files of the package that are neither modules nor packages.
NOT_MODULES = {"__init__.py", "py.typed", "__pycache__"}


def layer_of(name: str) -> int | None:
    """The layer (0 the top) of a top-level module or package name, without ``.py``."""
    for depth, names in enumerate(LAYERS):
        if name in {entry.removesuffix(".py").removesuffix(".pyi") for entry in names}:
            return depth
    return None


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


def test_every_module_of_the_package_has_a_layer() -> None:
    present = {
        path.name
        for path in ROOT.iterdir()
        if path.name not in NOT_MODULES and not path.name.endswith(".so")
    }
    listed = {entry for names in LAYERS for entry in names}
    assert present == listed, f"unlisted: {present - listed}, gone: {listed - present}"


@pytest.mark.parametrize("entry", [entry for names in LAYERS for entry in names])
def test_no_module_imports_its_own_layer_or_above(entry: str) -> None:
    target = ROOT / entry
    files = sorted(target.rglob("*.py")) if target.is_dir() else [target]
    own = layer_of(entry.removesuffix(".py").removesuffix(".pyi"))
    assert own is not None
    wrong = []
    for path in files:
        for line, module in imported_modules(path, _package_of(path)):
            parts = module.split(".")
            if parts[0] != "mazesim" or len(parts) == 1 or parts[1] == entry.removesuffix(".py"):
                continue
            other = layer_of(parts[1])  # None: a name of the package's door, ``mazesim.X``
            if other is not None and other <= own:
                wrong.append(f"{path.relative_to(ROOT)}:{line} imports {module}")
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
