"""Sizes before allocation on the Python side: a sequence or array-like the package converts
itself (``np.asarray(seeds)``) is checked against its bound before numpy reserves anything, so that
``seeds=range(10**9)`` is an :class:`~mazesim.errors.InvalidArgumentError` saying the bound and the
length found, not a ``MemoryError`` or an abort. The compiled core checks what it takes the same
way (``bounded_items`` in the binding crate).

Example:
    >>> from mazesim._sizes import bounded_array
    >>> bounded_array([1, 2], "seeds", "uint64", most=4).tolist()
    [1, 2]
"""

from __future__ import annotations

import itertools
import math
import warnings
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim.errors import InvalidArgumentError, _a_type, _shown

__all__ = [
    "MOST_ENVS",
    "bounded_array",
    "bounded_list",
    "index_array",
    "number_array",
    "seed_array",
    "size_of",
    "whole_array",
]

#: Most environments of a batch (the core's ``limits::MAX_ENVS``).
MOST_ENVS = 1 << 24


def size_of(value: Any) -> int | None:
    """The number of values ``value`` would give numpy, as far as it says without being read: a
    ``.shape``'s product, else its ``len()``; ``None`` for a scalar or an object of no size."""
    shape = getattr(value, "shape", None)
    if isinstance(shape, tuple) and len(shape) <= 64 and all(isinstance(d, int) for d in shape):
        return math.prod(shape)
    if isinstance(value, (str, bytes, bytearray)) or not hasattr(value, "__len__"):
        return None
    try:
        return len(value)
    except OverflowError:  # a length beyond sys.maxsize
        return 1 << 63
    except Exception:  # noqa: BLE001 - a __len__ that fails: no size known
        return None


def bounded_array(
    value: Any, name: str, dtype: npt.DTypeLike | None, most: int
) -> npt.NDArray[Any]:
    """``value`` as a numpy array of ``dtype`` (None: numpy's choice), refused before
    conversion when it holds more than ``most`` values; one numpy cannot convert is refused
    too, naming ``name``."""
    size = size_of(value)
    if size is not None and size > most:
        raise InvalidArgumentError(
            f"expected {name} to hold at most {most} values, found {size} ({_a_type(value)})"
        )
    try:
        array = np.asarray(value, dtype=dtype)
    except (TypeError, ValueError, OverflowError) as error:
        raise InvalidArgumentError(
            f"expected {name} to be {most} or fewer values of "
            f"{'numbers' if dtype is None else np.dtype(dtype)}, "
            f"found {_a_type(value)}: {str(error)[:200]}"
        ) from error
    if array.size > most:
        raise InvalidArgumentError(
            f"expected {name} to hold at most {most} values, found {array.size}"
        )
    return array


def bounded_list(value: Any, name: str, most: int) -> list[Any]:
    """``list(value)``, refused before it is read when it holds more than ``most`` items (or
    is not a sized collection)."""
    size = size_of(value)
    if size is None or isinstance(value, (str, bytes, bytearray)):
        raise InvalidArgumentError(
            f"expected {name} to be a list of at most {most} items, found {_a_type(value)}"
        )
    if size > most:
        raise InvalidArgumentError(
            f"expected {name} to hold at most {most} items, found {size} ({_a_type(value)})"
        )
    items = list(itertools.islice(value, most + 1))  # a __len__ that lied is cut short too
    if len(items) > most:
        raise InvalidArgumentError(f"expected {name} to hold at most {most} items, found more")
    return items


def index_array(
    value: Any, name: str, count: int, most: int | None = None
) -> npt.NDArray[np.int64]:
    """``value`` as int64 indices into ``count`` things (actions, states, levels, robots),
    refused unless each is a whole number from 0 to ``count - 1``: numpy would cut 1.7 to 1
    and take -1 as the last one, without a word. Booleans count as 0 and 1; floats that are
    whole (``2.0``) are taken. With ``most``, more than ``most`` values are refused before
    conversion (:func:`bounded_array`).

    Raises:
        InvalidArgumentError: An index is out of range, not whole, or not a number; or there
            are more than ``most``.
    """
    return _whole_numbers(value, name, 0, count, most, np.int64)


#: The smallest and the largest whole number :func:`whole_array` takes by default: int64's,
#: less its lowest value (whose absolute value int64 cannot hold).
SMALLEST_WHOLE = -(1 << 63) + 1
LARGEST_WHOLE = (1 << 63) - 1


def whole_array(
    value: Any,
    name: str,
    low: int = SMALLEST_WHOLE,
    high: int = LARGEST_WHOLE,
    most: int | None = None,
) -> npt.NDArray[np.int64]:
    """``value`` as int64 whole numbers from ``low`` to ``high`` (checkpoint events, counts,
    delays), refused unless each is one: numpy would cut 1.7 to 1 and read NaN as -2**63,
    without a word. Booleans count as 0 and 1; floats that are whole are taken. Use
    :func:`index_array` for indices into a collection.

    Raises:
        InvalidArgumentError: A value is out of range, not whole, or not a number; or there are
            more than ``most``.
    """
    return _whole_numbers(value, name, low, high + 1, most, np.int64)


