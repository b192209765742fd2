"""The one argument check at mazesim's public surface.

What is public: a module of the package whose dotted name has no part starting with ``_``, and in
it each function and class its ``__all__`` names (defined there, not re-exported), with each
class's constructor and its methods whose names do not start with ``_``. ``mazesim._core`` checks
its own arguments in the binding; private modules (``mazesim._paths``, ``mazesim.cli._args``) and
private names are helpers the package calls with values it made itself.

:func:`install` (called once by ``mazesim/__init__.py``) adds an import hook: when a public module
has been executed, every public function and method in it is replaced by a wrapper that checks
each argument against the parameter's type annotation before the call, through one conversion
helper (:func:`refusal`): the type (``int``, ``float``, ``str``, paths, sequences, mappings,
arrays, callables, the package's own classes, ``Literal`` choices, unions, ``None``) and the range
of integers (what a 64-bit integer holds). The length of a sized value (at most
:data:`MOST_ITEMS`, read from ``len()`` or ``.shape`` before anything is converted) is checked
before the call, and so is a text argument (``str`` or ``bytes``) against its annotation, which
``float()`` and ``int()`` would read as a number (``Robot.step("64")``); the rest when the call
fails with a built-in exception (``TypeError``, ``ValueError``, ``AttributeError``,
``RecursionError``...; a ``MemoryError`` is no argument of the wrong kind, and is said to be
the memory the input took), so that valid calls pay nothing for it and the function's own,
more precise messages are kept: an argument that does not fit then raises
:class:`~mazesim.errors.InvalidArgumentError` ("expected X, found Y") naming the function and the
parameter, and so does a call with missing or unknown arguments. A failure whose arguments all fit
their annotations (a bound the annotations cannot say, or a bug), and any other exception from
below the surface, is put into the package's error tree by :mod:`mazesim._error_tree`.
A new public function is checked without any code of its own. The check is made once per call
from outside: calls a checked function makes to other public functions of the package are not
checked again, and the compiled core's per-step work is not touched. The user's own code that
the package runs from inside a call (a Webots controller) calls from outside again:
:func:`mazesim._callers.users_code` says so.

Annotations the check cannot read (names imported for type checkers only, type variables,
protocols that are not runtime-checkable) are not checked; everything the check lets through
behaves exactly as before.
"""

from __future__ import annotations

import collections.abc as abc
import functools
import importlib.abc
import importlib.machinery
import inspect
import math
import os
import sys
import types
import typing
from collections.abc import Callable
from pathlib import PurePath
from typing import Any

import numpy as np

from mazesim._callers import STATE
from mazesim._error_tree import in_the_tree
from mazesim._hot_paths import is_checked, mark_checked
from mazesim._sizes import MOST_ENVS, size_of
from mazesim.errors import (
    InvalidArgumentError,
    MaybeInfinite,
    MazesimError,
    WrongTypeError,
    _a_type,
    _closest_name,
    _shortened,
    _shown,
)

__all__ = [
    "MOST_ARRAY_VALUES",
    "MOST_DIMENSIONS",
    "MOST_ITEMS",
    "SAMPLED_ITEMS",
    "annotations_of",
    "answers_non_finite",
    "checked",
    "guard_module",
    "install",
    "is_public_module",
    "public_names",
    "refusal",
    "refusal_error",
    "ThenLoader",
    "TypeRefusal",
]

#: Most items a sequence or mapping argument may hold: the package's bound on what it takes from
#: callers (``mazesim._sizes.MOST_ENVS``).
MOST_ITEMS = MOST_ENVS
#: Most values an array argument may hold (an image of 8K by 8K pixels holds 2**26 x 3).
MOST_ARRAY_VALUES = 1 << 28
#: Items of a sequence argument whose types are checked (the first ones: a check per call must not
#: read a long sequence).
SAMPLED_ITEMS = 8
#: Items of a list or tuple of ints (``tuple[int, int]``, ``Sequence[Sequence[int]]``) read
#: before the call, where ``int()`` would read 4.5 as 4 or True as 1 without a word.
CHECKED_INT_ITEMS = 1024
#: The integers an argument may be: what a signed or unsigned 64-bit integer holds.
SMALLEST_INT, LARGEST_INT = -(1 << 63), (1 << 64) - 1

_NUMBERS = (int, float, np.integer, np.floating)
#: The origins of union annotations (``X | Y`` is a ``types.UnionType`` from Python 3.10 on).
_UNIONS = (typing.Union, getattr(types, "UnionType", typing.Union))
#: The built-in containers; one given where a plain value (a number, a text) is annotated is
#: refused before the call (numpy's ``SeedSequence`` recurses into a list given for a seed in
#: C, without bound).
_CONTAINERS = (list, tuple, set, frozenset, dict)
#: numpy's protocols of array-likes (the parts of ``numpy.typing.ArrayLike``).
_ARRAY_PROTOCOLS = ("_NestedSequence", "_SupportsArray")
_ARRAY_LIKE = (np.ndarray, np.generic, abc.Sequence, int, float, complex, bool)


def _untestable_protocol(hint: Any) -> bool:
    """Whether ``hint`` is a protocol that ``isinstance`` cannot test (not runtime-checkable:
    ``isinstance`` raises TypeError)."""
    return bool(getattr(hint, "_is_protocol", False)) and not getattr(
        hint, "_is_runtime_protocol", False
    )


def _is_typeddict(hint: Any) -> bool:
    """Whether ``hint`` is a TypedDict class (``typing.is_typeddict``, which Python 3.9 lacks)."""
    return isinstance(hint, type) and issubclass(hint, dict) and hasattr(hint, "__total__")


def is_public_module(name: str) -> bool:
    """Whether the module ``name`` is part of the public surface."""
    parts = name.split(".")
    return parts[0] == "mazesim" and not any(p.startswith("_") for p in parts[1:])


class TypeRefusal(str):
    """A refusal (:func:`refusal`'s text) of a value whose type the annotation does not take, as
    opposed to a value of the right type out of its range: raised as
    :class:`~mazesim.errors.WrongTypeError`, which is also a ``TypeError``."""


def refusal_error(reason: str) -> type[InvalidArgumentError]:
    """The class a refusal is raised as: :class:`~mazesim.errors.WrongTypeError` for a value of
    the wrong type, :class:`~mazesim.errors.InvalidArgumentError` for one out of range."""
    return WrongTypeError if isinstance(reason, TypeRefusal) else InvalidArgumentError


def _describe(value: Any) -> str:
    """A short description of a value for a message: its type with its article (as the
    binding's refusals name it, :func:`~mazesim.errors._a_type`), and its repr if short."""
    try:
        text = repr(value) if isinstance(value, (int, float, str, bytes)) else ""
    except Exception:  # noqa: BLE001 - a repr that fails is not described
        text = ""
    return f"{_a_type(value)} {text}" if text and len(text) <= 60 else _a_type(value)


def _hint_name(hint: Any) -> str:
    if isinstance(hint, type):
        return hint.__name__
    return str(hint).replace("typing.", "").replace("collections.abc.", "")


#: The characters of one argument's value a catch-all message shows (:meth:`_Parameters.given`).
GIVEN_CHARACTERS = 60


