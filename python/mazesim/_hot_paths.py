"""The one marker of a function the surface's argument check leaves alone.

:mod:`mazesim._checks` wraps every public function and method in an argument check; a function
that already carries the marker (the check's own wrapper, or a per-step hot path that checks its
own arguments) is left as it is. The marker is set here and nowhere else (a test of the package's
source keeps it so): a hot path marked by hand skipped the thin wrapper below, and a call of the
wrong arity reached the user as Python's bare ``TypeError``. This module sits below every layer
that has a hot path (the Webots layer may not import the argument check itself).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any

from mazesim.errors import InvalidArgumentError

__all__ = ["checks_own_arguments", "is_checked", "mark_checked"]

#: The attribute that says a function's arguments are checked (by the surface or by itself).
_MARKER = "__mazesim_checked__"


def is_checked(func: object) -> bool:
    """Whether ``func`` is marked as checked: the surface's check leaves it as it is."""
    return bool(getattr(func, _MARKER, False))


def mark_checked(func: Callable[..., Any]) -> Callable[..., Any]:
    """Marks ``func`` (a wrapper that checks its arguments) as checked, and returns it."""
    setattr(func, _MARKER, True)
    return func


def checks_own_arguments(func: Callable[..., Any]) -> Callable[..., Any]:
    """Marks ``func`` as a per-step hot path that checks its own arguments (an env's ``step``
    refuses a bad action itself): the surface's check leaves it out, so a step pays nothing for
    it. Only a call with the wrong number of arguments (refused by Python before ``func`` runs,
    with a ``TypeError``) is turned into :class:`~mazesim.errors.InvalidArgumentError`, by a thin
    wrapper that does nothing else. The public-surface registry still feeds it hostile
    arguments."""
    error = InvalidArgumentError

    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            return func(*args, **kwargs)
        except TypeError as failure:
            trace = failure.__traceback__
            if trace is not None and trace.tb_next is None:  # raised by the call itself
                raise error(f"{func.__qualname__}: {failure}") from None
            raise

    functools.update_wrapper(wrapper, func)
    return mark_checked(wrapper)
