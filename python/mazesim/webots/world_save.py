"""A supervisor's ``worldSave``: the running world's text with some nodes' fields written anew.

Webots saves the world as it stands (reference manual, Supervisor, ``wb_supervisor_world_save``):
each node's ``translation`` and ``rotation`` where it is at that moment. The text here is the
world file's as a supervisor changed it (:mod:`mazesim.webots.scene_edits`); :func:`with_fields`
sets a node's fields in it, found by the line its node type is on, without moving any other
line, so that the lines of the nodes after it stay where they were.

The numbers are written as a person writes them: the shortest text that reads back as the same
single-precision number Webots' fields hold (0.3, not 0.30000001192092896), and a field the
node's text leaves out is added only where its value is not the field's default (a node standing
where its defaults put it is written as it was), as Webots writes only the fields that differ
from their defaults.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping, Sequence

import numpy as np

__all__ = ["with_fields"]

#: A number of a field's value, as VRML writes it.
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
#: A field name (a word not inside another).
_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


#: The value of a field the node's text may leave out, where it is its default.
_DEFAULTS: dict[str, Callable[[Sequence[float]], bool]] = {
    "translation": lambda values: all(_written(v) == "0" for v in values),
    "rotation": lambda values: len(values) == 4 and _written(values[3]) == "0",
}


def _written(value: float) -> str:
    """A number as the saved file writes it: the shortest text that reads back as the same
    single-precision number (``0`` for either zero)."""
    single = np.float32(value)
    if single == 0.0:
        return "0"
    text = str(single)
    return text[:-2] if text.endswith(".0") else text


def with_fields(text: str, line: int, fields: Mapping[str, Sequence[float]]) -> str:
    """``text`` with each of ``fields`` of the node whose type is on ``line`` (1-based) set to
    its values: replaced number by number where the node gives the field itself (not inside a
    node of one of its fields), written after the node's opening brace where it does not and
    the value is not the field's default.
    Every line stays a line: the numbers' spacing and line breaks are kept.

    A line holding no node (0, or beyond the text) leaves the text as it is.
    """
    lines = text.split("\n")
    if line < 1 or line > len(lines):
        return text
    start = sum(len(row) + 1 for row in lines[: line - 1])
    opening = _opening_brace(text, start)
    if opening < 0:
        return text
    given: dict[str, tuple[int, int]] = {}  # field -> span of its numbers in the text
    depth, at = 1, opening + 1
    while at < len(text) and depth > 0:
        char = text[at]
        if char == "#":
            at = _line_end(text, at)
            continue
        if char == '"':
            at = _string_end(text, at)
            continue
        if char in "{[":
            depth += 1
        elif char in "}]":
            depth -= 1
        elif depth == 1 and (word := _WORD.match(text, at)) and not _WORD.match(text[at - 1]):
            name = word.group()
            if name in fields and name not in given:
                given[name] = _numbers_span(text, word.end(), len(fields[name]))
            at = word.end()
            continue
        at += 1
    edited = text
    for name, (begin, end) in sorted(given.items(), key=lambda item: -item[1][0]):
        edited = edited[:begin] + _replaced(edited[begin:end], fields[name]) + edited[end:]
    missing = " ".join(
        f"{name} {' '.join(_written(v) for v in values)}"
        for name, values in fields.items()
        if name not in given and not _DEFAULTS.get(name, lambda _: False)(values)
    )
    if missing:
        edited = edited[: opening + 1] + f" {missing}" + edited[opening + 1 :]
    return edited


def _replaced(span: str, values: Sequence[float]) -> str:
    """``span`` with its first numbers replaced by ``values``, one by one, its spacing kept."""
    written = iter([_written(v) for v in values])
    return _NUMBER.sub(lambda _: next(written), span, count=len(values))


def _opening_brace(text: str, start: int) -> int:
    """The offset of the first ``{`` from ``start`` on, outside strings and comments (-1)."""
    at = start
    while at < len(text):
        if text[at] == "#":
            at = _line_end(text, at)
        elif text[at] == '"':
            at = _string_end(text, at)
        elif text[at] == "{":
            return at
        else:
            at += 1
    return -1


def _numbers_span(text: str, at: int, count: int) -> tuple[int, int]:
    """The span from ``at`` (the end of a field's name) to the end of the ``count`` numbers
    after it (fewer where fewer follow)."""
    end = at
    for _ in range(count):
        spaces = end
        while spaces < len(text) and text[spaces] in " \t\r\n,":
            spaces += 1
        number = _NUMBER.match(text, spaces)
        if number is None:
            break
        end = number.end()
    return at, end


def _line_end(text: str, at: int) -> int:
    end = text.find("\n", at)
    return len(text) if end < 0 else end


def _string_end(text: str, at: int) -> int:
    """The offset after the string that opens at ``at`` (backslash escapes skipped)."""
    at += 1
    while at < len(text) and text[at] != '"':
        at += 2 if text[at] == "\\" else 1
    return at + 1