def _expected(hint: Any) -> str:
    """An annotation as a message says what it expects: "an array of numbers" for numpy's
    ``ArrayLike`` (whose union is a paragraph), "any value" for none, else its name."""
    if hint is Any:
        return "any value"
    if _is_array_like(typing.get_args(hint)):
        return "an array of numbers"
    if typing.get_origin(hint) is np.ndarray:
        kinds = [typing.get_args(a) for a in typing.get_args(hint)[1:]]
        return f"a numpy array of {kinds[0][0].__name__}" if kinds and kinds[0] else "a numpy array"
    return _shortened(_hint_name(hint), GIVEN_CHARACTERS)


def refusal(value: Any, hint: Any) -> str | None:
    """Why ``value`` is not a valid value of the annotation ``hint`` ("expected X, found Y"), or
    None when it is (or when ``hint`` says nothing the check can test)."""
    try:
        return _refusal(value, hint)
    except Exception:  # noqa: BLE001 - a value whose inspection fails is refused, not raised
        return TypeRefusal(f"expected {_hint_name(hint)}, found {_describe(value)}")


def _too_many(value: Any, most: int = MOST_ITEMS) -> str | None:
    size = size_of(value)
    if size is not None and size > most:
        return f"expected at most {most} items, found {size} ({_a_type(value)})"
    return None


def _refusal(value: Any, hint: Any) -> str | None:  # noqa: C901, PLR0911, PLR0912 - one table
    if hint is Any or hint is object or isinstance(hint, (str, typing.TypeVar)):
        return None
    if hint is None or hint is type(None):
        return None if value is None else TypeRefusal(f"expected None, found {_describe(value)}")
    origin = typing.get_origin(hint)
    args = typing.get_args(hint)
    if origin in _UNIONS:
        if _is_array_like(args) and value is not None:
            return _array_like_refusal(value, args)
        reasons = [_refusal(value, arg) for arg in args]
        if any(reason is None for reason in reasons):
            return None
        of_value = [r for r in reasons if not isinstance(r, TypeRefusal)]
        if of_value:
            return of_value[0]  # the value is of a member's type, out of its range
        return TypeRefusal(f"expected {_hint_name(hint)}, found {_describe(value)}")
    if origin is typing.Annotated:
        return _refusal(value, args[0])
    if origin is typing.Literal:
        if isinstance(value, (str, int, float, bool, bytes, type(None))) and any(
            value == a and type(value) is type(a) for a in args
        ):
            return None
        reason = f"expected one of {', '.join(repr(a) for a in args)}, found {_describe(value)}"
        return reason if any(type(value) is type(a) for a in args) else TypeRefusal(reason)
    if origin is type:
        return (
            None
            if isinstance(value, type)
            else TypeRefusal(f"expected a class, found {_describe(value)}")
        )
    if origin is abc.Callable or hint is abc.Callable or hint is typing.Callable:
        return (
            None
            if callable(value)
            else TypeRefusal(f"expected a callable, found {_describe(value)}")
        )
    if origin is not None:
        return _container_refusal(value, hint, origin, args)
    if _is_typeddict(hint):  # isinstance refuses a TypedDict: it is read as a mapping
        return _class_refusal(value, abc.Mapping)
    if not isinstance(hint, type):
        return None  # a NewType, a ParamSpec...: not checked
    return _class_refusal(value, hint)


#: What to pass instead, by the class a parameter takes and the class of the value given (each
#: as ``module.qualname``, so that no such package is imported to say it).
_INSTEAD = {
    ("gymnasium.vector.vector_env.VectorEnv", "gymnasium.core.Env"): (
        "make a vector env of it with gymnasium.make_vec(id, num_envs=N)"
    ),
}


def _instead(value: Any, hint: type) -> str:
    """What to pass instead of ``value`` where ``hint`` is taken, as a clause (": make ..."), or
    "" when the table knows no better."""
    wanted = f"{hint.__module__}.{hint.__qualname__}"
    for given in type(value).__mro__:
        tip = _INSTEAD.get((wanted, f"{given.__module__}.{given.__qualname__}"))
        if tip is not None:
            return f": {tip}"
    return ""


def _class_refusal(value: Any, hint: type) -> str | None:  # noqa: PLR0911 - one table
    if hint is bool:
        ok = isinstance(value, (bool, np.bool_))
    elif hint is int:
        if isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_)):
            if not SMALLEST_INT <= int(value) <= LARGEST_INT:
                return f"expected an integer that fits in 64 bits, found {_describe(value)}"
            return None
        ok = False  # True and False are ints to Python, not counts or indices to mazesim
    elif hint is float or hint is complex:
        # True and False are ints to Python, not speeds or milliseconds to mazesim.
        ok = isinstance(value, (*_NUMBERS, complex if hint is complex else float))
        ok = ok and not isinstance(value, (bool, np.bool_))
        if ok and isinstance(value, int) and not SMALLEST_INT <= value <= LARGEST_INT:
            return f"expected a number, found an integer of {value.bit_length()} bits"
    elif hint is str:
        ok = isinstance(value, str)
    elif hint is bytes:
        ok = isinstance(value, (bytes, bytearray, memoryview))
    elif issubclass(hint, (PurePath, os.PathLike)):
        return _path_refusal(value)
    elif hint is np.ndarray:
        if not isinstance(value, _ARRAY_LIKE) or isinstance(value, (str, bytes)):
            return TypeRefusal(f"expected an array, found {_describe(value)}")
        return _too_many(value, MOST_ARRAY_VALUES) or _numbers_refusal(value)
    elif hint in _CONTAINERS or (hint.__module__ == "collections.abc"):
        return _container_refusal(value, hint, hint, ())
    elif getattr(hint, "_is_protocol", False):
        if _untestable_protocol(hint):
            return None
        ok = isinstance(value, hint)
    else:
        ok = isinstance(value, hint)
    if ok:
        return None
    return TypeRefusal(
        f"expected {_hint_name(hint)}, found {_describe(value)}{_instead(value, hint)}"
    )


def _container_refusal(value: Any, hint: Any, origin: Any, args: tuple[Any, ...]) -> str | None:
    if origin is np.ndarray:
        return _refusal(value, np.ndarray)
    if not isinstance(origin, type):
        return None
    if origin in (dict, abc.Mapping, abc.MutableMapping):
        if not isinstance(value, abc.Mapping):
            return TypeRefusal(f"expected a mapping, found {_describe(value)}")
        return _too_many(value)
    if origin in (tuple, list, abc.Sequence, abc.MutableSequence, set, frozenset, abc.Set,
                  abc.Collection, abc.Iterable, abc.Iterator, abc.Sized):  # fmt: skip
        if isinstance(value, (str, bytes)) and not _takes_text(args):
            return TypeRefusal(f"expected {_hint_name(hint)}, found {_describe(value)}")
        if origin is abc.Iterator:
            return (
                None
                if isinstance(value, abc.Iterator)
                else TypeRefusal(f"expected an iterator, found {_describe(value)}")
            )
        if not isinstance(value, abc.Iterable):
            return TypeRefusal(f"expected {_hint_name(hint)}, found {_describe(value)}")
        too_many = _too_many(value)
        if too_many is not None:
            return too_many
        if origin is tuple and args and args[-1] is not Ellipsis and isinstance(value, abc.Sized):
            if len(value) != len(args):
                return f"expected {len(args)} items ({_hint_name(hint)}), found {len(value)}"
            for item, arg in zip(value, args):  # noqa: B905 - equal lengths (above); no strict= in 3.9
                reason = _refusal(item, arg)
                if reason is not None:
                    return reason
        elif len(args) == 1 or (origin is tuple and len(args) == 2 and args[1] is Ellipsis):
            return _items_refusal(value, args[0])
        return None
    if issubclass(origin, os.PathLike):
        return _path_refusal(value)
    elif getattr(origin, "_is_protocol", False):
        return None  # numpy's _NestedSequence, _SupportsArray...: structural, not checked
    else:
        ok = isinstance(value, origin)
    return None if ok else TypeRefusal(f"expected {_hint_name(hint)}, found {_describe(value)}")