def number_array(
    value: Any,
    name: str,
    dtype: npt.DTypeLike = np.float64,
    *,
    nan_means: str = "",
    inf_means: str = "",
    checked_after: bool = False,
) -> npt.NDArray[Any]:
    """``value`` as an array of ``dtype`` numbers, refused when it holds NaN or an infinity,
    unless ``nan_means`` (``inf_means``) says what a NaN (an infinity) stands for there: a gap
    in a path, a reading not yet taken, a wall of no top. numpy takes both in without a word:
    every comparison with NaN answers False, so a range check downstream lets it through and a
    sum carries it on; an infinity turns a difference or a product with zero into NaN, and a
    number too large for ``dtype`` (1e300 as float32) becomes one. ``checked_after``: the
    caller refuses both itself, with a message that says more.

    Raises:
        InvalidArgumentError: ``value`` holds a NaN or an infinity where none is meant.
        TypeError, ValueError: numpy cannot read ``value`` as numbers (at the public surface,
            :mod:`mazesim._checks` turns it into a refusal naming the argument).
    """
    with np.errstate(over="ignore"):  # a number too large for dtype: refused below, by name
        array = np.asarray(value, dtype=dtype)  # numpy's error: the surface check names it
    held = getattr(getattr(value, "dtype", None), "kind", "f")  # bools and ints: all finite
    if checked_after or held not in "fcO" or array.dtype.kind not in "fc":
        return array
    if np.isfinite(array).all():
        return array
    if not nan_means and np.isnan(array).any():
        raise InvalidArgumentError(f"expected {name} as numbers, found NaN")
    if not inf_means and np.isinf(array).any():
        largest = f"{float(np.finfo(array.dtype).max):.3g}"
        raise InvalidArgumentError(
            f"expected {name} as finite numbers (at most {largest} in size), found an infinity "
            "or a number beyond that"
        )
    return array


def seed_array(value: Any, name: str, most: int) -> npt.NDArray[np.uint64]:
    """``value`` as uint64 seeds (at most ``most`` of them), refused unless each is a whole
    number from 0 to 2**64 - 1: numpy would cut 1.5 to 1, read the text ``"3"`` as 3 and wrap
    an int64 -1 to 2**64 - 1.

    Raises:
        InvalidArgumentError: A seed is negative, too large, not whole, or not a number; or
            there are more than ``most``.
    """
    return _whole_numbers(value, name, 0, 1 << 64, most, np.uint64)


def _whole_numbers(
    value: Any, name: str, low: int, below: int, most: int | None, dtype: type[np.integer[Any]]
) -> npt.NDArray[Any]:
    """``value`` as an array of ``dtype``, each a whole number from ``low`` to ``below - 1``."""
    expected = f"expected {name} as whole numbers{_range_words(low, below, dtype)}"
    try:
        array = np.asarray(value) if most is None else bounded_array(value, name, None, most)
    except InvalidArgumentError:
        raise  # too many values, said so by the bound
    except (TypeError, ValueError) as error:  # ragged nesting, unconvertible objects
        raise InvalidArgumentError(
            f"{expected}, found {_a_type(value)}: {str(error)[:200]}"
        ) from None
    if array.dtype.kind not in "biuf":
        raise InvalidArgumentError(f"{expected}, found an array of dtype {array.dtype}")
    if array.dtype.kind != "f" and (array.size == 0 or low <= array.min() and array.max() < below):
        return array.astype(dtype, copy=False)  # the usual case, in two passes
    fit = (array >= low) & (array < below)
    if array.dtype.kind == "f":
        fit &= array == np.floor(array)
        if not isinstance(value, np.ndarray):
            # Python ints past 2**63 beside small ones are read as floats (2**64 - 1 rounds up
            # to 2**64); taken exactly, they may fit.
            exact = _exactly(value, dtype)
            if exact is not None and np.array_equal(exact.astype(np.float64), array):
                return exact
    if not np.all(fit):
        found = array[~fit].flat[0].item()
        raise InvalidArgumentError(f"{expected}, found {_shown(found)}")
    return array.astype(dtype, copy=False)


def _range_words(low: int, below: int, dtype: type[np.integer[Any]]) -> str:
    """The range of :func:`_whole_numbers` as a message says it: " from 0 to 5", " of 0 or
    more" (a signed type, no bound above but its own), or nothing (a signed type's range)."""
    if np.iinfo(dtype).min < 0 and below - 1 >= np.iinfo(dtype).max:
        return "" if low <= SMALLEST_WHOLE else f" of {low} or more"
    return f" from {low} to {below - 1}"


def _exactly(value: Any, dtype: type[np.integer[Any]]) -> npt.NDArray[Any] | None:
    """``value`` (Python numbers) converted to ``dtype`` by numpy, None if it cannot be."""
    try:
        with np.errstate(invalid="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return np.asarray(value, dtype=dtype)
    except (TypeError, ValueError, OverflowError):
        return None
