"""Whole numbers are read as given or refused: never cut. ``int(4.5)`` is 4, numpy's
``np.asarray([4.5, nan], dtype=np.int64)`` is ``[4, -2**63]``, and both say nothing, so an
index, a count, a checkpoint event or a maze size given as a fraction, a bool or NaN was once
taken as another number. Two mechanisms make the next such argument right by construction:

- the package converts a parameter to integers only through ``mazesim._sizes`` (``index_array``,
  ``whole_array``, ``seed_array``), which refuse what is not a whole number in range; the scan
  below fails on a function that hands one of its parameters to numpy with an integer dtype;
- a parameter annotated as a list or tuple of ints (``tuple[int, int]``,
  ``Sequence[Sequence[int]]``) has its items checked before the call (``mazesim._checks``), as
  a plain ``int`` parameter always had, and so has a numpy array given for one.
"""

from __future__ import annotations

import ast
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np
import pytest

import mazesim
from mazesim._checks import checked

PACKAGE = Path(mazesim.__file__).parent
#: numpy's integer types, as a dtype argument names them.
INTEGER_TYPES = {
    "int", "int8", "int16", "int32", "int64", "intp", "uint", "uint8", "uint16", "uint32",
    "uint64", "uintp",
}  # fmt: skip
#: Calls that give their first argument's values back as an array (``np.ravel(x)``).
PASSING_THROUGH = {"ravel", "asarray", "array", "ascontiguousarray", "atleast_1d", "reshape"}


def dtype_of(types: set[str], prefixes: tuple[str, ...]) -> Callable[[ast.expr], bool]:
    """Whether a dtype argument names one of ``types`` (``np.int64``, ``int``, ``"<i8"``)."""

    def named(node: ast.expr) -> bool:
        if isinstance(node, ast.Attribute):
            return node.attr in types
        if isinstance(node, ast.Name):
            return node.id in types
        return isinstance(node, ast.Constant) and str(node.value).lstrip("<>=").startswith(prefixes)

    return named


_integer_dtype = dtype_of(INTEGER_TYPES, ("int", "uint", "i", "u"))


def conversions_of_parameters(source: str, dtype: Callable[[ast.expr], bool]) -> list[str]:
    """``function(parameter) line N`` for each numpy conversion of a parameter to a type
    ``dtype`` says yes to, in ``source``: ``np.asarray(p, dtype=np.int64)``,
    ``np.array(np.ravel(p), dtype=int)``, ``p.astype(np.intp)``."""
    found = []
    for function in ast.walk(ast.parse(source)):
        if not isinstance(function, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        arguments = function.args
        every = arguments.posonlyargs + arguments.args + arguments.kwonlyargs
        parameters = {a.arg for a in every} - {"self", "cls"}
        for node in ast.walk(function):
            if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)):
                continue
            converted = None
            if node.func.attr in ("array", "asarray", "ascontiguousarray") and node.args:
                dtypes = [k.value for k in node.keywords if k.arg == "dtype"] + node.args[1:2]
                if dtypes and dtype(dtypes[0]):
                    converted = _parameter_under(node.args[0], parameters)
            elif node.func.attr == "astype" and node.args and dtype(node.args[0]):
                converted = _parameter_under(node.func.value, parameters)
            if converted is not None:
                found.append(f"{function.name}({converted}) line {node.lineno}")
    return found


def _parameter_under(node: ast.expr, parameters: set[str]) -> str | None:
    """The parameter whose values ``node`` is (``x``, ``np.ravel(x)``, ``x.ravel()``)."""
    while True:
        if isinstance(node, ast.Name):
            return node.id if node.id in parameters else None
        if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)):
            return None
        if node.func.attr not in PASSING_THROUGH:
            return None
        node = node.args[0] if node.args else node.func.value


def integer_conversions_of_parameters(source: str) -> list[str]:
    """:func:`conversions_of_parameters` to an integer type."""
    return conversions_of_parameters(source, _integer_dtype)


def test_the_scan_finds_the_conversions_that_cut_fractions_silently() -> None:
    source = """
def start(self, envs, episodes):
    a = np.asarray(episodes, dtype=np.int64)
    b = np.ascontiguousarray(np.ravel(envs), dtype=np.intp)
    c = envs.astype(np.uint64)
    d = np.asarray(self.numbers, dtype=np.int64)  # the object's own: not a parameter
    e = np.asarray(episodes, dtype=np.float64)  # not to integers
"""
    assert integer_conversions_of_parameters(source) == [
        "start(episodes) line 3",
        "start(envs) line 4",
        "start(envs) line 5",
    ]


def conversions_in_package(dtype: Callable[[ast.expr], bool]) -> set[str]:
    """:func:`conversions_of_parameters` in every module of the package, by file."""
    return {
        f"{path.relative_to(PACKAGE)}: {where}"
        for path in sorted(PACKAGE.rglob("*.py"))
        for where in conversions_of_parameters(path.read_text(encoding="utf-8"), dtype)
    }


