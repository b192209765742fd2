"""Python 3.9, the oldest Python pyproject's ``requires-python`` promises, reads every module.

A type union written ``A | B`` outside an annotation (``isinstance(x, int | float)``, an alias
``Radii = Sequence[float | None]``) and names ``typing`` gained later (``TypeAlias``,
``is_typeddict``) run on the Python the suite runs on and fail on 3.9 when the line runs: the
Webots import stopped with "unsupported operand type(s) for |" there. These checks read the
source, so they hold whatever Python runs them; ``tests/test_wheel.py`` also imports every module
with Debian 11's own Python 3.9 where its chroot is made.
"""

from __future__ import annotations

import ast
import builtins
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: The source a user's Python runs: the package and the examples.
SOURCES = sorted([*(ROOT / "python" / "mazesim").rglob("*.py"), *(ROOT / "examples").rglob("*.py")])
#: Names of ``typing`` that Python 3.9's lacks (added in 3.10 to 3.13).
NEWER_TYPING = {
    "TypeAlias", "ParamSpec", "Concatenate", "TypeGuard", "is_typeddict", "Self", "Never",
    "LiteralString", "Required", "NotRequired", "Unpack", "TypeVarTuple", "assert_never",
    "reveal_type", "dataclass_transform", "assert_type", "get_overloads", "clear_overloads",
    "override", "TypeIs", "ReadOnly", "NoDefault",
}  # fmt: skip
_BUILTIN_TYPES = {name for name in dir(builtins) if isinstance(getattr(builtins, name), type)}


def oldest_python() -> tuple[int, int]:
    """The oldest Python pyproject promises (``requires-python = ">=3.9"`` -> (3, 9))."""
    text = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    found = re.search(r'^requires-python\s*=\s*">=\s*(\d+)\.(\d+)', text, re.MULTILINE)
    assert found is not None, 'pyproject.toml: requires-python = ">=3.N" expected'
    return int(found.group(1)), int(found.group(2))


def _is_type(node: ast.expr) -> bool:
    """Whether ``node`` reads as a type: None, a builtin type, a CamelCase class, numpy's
    ``np.bool_``, a subscripted type, or a union of them."""
    if isinstance(node, ast.Constant):
        return node.value is None
    if isinstance(node, ast.Name):
        return node.id in _BUILTIN_TYPES or (node.id[:1].isupper() and not node.id.isupper())
    if isinstance(node, ast.Attribute):
        # A flag's member (SampleState.Any, re.IGNORECASE) is no type.
        camel = node.attr[:1].isupper() and not node.attr.isupper() and node.attr != "Any"
        return camel or node.attr in ("bool_", "ndarray", "integer", "floating", "generic")
    if isinstance(node, ast.Subscript):
        return _is_type(node.value)
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.BitOr):
        return _is_type(node.left) or _is_type(node.right)
    return False


class _RunTimeUnions(ast.NodeVisitor):
    """Collects ``A | B`` of types in code that runs (annotations, which ``from __future__
    import annotations`` keeps as text, are not visited)."""

    def __init__(self) -> None:
        self.found: list[tuple[int, str]] = []

    def visit_AnnAssign(self, node: ast.AnnAssign) -> None:
        if node.value is not None:
            self.visit(node.value)

    def visit_FunctionDef(self, node: ast.FunctionDef | ast.AsyncFunctionDef) -> None:
        defaults = [*node.args.defaults, *(d for d in node.args.kw_defaults if d is not None)]
        for part in [*node.decorator_list, *defaults, *node.body]:
            self.visit(part)

    visit_AsyncFunctionDef = visit_FunctionDef

    def visit_BinOp(self, node: ast.BinOp) -> None:
        if isinstance(node.op, ast.BitOr) and _is_type(node.left) and _is_type(node.right):
            self.found.append((node.lineno, ast.unparse(node)))
            return
        self.generic_visit(node)


def _name(path: Path) -> str:
    return str(path.relative_to(ROOT))


def test_the_oldest_python_is_the_one_the_readme_and_the_classifiers_state() -> None:
    major, minor = oldest_python()
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert f"Python {major}.{minor}+" in readme
    pyproject = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    assert f'"Programming Language :: Python :: {major}.{minor}"' in pyproject


@pytest.mark.parametrize("path", SOURCES, ids=_name)
def test_every_module_is_written_in_the_oldest_pythons_grammar(path: Path) -> None:
    ast.parse(path.read_text(encoding="utf-8"), str(path), feature_version=oldest_python())


def test_no_type_union_is_written_with_a_bar_where_it_runs() -> None:
    found = []
    for path in SOURCES:
        visitor = _RunTimeUnions()
        visitor.visit(ast.parse(path.read_text(encoding="utf-8")))
        found += [f"{_name(path)}:{line}: {text}" for line, text in visitor.found]
    assert not found, "Python 3.9 has no `|` of types; write Union[...] or a tuple:\n" + "\n".join(
        found
    )


def test_no_name_of_typing_newer_than_the_oldest_python_is_used() -> None:
    found = []
    for path in SOURCES:
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names: list[str] = []
            if isinstance(node, ast.ImportFrom) and node.module == "typing":
                names = [alias.name for alias in node.names]
            elif (
                isinstance(node, ast.Attribute)
                and isinstance(node.value, ast.Name)
                and node.value.id == "typing"
            ):
                names = [node.attr]
            found += [
                f"{_name(path)}:{node.lineno}: typing.{n}" for n in names if n in NEWER_TYPING
            ]
    assert not found, "Python 3.9's typing lacks these:\n" + "\n".join(found)


@pytest.mark.parametrize(
    ("source", "caught"),
    [
        ("ok = isinstance(x, int | float)", True),
        ("Radii = Sequence[float | None] | Callable[[], None]", True),
        ("ok = isinstance(x, bool | np.bool_)", True),
        ("def f(x: int | None = None) -> str | None: ...", False),
        ("names = ROBOT_TYPES | {'Supervisor'}", False),
        ("flags = re.IGNORECASE | re.MULTILINE", False),
        ("mask = SampleState.Any | ViewState.Any", False),
        ("value: int | None = None", False),
    ],
)
def test_the_bar_check_tells_a_union_of_types_from_other_bars(source: str, caught: bool) -> None:
    visitor = _RunTimeUnions()
    visitor.visit(ast.parse(source))
    assert bool(visitor.found) is caught


def _core_dependencies(python: str) -> set[str]:
    """The distributions ``pip install mazesim`` brings on Python ``python`` (``"3.9"``)."""
    import tomllib
    from packaging.requirements import Requirement

    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    needed = [Requirement(text) for text in project["dependencies"]]
    return {
        each.name
        for each in needed
        if each.marker is None or each.marker.evaluate({"python_version": python})
    }


def test_every_python_without_tomllib_gets_the_toml_reader_with_mazesim() -> None:
    """``mazesim webots run`` and ``mazesim barcode-study`` read TOML (``mazesim._toml``): on
    Python 3.9 and 3.10 they stopped with "needs 'tomli': pip install tomli" after ``pip
    install mazesim`` or ``make demo``."""
    major, oldest = oldest_python()
    for minor in range(oldest, 14):
        has_tomllib = (major, minor) >= (3, 11)
        assert ("tomli" in _core_dependencies(f"{major}.{minor}")) is not has_tomllib, minor
    makefile = (ROOT / "Makefile").read_text(encoding="utf-8")
    assert "PY_BEFORE_311 := \"tomli; python_version < '3.11'\"" in makefile
    assert "$(PY_PACKAGES) $(PY_BEFORE_311)" in makefile
