"""Checking the JSON metadata of saved navigators and training checkpoints against a schema.

A schema is built from a few node kinds (:class:`Text`, :class:`Whole`, :class:`Number`,
:class:`ListOf`, :class:`Record`, :class:`AnyJson`); :meth:`Node.check` walks a
parsed document and raises :class:`mazesim.errors.PolicyFormatError` at the first value that does
not fit, naming the file, the field (``world.checkpoints[3]``), what was expected and what was
found. Every node bounds what it accepts (lengths, ranges, depth), so a checked document can be
used, compared and sized from without further care.

:func:`parse_metadata` turns the bytes of a metadata file into a document: it refuses files over
a size limit, text that is not UTF-8 or not JSON, and nesting deeper than :data:`MAX_DEPTH`,
before the schema is applied.
"""

from __future__ import annotations

import abc
import json
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from mazesim.errors import PolicyFormatError, _shown

__all__ = [
    "MAX_DEPTH",
    "MAX_METADATA_BYTES",
    "AnyJson",
    "ListOf",
    "Node",
    "Number",
    "Record",
    "Text",
    "Whole",
    "describe",
    "differing",
    "parse_metadata",
]

#: The largest metadata file read (the shipped navigator's is 17 kB).
MAX_METADATA_BYTES = 8 * 1024 * 1024
#: The deepest nesting of lists and objects accepted anywhere in a metadata file.
MAX_DEPTH = 32


def describe(value: Any) -> str:
    """A short description of a JSON value for messages: its type and a clipped rendering."""
    kinds = {dict: "an object", list: "a list", str: "a string", bool: "a boolean"}
    kind = kinds.get(type(value), "null" if value is None else "a number")
    text = repr(value) if not isinstance(value, (dict, list)) else f"of {len(value)} items"
    if len(text) > 60:
        text = text[:57] + "..."
    return f"{kind} {text}" if value is not None else kind