def _path_refusal(value: Any) -> str | None:
    """Why ``value`` is not a path: not text or a path object, or text with a NUL character
    (which no file system takes)."""
    if not isinstance(value, (str, os.PathLike)):
        return TypeRefusal(f"expected a path, found {_describe(value)}")
    if not isinstance(os.fspath(value), str):  # as the compiled core's paths (_paths.fs_path)
        return TypeRefusal(f"expected a path, found {_describe(value)} whose path is bytes")
    if "\x00" in str(os.fspath(value)):
        return "expected a path, found one with a NUL character"
    return None


def _is_array_like(args: tuple[Any, ...]) -> bool:
    """Whether a union's members are numpy's ``ArrayLike`` (or one of its parts with None)."""
    names = {getattr(typing.get_origin(a) or a, "__name__", "") for a in args}
    return bool(names & set(_ARRAY_PROTOCOLS))


def _array_like_refusal(value: Any, args: tuple[Any, ...]) -> str | None:
    """Why ``value`` is not an array of numbers for an ``ArrayLike`` (with None if the union
    takes it): text, a mapping, a value of another kind, too deep, or not numbers."""
    if isinstance(value, (str, bytes, abc.Mapping)) or not isinstance(value, _ARRAY_LIKE):
        if hasattr(value, "__array__") or hasattr(value, "__array_interface__"):
            return _too_many(value, MOST_ARRAY_VALUES) or _numbers_refusal(value)
        return TypeRefusal(f"expected an array of numbers, found {_describe(value)}")
    return _too_many(value, MOST_ARRAY_VALUES) or _numbers_refusal(value)


#: Dimensions an array argument may have (numpy's own limit is 64).
MOST_DIMENSIONS = 32


def _numbers_refusal(value: Any) -> str | None:
    """Why ``value`` (within its length bound) is not an array of real numbers or booleans:
    ragged, nested too deep, or holding text or objects. Read only after a call failed."""
    if isinstance(value, np.ndarray):
        array = value
    else:
        try:
            array = np.asarray(value)
        except (ValueError, TypeError, RecursionError, OverflowError) as error:
            found = _a_type(value)
            return f"expected an array of numbers, found {found} numpy cannot read ({error})"
    if array.ndim > MOST_DIMENSIONS:
        return f"expected an array of at most {MOST_DIMENSIONS} dimensions, found {array.ndim}"
    if array.dtype.kind not in "biuf":
        return TypeRefusal(f"expected an array of numbers, found an array of dtype {array.dtype}")
    return None


def _bound_of(hint: Any) -> int | None:
    """The length bound of an annotation's values, or None for one of no length (a sequence or
    mapping: :data:`MOST_ITEMS`; an array: :data:`MOST_ARRAY_VALUES`)."""
    origin = typing.get_origin(hint)
    if origin in _UNIONS or origin is typing.Annotated:
        bounds = [b for arg in typing.get_args(hint) if (b := _bound_of(arg)) is not None]
        return max(bounds) if bounds else None
    kind = origin if origin is not None else hint
    if kind is np.ndarray or getattr(kind, "__name__", "") in _ARRAY_PROTOCOLS:
        return MOST_ARRAY_VALUES
    if kind in _CONTAINERS or (isinstance(kind, type) and kind.__module__ == "collections.abc"):
        return None if kind is abc.Callable else MOST_ITEMS
    return None


def _items_refusal(value: Any, hint: Any) -> str | None:
    """Why the first :data:`SAMPLED_ITEMS` items of a sequence are not values of ``hint``."""
    if not isinstance(value, (abc.Sequence, np.ndarray)) or isinstance(value, (str, bytes)):
        return None  # an iterator is not read ahead; text is a sequence of itself
    for index in range(min(len(value), SAMPLED_ITEMS)):
        reason = _refusal(value[index], hint)
        if reason is not None:
            return type(reason)(f"item {index}: {reason}")
    return None


def _takes_text(args: tuple[Any, ...]) -> bool:
    """Whether a container's item annotations take strings (a ``Sequence[str]`` takes "ab")."""
    return any(a is str or a is Any for a in args)


#: What a function's code raises when an argument is not what it expects (its own errors aside):
#: the arguments are then checked against the annotations, and a refusal is raised instead.
_ARGUMENT_FAILURES = (
    TypeError,
    ValueError,
    AttributeError,
    IndexError,
    KeyError,
    OverflowError,
    RecursionError,
)

#: Arguments checked before every call: Python's ``float()``, ``int()`` and numpy read ``"64"`` or
#: ``b"64"`` as a number, so a call given text for a number would not fail and be checked after.
_TEXT = (str, bytes, bytearray)
#: Texts that fit a function's parameters remembered per function.
REMEMBERED_TEXTS = 64


class _Names(dict[str, Any]):
    """The names an annotation may use: its module's, then a public class of that name defined in
    a module of the package already imported (names imported for type checkers only)."""

    def __init__(self, module_globals: dict[str, Any]) -> None:
        super().__init__(module_globals)

    def __missing__(self, name: str) -> Any:
        for module_name, module in list(sys.modules.items()):
            if module_name.startswith("mazesim") and module is not None:
                found = vars(module).get(name)
                if isinstance(found, type) and found.__name__ == name:
                    return found
        raise KeyError(name)


def annotations_of(func: Callable[..., Any]) -> dict[str, Any]:
    """``func``'s annotations as objects; a name imported for type checkers only is looked up
    among the package's public classes, and an annotation that cannot be read is left out."""
    try:
        return typing.get_type_hints(func, include_extras=True)
    except Exception:  # noqa: BLE001 - names for type checkers only: read one by one
        pass
    hints = {}
    names = _Names(getattr(func, "__globals__", {}))
    for name, text in getattr(func, "__annotations__", {}).items():
        try:
            hints[name] = eval(text, {}, names) if isinstance(text, str) else text  # noqa: S307
        except Exception:  # noqa: BLE001, S112 - an annotation that cannot be read
            continue
    return hints


def _takes_int(hint: Any) -> bool:
    """Whether ``hint`` is ``int`` or a union with ``int`` and no ``float``."""
    if hint is int:
        return True
    args = typing.get_args(hint) if typing.get_origin(hint) in _UNIONS else ()
    return int in args and float not in args


