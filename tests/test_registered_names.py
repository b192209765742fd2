"""Every check of a user's value against a registry of names is ``errors._known_name``.

A value checked with ``value not in REGISTRY`` is hashed first: a list or a dict where a name
goes raises Python's own ``TypeError`` (unhashable) before the package's refusal, and each
hand-written refusal words the known names its own way. ``_known_name`` refuses any value that
is not one of the names with one :class:`~mazesim.errors.UnknownNameError`, listing them. This
test reads the package's source and finds any membership check of a value against a registry
(a constant of upper-case name, a call of ``..._names()``, or a literal tuple of names) whose
failure raises, which must go through ``_known_name`` instead.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import mazesim
from mazesim.errors import UnknownNameError, _known_name

PACKAGE = Path(mazesim.__file__).parent

#: Checks against a set of names that refuse something else than a user's name of a registered
#: thing (file and check), each with what it refuses instead.
NOT_A_REGISTRY = {
    # A field of a file read back is refused as that file's format error (file, field, value).
    "learn/schema.py: not isinstance(value, str) or value not in self.choices": "a policy file's",
    "replay/run_fields.py: choices is not None and value not in choices": "a run file's field",
    # argparse turns an ArgumentTypeError into its usage message.
    "cli/_args.py: not chosen or any((name not in names for name in chosen))": "argparse's",
    # A bad action is an InvalidActionError, whatever its code.
    "actions.py: key not in ACTIONS": "an action code, refused as an InvalidActionError",
    # A world file where a built-in world's name goes: an unknown name is refused before.
    "cli/worlds.py: name not in mazesim.builtin_world_names()": "a world file to export",
    # A module a world file's template imports: a WorldFormatError at its line.
    "webots/proto/templates.py: module not in JAVASCRIPT_MODULES": "a template's import",
    # A file name's suffix, refused naming the file as the option took it.
    "replay/video.py: suffix not in VIDEO_FORMATS": "a video file's name",
    "cli/replay.py: suffix not in ('.html', '.htm', '.mp4', '.gif')": "-o FILE's name",
    # The names of a multi-robot task's keyword arguments, refused as the argument checks do.
    "marl/entry_points.py: name not in names": "an argument's name, an unknown keyword",
}


def _is_registry(node: ast.expr) -> bool:
    """Whether ``node`` is a registry of names: ``NAMES``, ``module.NAMES``, ``self.names``,
    ``..._names()`` or a literal tuple, list or set of at least two strings."""
    if isinstance(node, ast.Name | ast.Attribute):
        name = node.id if isinstance(node, ast.Name) else node.attr
        return name.lstrip("_").isupper() or name in ("names", "choices", "known")
    if isinstance(node, ast.Call):
        called = node.func
        name = called.id if isinstance(called, ast.Name) else getattr(called, "attr", "")
        return name.endswith(("_names", "_ids"))
    if isinstance(node, ast.Tuple | ast.List | ast.Set):
        strings = [e for e in node.elts if isinstance(e, ast.Constant) and isinstance(e.value, str)]
        return len(strings) >= 2 and len(strings) == len(node.elts)
    return False


def _registry_checks(tree: ast.AST) -> list[tuple[int, str]]:
    """The ``if value not in REGISTRY: raise ...`` of ``tree``: line and test."""
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.If):
            continue
        raises = any(isinstance(n, ast.Raise) for stmt in node.body for n in ast.walk(stmt))
        for compare in ast.walk(node.test):
            if not (raises and isinstance(compare, ast.Compare)):
                continue
            checked = isinstance(compare.left, ast.Name | ast.Attribute | ast.Subscript)
            for op, right in zip(compare.ops, compare.comparators):
                if checked and isinstance(op, ast.NotIn) and _is_registry(right):
                    found.append((node.lineno, ast.unparse(node.test)))
    return found


def test_no_check_of_a_value_against_a_registry_is_written_by_hand() -> None:
    checks = [
        (f"{path.relative_to(PACKAGE).as_posix()}: {test}", line)
        for path in sorted(PACKAGE.rglob("*.py"))
        for line, test in _registry_checks(ast.parse(path.read_text(), str(path)))
    ]
    hand_written = [
        f"{check} (line {line})" for check, line in checks if check not in NOT_A_REGISTRY
    ]
    assert not hand_written, "\n".join(hand_written)
    assert set(NOT_A_REGISTRY) <= {check for check, _ in checks}, "an exception no longer there"


def test_the_scan_finds_each_shape_of_a_registry_check() -> None:
    # What the scan must find (a hand-written check) and what it must leave (_known_name, a
    # key of a file looked up, a dtype's kind).
    found = """
if mode not in MODES:
    raise InvalidArgumentError(mode)
if self.mode not in ("lockstep", "free"):
    raise InvalidArgumentError(mode)
if name not in mazesim.builtin_world_names():
    raise MazesimIOError(name)
if key not in self.names:
    raise ValueError(key)
"""
    left = """
_known_name(mode, "mode", MODES)
if "world" in grid and "maze_size" in grid:
    raise InvalidArgumentError(grid)
if array.dtype.kind not in "fiu":
    raise InvalidArgumentError(array)
if mode not in MODES:
    mode = "free"
"""
    assert [line for line, _ in _registry_checks(ast.parse(found))] == [2, 4, 6, 8]
    assert _registry_checks(ast.parse(left)) == []


@pytest.mark.parametrize("value", [["free"], {"free": 1}, None, 3, b"free", "Free"])
def test_a_value_of_any_type_for_a_registered_name_is_refused_listing_the_names(
    value: object,
) -> None:
    with pytest.raises(UnknownNameError) as refused:
        _known_name(value, "mode", ("lockstep", "free"))
    assert refused.value.available == ["lockstep", "free"]
