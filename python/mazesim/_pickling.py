"""Pickling and copying of the compiled core's objects.

A class of :mod:`mazesim._core` pickles and copies through a ``__reduce__`` of its own (a world
as its text, a simulator with its whole state). A class without one (a batch of environments, a
navigator's tables, the settings of one ``run`` call holding its output buffers) would fail in
Python's ``pickle`` or ``copy`` with a bare ``TypeError``; :func:`refuse_unpicklable` gives each
such class, once, a ``__reduce__`` that raises :class:`~mazesim.errors.WrongTypeError` (an
``InvalidArgumentError`` that is also a ``TypeError``, as ``pickle``'s own refusal is) naming the
class and what to do instead, so that a class added to the core later is covered without code of
its own.
"""

from __future__ import annotations

import types
from typing import Any, NoReturn

from mazesim.errors import WrongTypeError, _with_article

__all__ = ["refuse_unpicklable"]


def _refusal(name: str) -> Any:
    def __reduce__(self: Any) -> NoReturn:
        raise WrongTypeError(
            "expected an object that can be pickled or copied, "
            f"found {_with_article(name)}, which cannot be: "
            f"make a new {name} with the arguments that made this one",
        )

    __reduce__.__qualname__ = f"{name}.__reduce__"
    return __reduce__


def refuse_unpicklable(core: types.ModuleType) -> None:
    """Gives every class of ``core`` without a ``__reduce__`` of its own the refusing one."""
    for name in dir(core):
        cls = getattr(core, name)
        if not isinstance(cls, type) or issubclass(cls, BaseException):
            continue
        if "__reduce__" not in vars(cls) and "__getstate__" not in vars(cls):
            cls.__reduce__ = _refusal(name)  # type: ignore[method-assign]