def differing(expected: str, found: str, width: int = 120) -> str:
    """``expected X, found Y`` for two renderings that differ, each clipped to about ``width``
    characters around the first character where they differ (marked ``...`` where cut), so a
    long message shows the difference rather than the common start of both."""
    if len(expected) <= width and len(found) <= width:
        return f"expected {expected}, found {found}"
    at = next(
        (i for i, (a, b) in enumerate(zip(expected, found)) if a != b),
        min(len(expected), len(found)),
    )
    start = max(0, at - width // 3)

    def clipped(text: str) -> str:
        head = "..." if start > 0 else ""
        tail = "..." if start + width < len(text) else ""
        return f"{head}{text[start : start + width]}{tail}"

    return (
        f"expected {clipped(expected)}, found {clipped(found)} "
        f"(they differ from character {at + 1} on)"
    )


def _depth(document: Any) -> int:
    """The nesting depth of a parsed JSON document, found without recursion."""
    deepest = 0
    pending: list[tuple[Any, int]] = [(document, 0)]
    while pending:
        value, depth = pending.pop()
        deepest = max(deepest, depth)
        if isinstance(value, dict):
            pending.extend((item, depth + 1) for item in value.values())
        elif isinstance(value, list):
            pending.extend((item, depth + 1) for item in value)
    return deepest


def parse_metadata(data: bytes, where: str) -> Any:
    """Parses a metadata file's bytes as JSON within the size and depth limits.

    Raises:
        PolicyFormatError: Too large, not UTF-8, not JSON, or nested too deeply.
    """
    if len(data) > MAX_METADATA_BYTES:
        raise PolicyFormatError(
            f"{where}: expected at most {MAX_METADATA_BYTES} bytes of metadata, found {len(data)}"
        )
    from mazesim._paths import utf8_text

    text = utf8_text(data, where, "JSON metadata", PolicyFormatError)
    try:
        document = json.loads(text)
    except RecursionError:
        raise PolicyFormatError(
            f"{where}: expected JSON nested at most {MAX_DEPTH} deep, found deeper"
        ) from None
    except ValueError as error:
        from mazesim._paths import found_kind

        metadata = ("a trained policy (policy.json)", "a training checkpoint")
        kind = found_kind(data, metadata) if data.strip() else "an empty file"
        if kind is not None:  # another of mazesim's files: say which, and where it is taken
            raise PolicyFormatError(f"{where}: expected JSON metadata, found {kind}") from None
        raise PolicyFormatError(
            f"{where}: not valid JSON (truncated or corrupt?): {error}"
        ) from None
    if _depth(document) > MAX_DEPTH:
        raise PolicyFormatError(
            f"{where}: expected JSON nested at most {MAX_DEPTH} deep, found deeper"
        )
    return document


class Node(abc.ABC):
    """One node of a schema (an abstract base: each kind of node is a subclass)."""

    @abc.abstractmethod
    def check(self, value: Any, where: str, path: str) -> None:
        """Raises :class:`PolicyFormatError` unless ``value`` fits.

        Args:
            value: The parsed JSON value.
            where: The file, for messages.
            path: The field's dotted name, for messages.
        """
        raise NotImplementedError

    @staticmethod
    def fail(where: str, path: str, expected: str, value: Any) -> PolicyFormatError:
        """The error for a value that does not fit."""
        return PolicyFormatError(f"{where}: {path}: expected {expected}, found {describe(value)}")


@dataclass(frozen=True)
class Text(Node):
    """A string, at most ``max_length`` characters, one of ``choices`` if given, or made only of
    ``alphabet``'s characters if given."""

    max_length: int = 4096
    choices: tuple[str, ...] | None = None
    alphabet: str | None = None
    length: int | None = None

    def check(self, value: Any, where: str, path: str) -> None:
        if self.choices is not None:
            if not isinstance(value, str) or value not in self.choices:
                raise self.fail(where, path, f"one of {list(self.choices)}", value)
            return
        if not isinstance(value, str) or len(value) > self.max_length:
            raise self.fail(where, path, f"a string of at most {self.max_length} characters", value)
        if self.length is not None and len(value) != self.length:
            raise self.fail(where, path, f"a string of {self.length} characters", value)
        if self.alphabet is not None and value.strip(self.alphabet):
            raise self.fail(
                where, path, f"a string of the characters {_shown(self.alphabet)}", value
            )


@dataclass(frozen=True)
class Whole(Node):
    """A whole number (not a boolean) in ``[low, high]``."""

    low: int
    high: int

    def check(self, value: Any, where: str, path: str) -> None:
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.fail(where, path, f"a whole number in [{self.low}, {self.high}]", value)
        if not self.low <= value <= self.high:
            raise self.fail(where, path, f"a whole number in [{self.low}, {self.high}]", value)


@dataclass(frozen=True)
class Number(Node):
    """A finite number (whole or not, not a boolean) in ``[low, high]``."""

    low: float
    high: float

    def check(self, value: Any, where: str, path: str) -> None:
        expected = f"a finite number in [{self.low:g}, {self.high:g}]"
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.fail(where, path, expected, value)
        # Compared as is: a whole number too large for a float is out of range, not an error.
        if isinstance(value, float) and not math.isfinite(value):
            raise self.fail(where, path, expected, value)
        if not self.low <= value <= self.high:
            raise self.fail(where, path, expected, value)


@dataclass(frozen=True)
class ListOf(Node):
    """A list of ``low`` to ``high`` items, each fitting ``item``."""

    item: Node
    low: int = 0
    high: int = 4096

    def check(self, value: Any, where: str, path: str) -> None:
        if not isinstance(value, list) or not self.low <= len(value) <= self.high:
            raise self.fail(where, path, f"a list of {self.low} to {self.high} items", value)
        for index, item in enumerate(value):
            self.item.check(item, where, f"{path}[{index}]")


@dataclass(frozen=True)
class Record(Node):
    """An object with the keys of ``fields`` (those in ``optional`` may be absent), and with
    other keys only when ``open`` (each then fitting ``others``)."""

    fields: Mapping[str, Node]
    optional: frozenset[str] = field(default_factory=frozenset)
    open: bool = False
    others: Node | None = None

    def check(self, value: Any, where: str, path: str) -> None:
        if not isinstance(value, dict):
            raise self.fail(where, path, "an object", value)
        prefix = f"{path}." if path else ""
        for key, node in self.fields.items():
            if key in value:
                node.check(value[key], where, f"{prefix}{key}")
            elif key not in self.optional:
                raise PolicyFormatError(f"{where}: expected a field {prefix}{key}, found none")
        extra = [key for key in value if key not in self.fields]
        if extra and not self.open:
            raise PolicyFormatError(
                f"{where}: {path or 'the document'}: expected only the fields "
                f"{sorted(self.fields)}, found also {sorted(extra)[:5]}"
            )
        if self.others is not None:
            for key in extra:
                self.others.check(value[key], where, f"{prefix}{key}")


@dataclass(frozen=True)
class AnyJson(Node):
    """Any JSON value (its depth is bounded by :func:`parse_metadata`)."""

    def check(self, value: Any, where: str, path: str) -> None:
        return None