#: The types ``int()`` reads as ints, a value of which may be another number than the int.
_READ_AS_INTS = (bool, float, np.bool_, np.floating)
#: The types of a number that may be NaN.
_FLOATS = (float, np.floating)
#: The plain values a call may take without failing whatever their annotation says (``float()``
#: reads True, an f-string reads None or 3 as a name): checked before the call.
_SCALARS = (bool, np.bool_, int, float, type(None))
#: The scalar types each annotation takes without a closer look.
_PLAIN_TYPES: dict[Any, tuple[type, ...]] = {
    float: (float, int),
    int: (int,),
    # numpy's bool (a comparison of arrays gives one) is a bool, and no more an int than
    # Python's is.
    bool: (bool, np.bool_),
    str: (),
    type(None): (type(None),),
    None: (type(None),),
}


def _item_depth(hint: Any, kind: type = int) -> int:
    """How deep ``hint`` (or its member besides None) nests sequences of ``kind`` (ints, or
    numbers: ``float``, which may be given as ints): 1 for a list, tuple or sequence of them
    (``tuple[int, int]``), 2 for ``Sequence[Sequence[int]]``; 0 for any other annotation."""
    if typing.get_origin(hint) in _UNIONS:
        members = [m for m in typing.get_args(hint) if m is not type(None)]
        return _item_depth(members[0], kind) if len(members) == 1 else 0
    if typing.get_origin(hint) not in (list, tuple, abc.Sequence, abc.MutableSequence):
        return 0
    items = {a for a in typing.get_args(hint) if a is not Ellipsis}
    if (
        items == {kind}
        or kind is float
        and (items <= {float, int, MaybeInfinite} and items - {int})
    ):
        return 1
    inner = {_item_depth(a, kind) for a in items}
    return 1 + inner.pop() if len(inner) == 1 and 0 not in inner else 0


def _takes_float(hint: Any) -> bool:
    """Whether ``hint`` is a number (``float`` or :data:`~mazesim.errors.MaybeInfinite`), or a
    union with one."""
    if hint is float or hint == MaybeInfinite:
        return True
    members = typing.get_args(hint) if typing.get_origin(hint) in _UNIONS else ()
    return float in members or MaybeInfinite in members


def _may_be_infinite(hint: Any) -> bool:
    """Whether ``hint`` is :data:`~mazesim.errors.MaybeInfinite`, alone, in a union or as the
    items of a list or tuple."""
    if hint == MaybeInfinite:
        return True
    return typing.get_origin(hint) in (*_UNIONS, list, tuple, abc.Sequence) and any(
        _may_be_infinite(member) for member in typing.get_args(hint)
    )


def _not_a_finite(value: Any, infinite: bool) -> str | None:
    """What is wrong with a number (a float) given where a finite one is meant (or, with
    ``infinite``, any but NaN), or None."""
    if value != value:
        return "expected a number, found NaN"
    if not infinite and value in (math.inf, -math.inf):
        return f"expected a finite number, found {float(value)}"
    return None


#: Why an array is refused for a list of numbers.
_NAN = "expected numbers, found NaN"
_NOT_FINITE = "expected finite numbers, found NaN or an infinity"


def _nan_item(value: Any, depth: int, budget: list[int], infinite: bool) -> tuple[str, str] | None:
    """The place (``"item 0: item 2"``) and the refusal of the first NaN (or, unless
    ``infinite``, infinity) of a list or tuple of numbers nested ``depth`` deep, or of a numpy
    array in its place; at most ``budget[0]`` items are read, the budget shared by the levels."""
    for index, item in enumerate(value):
        if budget[0] <= 0:
            return None
        budget[0] -= 1
        if isinstance(item, np.ndarray):
            if _holds_nan(item, infinite):
                return f"item {index}", _NAN if infinite else _NOT_FINITE
        elif depth > 1 and isinstance(item, (list, tuple)):
            inner = _nan_item(item, depth - 1, budget, infinite)
            if inner is not None:
                return f"item {index}: {inner[0]}", inner[1]
        elif isinstance(item, _FLOATS):
            reason = _not_a_finite(item, infinite)
            if reason is not None:
                return f"item {index}", reason
    return None


def _holds_nan(array: np.ndarray[Any, Any], infinite: bool = True) -> bool:
    """Whether a numpy array of floats (of at most :data:`MOST_ARRAY_VALUES`) holds a NaN (or,
    unless ``infinite``, an infinity), its masked values too; an array of another kind is left to
    the call's own conversion."""
    if array.dtype.kind not in "fc" or array.size > MOST_ARRAY_VALUES:
        return False
    values = np.asarray(array.data if isinstance(array, np.ma.MaskedArray) else array)
    return bool(np.isnan(values).any() if infinite else not np.isfinite(values).all())


def _another_int_item(value: Any, depth: int, budget: list[int]) -> tuple[str, Any] | None:
    """The place (``"item 0: item 2"``) and value of the first item of a list or tuple of ints
    nested ``depth`` deep that ``int()`` would read as another number (a bool, 4.5, NaN), that
    no 64-bit integer holds, or that is a list or tuple where an int belongs; at most
    ``budget[0]`` items are read, the budget shared by the levels."""
    for index, item in enumerate(value):
        if budget[0] <= 0:
            return None
        budget[0] -= 1
        if depth > 1:
            inner = None
            if isinstance(item, (list, tuple)):  # another kind is left to the usual check
                inner = _another_int_item(item, depth - 1, budget)
            if inner is not None:
                return f"item {index}: {inner[0]}", inner[1]
        elif isinstance(item, (list, tuple)) or _read_as_another_int(item):
            return f"item {index}", item
        elif type(item) is int and not SMALLEST_INT <= item <= LARGEST_INT:
            return f"item {index}", item
    return None


def _not_whole_array(array: np.ndarray[Any, Any]) -> str | None:
    """Why a numpy array given for a list or tuple of ints is not whole numbers (a bool array, a
    float one holding 4.5, NaN or an infinity), or None; ``int()`` would read its values as
    other numbers without a word."""
    if array.dtype.kind == "b":
        return TypeRefusal(f"expected ints, found an array of dtype {array.dtype}")
    if array.dtype.kind != "f" or array.size > MOST_ARRAY_VALUES:
        return None  # ints, or a kind the call's own conversion refuses
    values = np.asarray(array.data if isinstance(array, np.ma.MaskedArray) else array)
    with np.errstate(invalid="ignore"):
        whole = np.isfinite(values) & (values == np.floor(values))
    if whole.all():
        return None
    found = values[~whole].flat[0]
    return TypeRefusal(f"expected ints, found {_describe(float(found))} in an array")


def _plain_types(hint: Any) -> tuple[type, ...] | None:
    """The scalar types (of :data:`_SCALARS`) a value of ``hint`` may have without a closer
    look, or None when ``hint`` is one the scalar check leaves alone (``Any``, a choice of
    literals, an array-like, a class of the package...): those are checked after a failure."""
    members = typing.get_args(hint) if typing.get_origin(hint) in _UNIONS else (hint,)
    if not members or any(m not in _PLAIN_TYPES for m in members):
        return None
    return tuple({t for m in members for t in _PLAIN_TYPES[m]})