def test_no_function_of_the_package_hands_a_parameter_to_numpy_as_integers() -> None:
    found = conversions_in_package(_integer_dtype)
    assert not found, (
        "convert with mazesim._sizes.index_array (indices), whole_array (counts, events) or "
        f"seed_array (seeds), which refuse 1.5, NaN and out-of-range values: {sorted(found)}"
    )


WRONG = mazesim.WrongTypeError


def _nested(depth: int) -> list[object]:
    nested: list[object] = []
    for _ in range(depth):
        nested = [nested]
    return nested


@checked
def _size_and_groups(size: tuple[int, int], groups: Sequence[Sequence[int]] | None = None) -> int:
    return int(size[0]) * int(size[1]) + sum(int(i) for g in groups or () for i in g)


@pytest.mark.parametrize(
    ("size", "groups", "error", "words"),
    [
        ((4.5, 4), None, WRONG, "size refused: item 0: expected int, found a float 4.5"),
        ((4, True), None, WRONG, "size refused: item 1: expected int, found a bool"),
        ((4, 4), [[1], [2, float("nan")]], WRONG, "groups refused: item 1: item 1"),
        ((4, 4), [[1, 2**70]], mazesim.InvalidArgumentError, "fits in 64 bits"),
        ((4, 4), [list(range(20)) + [0.5]], WRONG, "item 0: item 20"),
        ((4, [4]), None, WRONG, "size refused: item 1: expected int, found a list"),
        ((4, 4), [[1, [2]]], WRONG, "groups refused: item 0: item 1: expected int, found a list"),
        ((4, 4), np.array([[1.0, 2.5]]), WRONG, "groups refused: expected ints, found a float 2.5"),
        ((4, 4), np.array([[1.0, np.nan]]), WRONG, "groups refused: expected ints, found a float"),
        (np.array([True, False]), None, WRONG, "size refused: expected ints, found an array of"),
        # A masked array's values are read whatever its mask (once an IndexError: all masked).
        (np.ma.masked_array([4.5, 4.0], mask=True), None, WRONG, "found a float 4.5 in an array"),
        # A list nested 100,000 deep is read as deep as the annotation nests, no deeper.
        ((4, 4), [_nested(100_000)], WRONG, "groups refused: item 0: item 0: expected int"),
    ],
)  # fmt: skip
def test_the_items_of_a_list_of_ints_are_checked_before_the_call(
    size: tuple[float, float], groups: list[list[float]] | None, error: type, words: str
) -> None:
    with pytest.raises(error, match=words):
        _size_and_groups(size, groups)


def test_whole_items_are_taken_as_they_are() -> None:
    assert _size_and_groups((4, 5), [[1, 2], [3]]) == 26
    assert _size_and_groups((np.int64(2), 3.0)) == 6  # a whole float is the number it says
    assert _size_and_groups(np.array([2.0, 3.0]), [np.array([1, 2])]) == 9


def test_the_entry_points_that_once_cut_numbers_refuse_them() -> None:
    from mazesim.learn.higher import HigherLevel
    from mazesim.learn.qlearning import LearningRate, batch_update
    from mazesim.marl.tasks import MazeGoalsTask
    from mazesim.transfer.control_timing import DelayedNavigator

    with pytest.raises(mazesim.InvalidArgumentError, match="visits as whole numbers of 0 or more"):
        HigherLevel([[1, 2]], visits=np.full((1, 4, 4), np.nan))
    with pytest.raises(mazesim.InvalidArgumentError, match="checkpoint_ids .* from 1 to 65535"):
        HigherLevel([[-1, 2]])
    with pytest.raises(mazesim.WrongTypeError, match="expected int, found a float 1.5"):
        HigherLevel([[1.5]])
    level = HigherLevel([[3, 1]])
    assert level.checkpoint_ids == [[1, 3]]
    with pytest.raises(mazesim.InvalidArgumentError, match="events as whole numbers, found 0.5"):
        level.states([0], [0.5])
    q, visits = np.zeros((4, 3)), np.zeros((4, 3), np.int64)
    with pytest.raises(
        mazesim.InvalidArgumentError, match="next_states as whole numbers, found nan"
    ):
        batch_update(q, visits, [0], [0], [1.0], [np.nan], [0.9], LearningRate())
    with pytest.raises(mazesim.InvalidArgumentError, match="found 1, 1 and 2"):
        batch_update(q, visits, [0], [0], [1.0], [1, 2], [0.9], LearningRate())
    assert not visits.any()  # refused before anything was written
    with pytest.raises(mazesim.WrongTypeError, match="maze_size refused: item 0"):
        MazeGoalsTask(maze_size=(4.5, 4))
    with pytest.raises(mazesim.InvalidArgumentError, match="2 to 200 cells a side"):
        MazeGoalsTask(maze_size=(4, 10**9))  # once refused at the first reset, not when made
    with pytest.raises(mazesim.InvalidArgumentError, match="delays as whole numbers from 0 to"):
        DelayedNavigator(object(), [1, 2.5])
