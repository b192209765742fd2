"""Reading the fields of a run file's JSON, each checked before it is used.

A run file may be damaged, edited by hand or written by someone else: every field read through
a :class:`RunFields` is checked for its type, its range and its length (a field per frame has one
item per frame), and a bad one raises :class:`mazesim.errors.RunFormatError` naming the file,
the field (``episodes[0].x``), what was expected and what was found. What passes can be drawn
and indexed without further care: numbers are finite, indices point into what they index.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._sizes import number_array
from mazesim.errors import RunFormatError
from mazesim.learn.schema import describe

#: The largest magnitude of a number in a run's tables: whole numbers up to it are exact in a
#: float and in a 64-bit integer, so a run written again or shown in a replay keeps them.
MAX_TABLE_NUMBER = float(2**53)

__all__ = ["RunFields"]

#: Marks a field without a default: it must be present.
_REQUIRED = object()


class RunFields:
    """Checked reads of the JSON values of one run file.

    Args:
        source: The file, named in every error.
    """

    def __init__(self, source: str) -> None:
        self.source = source

    def fail(self, field: str, expected: str, found: Any) -> RunFormatError:
        """The error for a field that is not what it should be."""
        return RunFormatError(
            f"{self.source}: {field}: expected {expected}, found {describe(found)}"
        )

    def get(self, values: Any, key: str, field: str, default: Any = _REQUIRED) -> Any:
        """``values[key]`` of a JSON object, or ``default`` when absent (required without)."""
        if not isinstance(values, dict):
            raise self.fail(
                field.rsplit(".", 1)[0] if "." in field else "the run", "an object", values
            )
        if key in values:
            return values[key]
        if default is _REQUIRED:
            raise RunFormatError(f"{self.source}: expected a field {field}, found none")
        return default

    def whole(self, value: Any, field: str, low: int, high: int) -> int:
        """A whole number in ``[low, high]``."""
        if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
            raise self.fail(field, f"a whole number in [{low}, {high}]", value)
        return value

    def number(self, value: Any, field: str, low: float, high: float) -> float:
        """A finite number in ``(low, high]`` (above ``low``, at most ``high``)."""
        expected = f"a finite number above {low:g} and at most {high:g}"
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.fail(field, expected, value)
        try:
            number = float(value)
        except OverflowError:
            raise self.fail(field, expected, value) from None
        if not math.isfinite(number) or not low < number <= high:
            raise self.fail(field, expected, value)
        return number

    def text(self, value: Any, field: str, choices: Sequence[str] | None = None) -> str:
        """A string (one of ``choices`` when given)."""
        if choices is not None and value not in choices:
            raise self.fail(field, f"one of {list(choices)}", value)
        if not isinstance(value, str):
            raise self.fail(field, "a string", value)
        return value

    def texts(self, value: Any, field: str, count: int | None = None) -> list[str]:
        """A list of strings (of ``count`` items when given)."""
        if not isinstance(value, list) or (count is not None and len(value) != count):
            size = "a list" if count is None else f"a list of {count} items"
            raise self.fail(field, f"{size} of strings", value)
        return [self.text(item, f"{field}[{index}]") for index, item in enumerate(value)]

    def table(
        self,
        value: Any,
        field: str,
        rows: int,
        columns: int | None = None,
        bound: float = MAX_TABLE_NUMBER,
    ) -> npt.NDArray[np.float64]:
        """Numbers within ``[-bound, bound]``: ``rows`` of them (``columns`` None), or ``rows``
        rows of ``columns`` each (``columns`` -1: of any one width)."""
        numbers = f"numbers in [-{bound:g}, {bound:g}]"
        if columns is None:
            expected = f"a list of {rows} {numbers}"
        else:
            width = "one width" if columns < 0 else f"{columns}"
            expected = f"a list of {rows} rows of {width} {numbers}"
        if not isinstance(value, list) or len(value) != rows:
            raise self.fail(field, expected, value)
        try:
            misfit = "a misfit, refused below by its place"
            array = number_array(value, field, nan_means=misfit, inf_means=misfit)
        except (ValueError, TypeError, OverflowError):  # InvalidArgumentError is a ValueError
            raise self._first_misfit(value, field, columns, bound) from None
        wanted_ndim = 1 if columns is None else 2
        if rows == 0 and columns is not None:
            array = array.reshape(0, max(columns, 0))
        if (
            array.ndim != wanted_ndim
            or (columns is not None and columns >= 0 and array.shape[1] != columns)
            or not np.all(np.abs(array) <= bound)
        ):
            raise self._first_misfit(value, field, columns, bound)
        return array

    def _first_misfit(
        self, value: list[Any], field: str, columns: int | None, bound: float
    ) -> RunFormatError:
        """The refusal of a table's first item that does not fit, named by its index (``x[5]``,
        ``readings[3][1]``): a list of the right length is refused for what is in it."""
        number = f"a number in [-{bound:g}, {bound:g}]"
        width = None if columns is None or columns < 0 else columns
        if columns is not None and columns < 0 and value and isinstance(value[0], list):
            width = len(value[0])
        for index, item in enumerate(value):
            place = f"{field}[{index}]"
            if columns is None:
                if not _fits(item, bound):
                    return self.fail(place, number, item)
                continue
            if not isinstance(item, list) or (width is not None and len(item) != width):
                return self.fail(place, f"a row of {width} numbers", item)
            for column, entry in enumerate(item):
                if not _fits(entry, bound):
                    return self.fail(f"{place}[{column}]", number, entry)
        return self.fail(field, f"a table of numbers in [-{bound:g}, {bound:g}]", value)

    def indices(self, value: Any, field: str, count: int) -> list[int]:
        """A list of whole numbers in ``[0, count)``."""
        if not isinstance(value, list):
            raise self.fail(field, f"a list of frames in [0, {count - 1}]", value)
        return [self.whole(item, f"{field}[{i}]", 0, count - 1) for i, item in enumerate(value)]


def _fits(item: Any, bound: float) -> bool:
    """Whether one item of a table is a finite number within ``[-bound, bound]``."""
    if isinstance(item, bool) or not isinstance(item, (int, float)):
        return False
    try:
        return math.isfinite(float(item)) and abs(float(item)) <= bound
    except OverflowError:
        return False