def _read_as_another_int(value: Any) -> bool:
    """Whether ``int(value)`` is a number other than the one given: a bool, or a float with a
    fractional part, NaN or an infinity."""
    if isinstance(value, (bool, np.bool_)):
        return True
    return isinstance(value, _READ_AS_INTS) and not float(value).is_integer()


#: The most characters of a parameter's description a missing-argument message quotes.
MOST_DESCRIBED = 300

#: What a parameter takes with no check to make (:meth:`_Parameters._plain_kind`): any value;
#: values that are no scalar, text or container (a device, a world); a 64-bit int; an int or a
#: finite float; an int or a float but NaN; an int or any float.
TAKES_ANY, TAKES_OPAQUE, TAKES_INT, TAKES_FINITE, TAKES_NOT_NAN, TAKES_ANY_FLOAT = range(6)


def documented_argument(func: Callable[..., Any], name: str) -> str | None:
    """What the ``Args:`` section of ``func``'s docstring says of the parameter ``name``, on one
    line (continuation lines joined; cut at :data:`MOST_DESCRIBED` characters), or None when the
    docstring does not describe it: what a call that forgot the argument is told to pass."""
    lines = (inspect.getdoc(inspect.unwrap(func)) or "").splitlines()
    try:
        start = next(i for i, line in enumerate(lines) if line.strip() == "Args:")
    except StopIteration:
        return None
    found: list[str] = []
    indent = None
    for line in lines[start + 1 :]:
        text = line.strip()
        depth = len(line) - len(line.lstrip())
        if indent is None:
            if text and depth == 0:  # the next section: the parameter is not described
                break
            if text.startswith((f"{name}:", f"{name} (")):
                indent = depth
                found.append(text.split(":", 1)[1].strip())
        elif text and depth > indent:
            found.append(text)
        else:
            break
    described = " ".join(found).strip()
    if not described:
        return None
    return (
        described if len(described) <= MOST_DESCRIBED else described[: MOST_DESCRIBED - 3] + "..."
    )


