"""Reading the TOML files of commands (sweep files, randomisation files) with their nesting bounded,
and writing TOML text back (:func:`dump_toml`).

Python's TOML reader parses nested arrays and inline tables by recursion: a file of ten thousand
``[`` ends in a ``RecursionError``. :func:`load_toml` first measures how deep the values nest, and
refuses a file nested deeper than :data:`MAX_TOML_NESTING` with an error naming the line and the
field, before the reader sees it.
"""

from __future__ import annotations

import json
import re
import sys
from collections.abc import Mapping
from typing import Any

from mazesim.errors import InvalidArgumentError, MissingDependencyError

__all__ = ["MAX_TOML_NESTING", "dump_toml", "load_toml"]

#: The deepest nesting of arrays and inline tables a command's TOML file may have: far beyond any
#: real one (a sweep's values nest two deep), far below Python's recursion limit.
MAX_TOML_NESTING = 32

#: The characters the nesting scan stops at: brackets, braces, string quotes, comments, lines.
_SPECIAL = re.compile(r"[\[\]{}\"'#\n]")

#: A quoted part of a dotted key (its dots are the name's, not the key's).
_QUOTED = re.compile(r'"[^"\\]*(?:\\.[^"\\]*)*"|\'[^\']*\'')


def _string_end(text: str, index: int) -> int:
    """Where the string starting at ``index`` (at its opening quote) ends, just past it."""
    quote = text[index]
    delimiter = quote * 3 if text.startswith(quote * 3, index) else quote
    index += len(delimiter)
    while True:
        end = text.find(delimiter, index)
        if end < 0:
            return len(text)
        if quote == "'" or not _escaped(text, end):
            return end + len(delimiter)
        index = end + 1


def _escaped(text: str, index: int) -> bool:
    """Whether the character at ``index`` follows an odd number of backslashes."""
    backslashes = 0
    while index - backslashes - 1 >= 0 and text[index - backslashes - 1] == "\\":
        backslashes += 1
    return backslashes % 2 == 1


def _key_parts(key: str) -> int:
    """How many parts a dotted key has (its dots outside quoted parts, plus one)."""
    return _QUOTED.sub("", key).count(".") + 1


def _deepest_field(text: str) -> tuple[int, str] | None:
    """The line and key of the first value nested deeper than :data:`MAX_TOML_NESTING`, or None.

    Strings and comments are skipped; a dotted key (``a.b.c = 1``, a header ``[a.b.c]``) nests
    by its parts, as the tables it makes do.
    """
    depth, key = 0, ""
    index = 0
    read_to = -1  # the end of the last top-level line whose key was read (each is read once)
    while True:
        if depth == 0 and index > read_to:
            # At the top level: a line is a header, a key = value, a comment or blank.
            line_end = text.find("\n", index)
            read_to = len(text) if line_end < 0 else line_end
            stripped = text[index:read_to].lstrip()
            if stripped.startswith("["):
                header = stripped.strip("[ \t").split("]", 1)[0]
                if _key_parts(header) > MAX_TOML_NESTING:
                    return text.count("\n", 0, index) + 1, header[:40]
                if line_end < 0:
                    return None
                index = line_end + 1
                continue
            if "=" in stripped and not stripped.startswith("#"):
                key = stripped.split("=", 1)[0].strip()
                if _key_parts(key) > MAX_TOML_NESTING:
                    return text.count("\n", 0, index) + 1, key[:40]
        found = _SPECIAL.search(text, index)
        if found is None:
            return None
        char, index = found.group(), found.start()
        if char in "\"'":
            index = _string_end(text, index)
        elif char == "#":
            line_end = text.find("\n", index)
            index = len(text) if line_end < 0 else line_end
        elif char == "\n":
            index += 1
        elif char in "[{":
            depth += 1
            if depth > MAX_TOML_NESTING:
                return text.count("\n", 0, index) + 1, key
            index += 1
        else:
            depth = max(0, depth - 1)
            index += 1
            if depth == 0:
                line_end = text.find("\n", index)
                index = len(text) if line_end < 0 else line_end + 1


def load_toml(text: str, source: str) -> dict[str, Any]:
    """The TOML document ``text``; ``source`` (a file name) names it in errors.

    Raises:
        InvalidArgumentError: Not valid TOML, or nested deeper than :data:`MAX_TOML_NESTING`
            (the message names the line and the field).
        MissingDependencyError: Python < 3.11 without the ``tomli`` package.
    """
    if sys.version_info >= (3, 11):
        import tomllib
    else:  # pragma: no cover - Python 3.9 and 3.10
        try:
            import tomli as tomllib
        except ImportError:
            raise MissingDependencyError(
                f"reading {source} on Python < 3.11 needs 'tomli': pip install tomli"
            ) from None
    deepest = _deepest_field(text)
    if deepest is not None:
        line, key = deepest
        raise InvalidArgumentError(
            f"{source}:{line}: field `{key}`: expected values nested at most "
            f"{MAX_TOML_NESTING} deep (arrays, inline tables and the parts of a dotted key), "
            "found deeper"
        )
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise InvalidArgumentError(f"{source}: not a valid TOML file: {error}") from None
    except RecursionError:
        raise InvalidArgumentError(
            f"{source}: expected values nested at most {MAX_TOML_NESTING} deep, found deeper"
        ) from None


def dump_toml(layout: Mapping[str, Any], path: str = "") -> str:
    """The TOML text of a document as :func:`load_toml` returns it (tables and arrays of tables
    as dicts and lists of dicts; strings, booleans, numbers and arrays of them): keys of values,
    then tables, then arrays of tables."""
    lines = [
        f"{key} = {_toml_value(value)}"
        for key, value in layout.items()
        if not isinstance(value, dict) and not _is_table_array(value)
    ]
    for key, value in layout.items():
        inner = f"{path}.{key}" if path else key
        if isinstance(value, dict):
            lines.append(f"\n[{inner}]\n{dump_toml(value, inner)}")
        elif _is_table_array(value):
            lines.extend(f"\n[[{inner}]]\n{dump_toml(item, inner)}" for item in value)
    return "\n".join(lines)


def _is_table_array(value: Any) -> bool:
    return isinstance(value, list) and bool(value) and all(isinstance(v, dict) for v in value)


def _toml_value(value: Any) -> str:
    """One TOML value: a string, boolean, number or array of them."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, list):
        return "[" + ", ".join(_toml_value(item) for item in value) + "]"
    return repr(value)
