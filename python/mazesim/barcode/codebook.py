"""Code books: which barcode each checkpoint carries, and what a reading of it means.

A checkpoint's code is read bit by bit in the order the sensor meets the bars. Crossing along the
checkpoint's yaw (arriving at the door it faces) reads the code as written; crossing the other way
(departing) reads it backwards. A valid book has no palindrome, no duplicate and no code that is
another code read backwards (docs/barcodes.md), so every reading names one checkpoint and one
direction, or nothing.
"""

from __future__ import annotations

import numbers
from collections.abc import Iterator, Mapping, Sequence
from typing import TYPE_CHECKING, Union, cast

import numpy as np

from mazesim._core import default_codes, validate_codes
from mazesim.errors import InvalidArgumentError, _shown

if TYPE_CHECKING:
    from mazesim._core import World

__all__ = ["ARRIVAL", "DEPARTURE", "CodeBook"]

#: Direction of a crossing along the checkpoint's yaw: the code reads as written.
ARRIVAL = "arrival"
#: Direction of a crossing against the checkpoint's yaw: the code reads backwards.
DEPARTURE = "departure"

CodesArgument = Union[Sequence[str], Mapping[int, str]]


class CodeBook:
    """The codes of a set of checkpoints, looked up both ways.

    Args:
        codes: Either a sequence of bit strings, where checkpoint ``k`` (1-based) gets the k-th
            code as in the core's default book and the maze generator, or a mapping from
            checkpoint id to code.

    Raises:
        InvalidArgumentError: A code is not a string of 0 and 1 of the book's length, a code is a
            palindrome, two codes are equal, one code is another read backwards, the book is
            empty, or an id is not a positive integer.

    Example:
        >>> book = CodeBook({1: "10110", 2: "11010"})
        >>> book.lookup("10110")
        (1, 'arrival')
        >>> book.lookup("01101")
        (1, 'departure')
        >>> book.reading(2, "departure")
        '01011'
        >>> book.lookup("11111") is None
        True
    """

    def __init__(self, codes: CodesArgument) -> None:
        if isinstance(codes, Mapping):
            pairs = [(self._checked_id(key), str(code)) for key, code in codes.items()]
        elif isinstance(codes, str):
            raise InvalidArgumentError(
                "expected a sequence of codes or a mapping id -> code, found the string "
                f"{_shown(codes)}"
            )
        else:
            pairs = [(index + 1, str(code)) for index, code in enumerate(codes)]
        if not pairs:
            raise InvalidArgumentError("expected at least one code in a code book, found none")
        pairs.sort()
        validate_codes([code for _, code in pairs])
        self._codes: dict[int, str] = dict(pairs)
        self._readings: dict[str, tuple[int, str]] = {}
        for checkpoint, code in pairs:
            self._readings[code] = (checkpoint, ARRIVAL)
            self._readings[code[::-1]] = (checkpoint, DEPARTURE)

    @staticmethod
    def _checked_id(value: object) -> int:
        # An int, or numpy's (np.int64(1), as ids read from an array are); no bool.
        whole = isinstance(value, numbers.Integral) and not isinstance(value, (bool, np.bool_))
        if not whole or int(value) < 1:  # type: ignore[call-overload]
            raise InvalidArgumentError(
                f"expected checkpoint ids that are positive integers, found {_shown(value)}"
            )
        return int(value)  # type: ignore[call-overload]

    @classmethod
    def default(cls) -> CodeBook:
        """The core's default five-bit book: checkpoint k gets the k-th of its 12 codes."""
        return cls(default_codes())

    @classmethod
    def from_world(cls, world: World) -> CodeBook:
        """The book of a world's checkpoints (their ids and codes).

        Raises:
            InvalidArgumentError: The world has no checkpoints.
        """
        checkpoints = world.checkpoints()
        if not checkpoints:
            raise InvalidArgumentError(
                f"world {_shown(world.name)} has no barcode checkpoints to make a code book of"
            )
        return cls({int(cast(int, cp["id"])): str(cp["code"]) for cp in checkpoints})

    @property
    def code_length(self) -> int:
        """Bits per code (5 for the report's barcodes)."""
        return len(next(iter(self._codes.values())))

    @property
    def ids(self) -> list[int]:
        """The checkpoint ids, ascending."""
        return list(self._codes)

    def code(self, checkpoint: int) -> str:
        """The code of a checkpoint, as read when arriving.

        Raises:
            InvalidArgumentError: No checkpoint has this id.
        """
        try:
            return self._codes[checkpoint]
        except KeyError:
            raise InvalidArgumentError(
                f"expected one of the checkpoint ids {self.ids}, found {_shown(checkpoint)}"
            ) from None

    def reading(self, checkpoint: int, direction: str) -> str:
        """The bits a sensor reads crossing ``checkpoint`` in ``direction``.

        Raises:
            InvalidArgumentError: Unknown checkpoint, or a direction other than "arrival" or
                "departure".
        """
        code = self.code(checkpoint)
        if direction == ARRIVAL:
            return code
        if direction == DEPARTURE:
            return code[::-1]
        raise InvalidArgumentError(
            f"expected direction {_shown(ARRIVAL)} or {_shown(DEPARTURE)}, found "
            f"{_shown(direction)}"
        )

    def lookup(self, bits: str) -> tuple[int, str] | None:
        """The (checkpoint id, direction) a reading names, or None if it names none."""
        return self._readings.get(bits)

    def signed_id(self, bits: str) -> int:
        """A reading as the simulator's signed id: +id arrival, -id departure, 0 for none."""
        found = self._readings.get(bits)
        if found is None:
            return 0
        checkpoint, direction = found
        return checkpoint if direction == ARRIVAL else -checkpoint

    def __len__(self) -> int:
        return len(self._codes)

    def __iter__(self) -> Iterator[tuple[int, str]]:
        """(checkpoint id, code) pairs in ascending id order."""
        return iter(self._codes.items())

    def __eq__(self, other: object) -> bool:
        return isinstance(other, CodeBook) and self._codes == other._codes

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return f"CodeBook({self._codes!r})"