class _Parameters:
    """The checks of one callable's parameters, read from its annotations at its first call."""

    def __init__(self, func: Callable[..., Any], skip_first: bool, takes_nan: bool = False) -> None:
        self.func = func
        self.skip_first = skip_first
        self.ready = False
        self.positional: list[tuple[str, Any]] = []
        self.by_name: dict[str, Any] = {}
        #: Parameters without a default: (position, name, keyword-only).
        self.required: list[tuple[int, str, bool]] = []
        self.any_keyword = True
        #: The name of the unchecked first parameter (``self`` or ``cls``), if any.
        self.first: str | None = None
        #: Parameters whose values have a length bound: (position, name, bound).
        self.sized: list[tuple[int, str, int]] = []
        #: (parameter, text) pairs that fit, by :meth:`refuse_text`.
        self.fitting_text: set[tuple[str, str | bytes] | None] = set()
        #: The parameters annotated as ints (not floats), which ``int()`` would read a bool or
        #: a float of 1.5 as, silently: checked before the call.
        self.ints: set[str] = set()
        #: The parameters annotated as lists or tuples of ints, by how deep they nest
        #: (:func:`_item_depth`): ``int()`` would read their items as silently, so they
        #: are checked before the call.
        self.int_items: dict[str, int] = {}
        #: The scalar types each plainly annotated parameter takes (:func:`_plain_types`): a
        #: bool, None or number of another type is refused before the call.
        self.plain: dict[str, tuple[type, ...]] = {}
        #: The parameters annotated as numbers (``float``), and those annotated as lists or
        #: tuples of numbers by how deep they nest: NaN, which every comparison answers False
        #: and every sum carries on, is no number they take (refused before the call), unless
        #: ``takes_nan`` (Webots' API, which answers NaN itself as Webots does).
        self.takes_nan = takes_nan
        self.numbers: set[str] = set()
        self.number_items: dict[str, int] = {}
        #: Those of them annotated :data:`~mazesim.errors.MaybeInfinite`: an infinity is taken;
        #: the others are given a finite number or refused.
        self.infinite: set[str] = set()
        #: Whether any parameter is a list of ints or of numbers (an array may stand for one).
        self.any_items = False
        #: Per positional parameter, the values it takes without a closer look
        #: (:func:`_plain_kind`); None until prepared, or when a parameter has a length bound.
        self.plainly: tuple[int, ...] | None = None

    def prepare(self) -> None:
        func = inspect.unwrap(self.func)
        hints = annotations_of(func)
        try:
            parameters = list(inspect.signature(func).parameters.values())
        except (TypeError, ValueError):
            parameters = []
        self.any_keyword = not parameters
        for index, p in enumerate(parameters):
            hint = hints.get(p.name, Any)
            if index == 0 and self.skip_first:
                hint = Any
                self.first = p.name
            elif p.default is p.empty and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
                self.required.append((len(self.positional), p.name, p.kind is p.KEYWORD_ONLY))
            if p.kind is p.VAR_KEYWORD:
                self.any_keyword = True
            if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
                continue
            if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD):
                self.positional.append((p.name, hint))
            if p.kind is not p.POSITIONAL_ONLY:
                self.by_name[p.name] = hint
            if _takes_int(hint):
                self.ints.add(p.name)
            depth = _item_depth(hint)
            if depth:
                self.int_items[p.name] = depth
            plain = _plain_types(hint) if hint is not Any else None
            if plain is not None:
                self.plain[p.name] = plain
            if not self.takes_nan and _takes_float(hint):
                self.numbers.add(p.name)
            depth = 0 if self.takes_nan else _item_depth(hint, float)
            if depth:
                self.number_items[p.name] = depth
            if _may_be_infinite(hint):
                self.infinite.add(p.name)
        self.any_items = bool(self.int_items or self.number_items)
        for index, p in enumerate(parameters):
            most = _bound_of(hints.get(p.name, Any))
            if most is not None and not (index == 0 and self.skip_first):
                position = index if p.kind is not p.KEYWORD_ONLY else 1 << 30
                self.sized.append((position, p.name, most))
        if not self.sized:
            self.plainly = tuple(self._plain_kind(name, hint) for name, hint in self.positional)
        self.ready = True

    def _plain_kind(self, name: str, hint: Any) -> int:
        """Which values parameter ``name`` takes with no check to make (:data:`TAKES_ANY`...):
        every value for ``Any``, a 64-bit int for ``int``, an int or a finite float for
        ``float``; for any other annotation, values that are no scalar, text or container."""
        if hint is Any:
            return TAKES_ANY
        simple = name not in self.int_items and name not in self.number_items
        if hint is int and simple:
            return TAKES_INT
        if (hint is float or hint == MaybeInfinite) and simple:
            if self.takes_nan:
                return TAKES_ANY_FLOAT
            return TAKES_NOT_NAN if name in self.infinite else TAKES_FINITE
        return TAKES_OPAQUE

    def check_sizes(self, args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
        """Refuses, before the call, a sized argument longer than its bound."""
        if not self.ready:
            self.prepare()
        for index, name, most in self.sized:
            value = args[index] if index < len(args) else kwargs.get(name)
            if value is not None and not isinstance(value, (str, bytes)):
                reason = _too_many(value, most)
                if reason is not None:
                    where = self.func.__qualname__
                    raise InvalidArgumentError(f"{where}: {name} refused: {reason}")

    def check(self, args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
        """Refuses an unknown argument, a missing one or one that is not a value of its
        annotation, in the order Python names them: the others may be refused only for standing
        in a missing one's place (``plot_world(world)`` gives the world as the axes)."""
        if not self.ready:
            self.prepare()
        for name in kwargs:
            if not self.any_keyword and name not in self.by_name:
                names = [known for known in self.by_name if known != self.first]
                meant = _closest_name(name, names)
                raise InvalidArgumentError(
                    f"{self.func.__qualname__}: expected no argument named {_shown(name)}, "
                    "found one; "
                    f"its arguments: {', '.join(names) or 'none by name'}"
                    + (f"; did you mean {_shown(meant)}?" if meant else "")
                )
        for index, name, keyword_only in self.required:
            if name not in kwargs and (keyword_only or index >= len(args)):
                meaning = documented_argument(self.func, name)
                raise InvalidArgumentError(
                    f"{self.func.__qualname__}: expected the argument {_shown(name)}, found none"
                    + self._given_in_another_place(name, args)
                    + (f"; {name}: {meaning}" if meaning else "")
                )
        for (name, hint), value in zip(self.positional, args):  # noqa: B905 - extras: TypeError
            if hint is not Any:
                self.refuse(name, value, hint)
        for name, value in kwargs.items():
            hint = self.by_name.get(name, Any)
            if hint is not Any:
                self.refuse(name, value, hint)

    def _given_in_another_place(self, missing: str, args: tuple[Any, ...]) -> str:
        """What to add when the value of a missing argument annotated with one of the package's
        classes was given in another place (``plot_world(world)``, whose first argument is the
        axes): which argument took it, and the order the function takes them in; "" otherwise."""
        hint = self.by_name.get(missing)
        if not (isinstance(hint, type) and hint.__module__.startswith("mazesim")):
            return ""
        if _is_typeddict(hint):  # a TypedDict is any mapping: no value is told as one
            return ""
        if _untestable_protocol(hint):
            return ""
        for (name, _), value in zip(self.positional, args):  # noqa: B905 - extras: TypeError
            if isinstance(value, hint):
                order = ", ".join(known for known, _ in self.positional)
                return (
                    f" (the {hint.__name__} was given as {_shown(name)}: "
                    f"{self.func.__name__}({order}))"
                )
        return ""

    def check_text(self, args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
        """Refuses, before the call, a text argument (``str`` or ``bytes``) its annotation does
        not take."""
        for (name, hint), value in zip(self.positional, args):  # noqa: B905 - extras: TypeError
            if isinstance(value, _TEXT) and hint is not Any:
                self.refuse_text(name, value, hint)
        for name, value in kwargs.items():
            hint = self.by_name.get(name, Any)
            if isinstance(value, _TEXT) and hint is not Any:
                self.refuse_text(name, value, hint)

    def check_scalars(self, args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
        """Refuses, before the call, a plain value its parameter's annotation does not take,
        which the call could read as something else without a word: a bool or a float with a
        fractional part (or not finite) given for an int (``int()`` reads them), an int beyond
        64 bits for an int, a bool for a number (``Robot.step(True)`` is not 1 ms), None or a
        number for text (``getDevice(None)`` is not the device named "None"); a list, tuple,
        mapping or set for any of those (C code may read it without bound)."""
        pairs = [*self.positional[: len(args)], *((n, self.by_name.get(n, Any)) for n in kwargs)]
        values = [*args[: len(self.positional)], *kwargs.values()]
        for (name, hint), value in zip(pairs, values):  # noqa: B905 - one value per pair
            if hint is not Any and isinstance(value, _CONTAINERS) and name in self.plain:
                self.refuse(name, value, hint)  # a list for a number: C code may recurse into it
            if name in self.int_items and isinstance(value, np.ndarray):
                reason = _not_whole_array(value)
                if reason is not None:
                    where = self.func.__qualname__
                    raise refusal_error(reason)(f"{where}: {name} refused: {reason}")
            if name in self.int_items and isinstance(value, (list, tuple)):
                another = _another_int_item(value, self.int_items[name], [CHECKED_INT_ITEMS])
                if another is not None:
                    place, item = another
                    reason = _refusal(item, int) or f"expected int, found {_describe(item)}"
                    raise refusal_error(reason)(
                        f"{self.func.__qualname__}: {name} refused: {place}: {reason}"
                    )
            if name in self.numbers and isinstance(value, _FLOATS):
                reason = _not_a_finite(value, name in self.infinite)
                if reason is not None:
                    self.refuse_nan(name, "", reason)
            if name in self.number_items:
                self.refuse_nan_items(name, value)
            if hint is Any or not isinstance(value, _SCALARS):
                continue
            if name in self.ints and (
                _read_as_another_int(value)
                or (type(value) is int and not SMALLEST_INT <= value <= LARGEST_INT)
            ):
                self.refuse(name, value, hint)
            plain = self.plain.get(name)
            if plain is not None and type(value) not in plain:
                self.refuse(name, value, hint)

    def refuse_nan_items(self, name: str, value: Any) -> None:
        """Refuses a list or tuple of numbers (or a numpy array in its place) holding NaN."""
        infinite = name in self.infinite
        found: tuple[str, str] | None = None
        if isinstance(value, np.ndarray):
            if _holds_nan(value, infinite):
                found = ("", _NAN if infinite else _NOT_FINITE)
        elif isinstance(value, (list, tuple)):
            found = _nan_item(value, self.number_items[name], [CHECKED_INT_ITEMS], infinite)
        if found is not None:
            place, reason = found
            self.refuse_nan(name, f"{place}: " if place else "", reason)

    def refuse_nan(self, name: str, place: str, reason: str) -> None:
        """Refuses NaN or an infinity given for ``name`` (at ``place`` in it), saying what the
        parameter is when the docstring says it (its range, its unit)."""
        meaning = documented_argument(self.func, name)
        raise InvalidArgumentError(
            f"{self.func.__qualname__}: {name} refused: {place}{reason}"
            + (f"; {name}: {meaning}" if meaning else "")
        )

    def refuse_text(self, name: str, value: str | bytes | bytearray, hint: Any) -> None:
        """:meth:`refuse` for text, remembering the last texts that fit (a controller asks for
        the same device names at every step)."""
        key = None if isinstance(value, bytearray) else (name, value)
        if key in self.fitting_text:
            return
        self.refuse(name, value, hint)
        if key is not None:
            if len(self.fitting_text) >= REMEMBERED_TEXTS:
                self.fitting_text.clear()
            self.fitting_text.add(key)

    def given(self, args: tuple[Any, ...], kwargs: dict[str, Any]) -> str:
        """What a call was given and what its annotations expected, for the message of a
        failure no check names ("expected levels: an array of numbers; found levels=[nan]"):
        every refusal then says what was expected and what was found."""
        if not self.ready:
            self.prepare()
        named = [*zip(self.positional, args)]
        named += [((n, self.by_name.get(n, Any)), v) for n, v in kwargs.items()]
        given = [(name, hint, value) for (name, hint), value in named if name != self.first]
        if not given:
            return ""
        expected = ", ".join(f"{name}: {_expected(hint)}" for name, hint, _ in given)
        found = ", ".join(
            f"{name}={_shortened(_shown(value), GIVEN_CHARACTERS)}" for name, _, value in given
        )
        return f"expected {expected}; found {found}"

    def refuse(self, name: str, value: Any, hint: Any) -> None:
        reason = refusal(value, hint)
        if reason is not None:
            raise refusal_error(reason)(f"{self.func.__qualname__}: {name} refused: {reason}")


def answers_non_finite(func: Callable[..., Any]) -> Callable[..., Any]:
    """Marks ``func`` as answering NaN and infinities given for its numbers itself (with a
    refusal of its own class, ``InvalidActionError`` for a command): the surface check lets
    them through to it. A module does the same for all its functions with a module-level
    ``_takes_nan = True`` (a wire format that carries any double), a class for its methods."""
    func._takes_nan = True  # type: ignore[attr-defined]
    return func


def checked(
    func: Callable[..., Any], *, method: bool = False, takes_nan: bool = False
) -> Callable[..., Any]:
    """``func`` with its arguments checked against its annotations before each call (``method``:
    its first parameter, ``self`` or ``cls``, is not checked; ``takes_nan``: a parameter annotated
    as a number may be given NaN, which ``func`` answers itself). The wrapper runs in ``func``'s
    module's globals, so doctest and ``inspect`` see it as that module's function."""
    if is_checked(func):
        return func
    parameters = _Parameters(func, method, takes_nan or bool(getattr(func, "_takes_nan", False)))
    # The wrapper runs in func's globals: everything it uses is bound here.
    error, own, failures, text = InvalidArgumentError, MazesimError, _ARGUMENT_FAILURES, _TEXT
    wrong = WrongTypeError
    scalars_or_containers = (*_SCALARS, np.floating, *_CONTAINERS)
    with_arrays = (*scalars_or_containers, np.ndarray)  # an array for a list of ints
    opaque_not = (*with_arrays, *text, np.generic)  # what an opaque parameter checks closer
    tree = in_the_tree
    state = STATE  # per thread, whether a checked call is running

    def plainly_taken(args: tuple[Any, ...]) -> bool:
        """Whether every argument is one its parameter takes with no check to make: the
        common call (``drawPixel(3, 4)``, ``setVelocity(6.28)``) skips the checks below."""
        kinds = parameters.plainly
        if kinds is None or len(args) > len(kinds):
            return False
        for value, kind in zip(args, kinds):  # noqa: B905 - fewer values: defaults
            if kind == TAKES_ANY:
                continue
            kind_of_value = type(value)
            if kind_of_value is int:
                if kind == TAKES_OPAQUE or (
                    kind == TAKES_INT and not SMALLEST_INT <= value <= LARGEST_INT
                ):
                    return False
            elif kind_of_value is float:
                if kind == TAKES_FINITE:
                    taken = value - value == 0.0  # NaN and the infinities give NaN
                elif kind == TAKES_NOT_NAN:
                    taken = value == value
                else:
                    taken = kind == TAKES_ANY_FLOAT
                if not taken:
                    return False
            elif kind != TAKES_OPAQUE or isinstance(value, opaque_not):
                return False
        return True

    def check_before(args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
        """The checks made before the call: lengths, text, plain values."""
        if parameters.sized or not parameters.ready:
            parameters.check_sizes(args, kwargs)
        for value in (*args, *kwargs.values()) if kwargs else args:
            if isinstance(value, text):  # float("64") would take text for a number: check now
                parameters.check_text(args, kwargs)
                break
        if parameters.ints or parameters.plain or parameters.any_items or parameters.numbers:
            # int(True), f"{None}", NaN for a number
            kinds = with_arrays if parameters.any_items else scalars_or_containers
            for value in (*args, *kwargs.values()) if kwargs else args:
                if isinstance(value, kinds):
                    parameters.check_scalars(args, kwargs)
                    break

    def wrapper(*args: Any, **kwargs: Any) -> Any:
        if getattr(state, "inside", False):
            return func(*args, **kwargs)  # called by the package itself: checked at the surface
        if kwargs or not plainly_taken(args):
            check_before(args, kwargs)
        state.inside = True
        try:
            return func(*args, **kwargs)
        except KeyboardInterrupt:
            raise
        except own as failure:
            if isinstance(failure, error) and not isinstance(failure, wrong):
                # The function's own refusal; an argument of a type its annotation does not
                # take is the cause to name, as a TypeError (a hand-written check said "found
                # 42" without saying that it was the type that was wrong).
                try:
                    parameters.check(args, kwargs)
                except wrong as refusal:
                    raise refusal.with_traceback(None) from None
                except error:
                    pass  # a missing or unknown argument: the function's message says more
            raise
        except failures as failure:
            try:
                parameters.check(args, kwargs)  # raises InvalidArgumentError naming the argument
            except error as refusal:
                # The refusal says what is wrong; the line deep inside that failed would not.
                raise refusal.with_traceback(None) from None
            trace = failure.__traceback__
            if isinstance(failure, TypeError) and trace is not None and trace.tb_next is None:
                raise error(f"{func.__qualname__}: {failure}") from None  # wrong arguments
            instead = tree(func.__qualname__, failure, True, parameters.given(args, kwargs))
            if instead is failure:
                raise
            raise instead from failure
        except Exception as failure:
            # Any other failure (a library's own exception, ZeroDivisionError, a RuntimeError
            # from a value's method): an argument its annotation does not take is the cause.
            # Out of memory, a check of the arguments would run out again: not made.
            try:
                if not isinstance(failure, MemoryError):
                    parameters.check(args, kwargs)
            except error as refusal:
                raise refusal.with_traceback(None) from None
            instead = tree(func.__qualname__, failure, False)
            if instead is failure:
                raise
            raise instead from failure
        finally:
            state.inside = False

    code = wrapper.__code__
    # A function made by exec without builtins (a NamedTuple's __new__) keeps this module's.
    home = func.__globals__ if func.__globals__.get("__builtins__") else globals()
    made = types.FunctionType(code, home, func.__name__, None, wrapper.__closure__)
    functools.update_wrapper(made, func)
    made.__kwdefaults__ = None
    return mark_checked(made)


def _refuse_any_argument(cls: type) -> Callable[..., None]:
    """An ``__init__`` for a class that takes no arguments (its ``__init__`` and ``__new__``
    are ``object``'s), so that a call with some is refused by the check as any other. Not for
    a class with subclasses (a mixin's ``__init__`` would hide the next class's)."""

    def __init__(self: Any) -> None:
        pass

    __init__.__qualname__ = f"{cls.__qualname__}.__init__"
    __init__.__module__ = cls.__module__
    return __init__


def _refuse_abstract(cls: type, *args: Any, **kwargs: Any) -> Any:
    """The ``__new__`` of a public abstract class: a class that still lacks a method is refused
    as a :class:`~mazesim.errors.WrongTypeError` (a ``TypeError``) that names what to define
    and the subclasses there are; any other is made as ``object`` makes it."""
    if inspect.isabstract(cls):
        lacking = ", ".join(sorted(cls.__abstractmethods__))  # type: ignore[attr-defined]
        ready = sorted(sub.__name__ for sub in _subclasses(cls) if not inspect.isabstract(sub))
        raise WrongTypeError(
            f"{cls.__qualname__}: expected a subclass that defines {lacking}"
            + (f" (such as {', '.join(ready)})" if ready else "")
            + f", found the abstract {cls.__qualname__} itself"
        )
    return object.__new__(cls)


def _subclasses(cls: type) -> list[type]:
    """Every subclass of ``cls``, however deep."""
    subs: list[type] = cls.__subclasses__()
    return [deeper for sub in subs for deeper in (sub, *_subclasses(sub))]


def _guard_class(cls: type) -> None:
    if issubclass(cls, BaseException) or getattr(cls, "_is_protocol", False):
        return
    import enum

    if issubclass(cls, enum.Enum):
        return
    # A class with ``_takes_nan`` answers NaN itself (Webots' API, as Webots does): its number
    # parameters are not refused NaN.
    nan = bool(getattr(cls, "_takes_nan", False))
    inherited = cls.__init__
    if "__init__" not in vars(cls) and inspect.isfunction(inherited):
        cls.__init__ = checked(inherited, method=True, takes_nan=nan)  # type: ignore[method-assign]
    elif (
        inherited is object.__init__ and cls.__new__ is object.__new__ and not cls.__subclasses__()
    ):
        cls.__init__ = checked(_refuse_any_argument(cls), method=True, takes_nan=nan)  # type: ignore[method-assign]
    if inspect.isabstract(cls) and "__new__" not in vars(cls) and cls.__new__ is object.__new__:
        cls.__new__ = _refuse_abstract  # type: ignore[method-assign]
    made_by = getattr(vars(cls).get("__new__"), "__func__", None)
    if inspect.isfunction(made_by):  # a NamedTuple's constructor
        cls.__new__ = staticmethod(checked(made_by, method=True, takes_nan=nan))  # type: ignore[method-assign]
    for name, raw in list(vars(cls).items()):
        if name.startswith("_") and name != "__init__":
            continue
        if isinstance(raw, staticmethod):
            setattr(cls, name, staticmethod(checked(raw.__func__, takes_nan=nan)))
        elif isinstance(raw, classmethod):
            setattr(cls, name, classmethod(checked(raw.__func__, method=True, takes_nan=nan)))
        elif inspect.isfunction(raw):
            setattr(cls, name, checked(raw, method=True, takes_nan=nan))
    for name, raw in _inherited_from_private_bases(cls):
        # A copy named as cls's own method, so that a refusal names the class the user has.
        own = types.FunctionType(
            raw.__code__, raw.__globals__, raw.__name__, raw.__defaults__, raw.__closure__
        )
        functools.update_wrapper(own, raw)
        own.__qualname__ = f"{cls.__qualname__}.{name}"
        own.__kwdefaults__ = raw.__kwdefaults__
        setattr(cls, name, checked(own, method=True, takes_nan=nan))


def _inherited_from_private_bases(cls: type) -> list[tuple[str, Callable[..., Any]]]:
    """The public methods ``cls`` takes from the package's private base classes (a Webots
    ``DistanceSensor``'s ``enable``, from ``_Sensor``), which no public class of their own puts
    the check on: they are part of ``cls``'s surface."""
    found = []
    for base in cls.__mro__[1:]:
        if not base.__name__.startswith("_") or not base.__module__.startswith("mazesim."):
            continue
        for name, raw in vars(base).items():
            if name.startswith("_") or not inspect.isfunction(raw):
                continue
            if inspect.getattr_static(cls, name) is raw:
                found.append((name, raw))
    return found


def public_names(module: types.ModuleType) -> list[str]:
    """The public functions and classes of a public module: those its ``__all__`` names (every
    name not starting with ``_`` when it has none) that are defined in it, not re-exported."""
    names = getattr(module, "__all__", None)
    found = []
    for name in names if names is not None else dir(module):
        obj = getattr(module, name, None)
        if name.startswith("_") or getattr(obj, "__module__", None) != module.__name__:
            continue
        if inspect.isfunction(obj) or inspect.isclass(obj) or inspect.isbuiltin(obj):
            found.append(name)
    return found


def listing(module: types.ModuleType) -> Callable[[], list[str]]:
    """The module's ``__dir__``: what its ``__all__`` names, its imported public submodules and
    its dunder names, without the names its code imported for itself (``os``, ``annotations``
    of ``from __future__``), so that tab completion (``mazesim.<Tab>``, ``dir(mazesim)``) offers
    the API."""

    def __dir__() -> list[str]:
        names = set(getattr(module, "__all__", ()))
        for name, value in vars(module).items():
            dunder = name.startswith("__") and name.endswith("__")
            submodule = isinstance(value, types.ModuleType) and not name.startswith("_")
            if dunder or (submodule and value.__name__ == f"{module.__name__}.{name}"):
                names.add(name)
        return sorted(names)

    return __dir__


def guard_module(module: types.ModuleType) -> None:
    """Puts the check on every public function and method of ``module``, and gives a module
    with an ``__all__`` and no ``__dir__`` of its own the :func:`listing` of its API."""
    if hasattr(module, "__all__") and "__dir__" not in vars(module):
        module.__dir__ = listing(module)  # type: ignore[method-assign]
    for name in public_names(module):
        obj = getattr(module, name)
        if inspect.isfunction(obj):
            setattr(module, name, checked(obj, takes_nan=bool(getattr(module, "_takes_nan", 0))))
        elif inspect.isclass(obj):
            _guard_class(obj)


class ThenLoader(importlib.abc.Loader):
    """Executes a module with its own loader, then calls ``then`` with it: the one way the
    package's import hooks act on a module once it is imported (here the argument check on a
    public module's surface; :mod:`mazesim._gym_registration` the environments' registration)."""

    def __init__(self, loader: Any, then: Callable[[types.ModuleType], None]) -> None:
        self._loader = loader
        self._then = then

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType | None:
        return self._loader.create_module(spec)

    def exec_module(self, module: types.ModuleType) -> None:
        self._loader.exec_module(module)
        self._then(module)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._loader, name)


class _CheckingFinder(importlib.abc.MetaPathFinder):
    """Finds mazesim's public modules as usual and gives them the checking loader."""

    def find_spec(
        self, fullname: str, path: Any, target: types.ModuleType | None = None
    ) -> importlib.machinery.ModuleSpec | None:
        if not is_public_module(fullname) or fullname == "mazesim":
            return None
        spec = importlib.machinery.PathFinder.find_spec(fullname, path, target)
        if spec is None or spec.loader is None or isinstance(spec.loader, ThenLoader):
            return spec
        spec.loader = ThenLoader(spec.loader, guard_module)
        return spec


def install() -> None:
    """Adds the import hook (once), and checks the public modules imported before it."""
    if not any(isinstance(f, _CheckingFinder) for f in sys.meta_path):
        sys.meta_path.insert(0, _CheckingFinder())
    for name, module in list(sys.modules.items()):
        if is_public_module(name) and name != "mazesim" and module is not None:
            guard_module(module)
