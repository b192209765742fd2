"""A folder of Q-tables: an ``.npz`` archive and the JSON metadata that describes it.

:func:`write_bundle` writes the archive, then the metadata, each atomically; the metadata is
written last and records the archive's size and sha256, so a reader never takes a half-written
pair for a whole one. :func:`read_bundle` checks in an order that lets no file decide how much
memory is used: the metadata's size and depth (:func:`mazesim.learn.schema.parse_metadata`), its
format and version, its schema; then the arrays it must describe (computed by the caller from the
checked metadata), the archive's size against them, its sha256, and every member's header
(:func:`mazesim.learn.archive.read_arrays`), before any table is read.
"""

from __future__ import annotations

import errno
import hashlib
import io
import json
import os
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._atomic import atomic_file
from mazesim._paths import read_input
from mazesim.errors import MazesimIOError, PolicyFormatError
from mazesim.learn.archive import MAX_HEADER_BYTES, ArraySpec, read_arrays
from mazesim.learn.schema import (
    MAX_METADATA_BYTES,
    ListOf,
    Node,
    Record,
    Text,
    Whole,
    describe,
    differing,
    parse_metadata,
)

__all__ = [
    "FORMAT_VERSION",
    "HEX_DIGITS",
    "read_bundle",
    "read_limited",
    "sha256",
    "tables_schema",
    "write_bundle",
]

#: The version of the file formats written by this mazesim.
FORMAT_VERSION = 1
HEX_DIGITS = "0123456789abcdef"
#: The most dimensions a table may have.
_MAX_DIMENSIONS = 4
#: Bytes an archive may hold beyond its arrays' data (zip headers and directory, .npy headers).
_ARCHIVE_OVERHEAD = 4096

#: Computes the arrays an archive must hold from its checked metadata.
ArraysOf = Callable[[dict[str, Any]], Mapping[str, ArraySpec]]


def sha256(data: bytes) -> str:
    """The hex sha256 of some bytes."""
    return hashlib.sha256(data).hexdigest()


def tables_schema(npz_name: str) -> Record:
    """The schema of the metadata's ``tables`` entry, describing the archive ``npz_name``."""
    array = Record(
        {
            "shape": ListOf(Whole(0, 2**31), 0, _MAX_DIMENSIONS),
            "dtype": Text(choices=("float64", "int64")),
        }
    )
    return Record(
        {
            "file": Text(choices=(npz_name,)),
            "bytes": Whole(0, 2**40),
            "sha256": Text(length=64, alphabet=HEX_DIGITS),
            "arrays": Record({}, open=True, others=array),
        }
    )


def write_bundle(
    folder: str | os.PathLike[str],
    npz_name: str,
    json_name: str,
    arrays: dict[str, npt.NDArray[Any]],
    metadata: dict[str, Any],
) -> None:
    """Writes ``npz_name`` and ``json_name`` into ``folder`` (created if missing), atomically.

    The JSON gets a ``tables`` entry with each array's shape and dtype and the ``.npz``'s size
    and sha256; it is written after the ``.npz``.
    """
    path = Path(folder)
    path.mkdir(parents=True, exist_ok=True)
    buffer = io.BytesIO()
    savez: Any = np.savez_compressed
    savez(buffer, **arrays)
    data = buffer.getvalue()
    described = dict(metadata)
    described["tables"] = {
        "file": npz_name,
        "bytes": len(data),
        "sha256": sha256(data),
        "arrays": {
            name: {"shape": list(array.shape), "dtype": str(array.dtype)}
            for name, array in arrays.items()
        },
    }
    with atomic_file(path / npz_name) as handle:
        handle.write(data)
    with atomic_file(path / json_name) as handle:
        handle.write((json.dumps(described, indent=2) + "\n").encode("utf-8"))


def read_limited(path: Path, limit: int, what: str) -> bytes:
    """Reads a whole file of at most ``limit`` bytes.

    Raises:
        PolicyFormatError: The file is missing, not a file, unreadable or larger than ``limit``.
    """
    try:
        data = read_input(path, limit, what)
    except MazesimIOError as error:
        if error.errno == errno.ENOENT:
            raise PolicyFormatError(f"{path}: no such file (expected {what})") from None
        if error.strerror and error.strerror.endswith("found a folder"):
            raise PolicyFormatError(f"{path}: expected {what}, found a folder") from None
        raise PolicyFormatError(f"{path}: cannot be read: {error.strerror or error}") from None
    if len(data) > limit:
        raise PolicyFormatError(f"{path}: expected {what} of at most {limit} bytes, found more")
    return data


def _check_format(metadata: Any, where: str, expected_format: str) -> dict[str, Any]:
    if not isinstance(metadata, dict):
        raise PolicyFormatError(f"{where}: expected a JSON object, found {describe(metadata)}")
    found = metadata.get("format")
    if found != expected_format:
        raise PolicyFormatError(
            f"{where}: expected format {expected_format!r}, found {describe(found)}"
        )
    version = metadata.get("version")
    if isinstance(version, bool) or version != FORMAT_VERSION:
        raise PolicyFormatError(
            f"{where}: expected format version {FORMAT_VERSION}, found {describe(version)}"
        )
    return metadata


def _check_described(described: Any, expected: Mapping[str, ArraySpec], where: str) -> None:
    """The metadata's ``tables.arrays`` must name exactly the expected arrays."""
    wanted = {
        name: {"shape": list(spec.shape), "dtype": spec.dtype} for name, spec in expected.items()
    }
    if described != wanted:
        raise PolicyFormatError(
            f"{where}: tables.arrays: {differing(json.dumps(wanted), json.dumps(described))}"
        )


def read_bundle(
    folder: str | os.PathLike[str],
    npz_name: str,
    json_name: str,
    expected_format: str,
    schema: Node,
    arrays_of: ArraysOf,
) -> tuple[dict[str, npt.NDArray[Any]], dict[str, Any]]:
    """Reads and checks what :func:`write_bundle` wrote.

    Args:
        folder: The folder of the two files.
        npz_name: The archive's file name.
        json_name: The metadata's file name.
        expected_format: The metadata's ``format``.
        schema: The metadata's schema (``format``, ``version`` and ``tables`` are checked in
            any case).
        arrays_of: The arrays the archive must hold, computed from the checked metadata.

    Raises:
        PolicyFormatError: A file is missing, unreadable, truncated, corrupt or of another
            format or version, or the metadata or an array differs from what is expected.
    """
    path = Path(folder)
    meta_path = path / json_name
    npz_path = path / npz_name
    where = str(meta_path)
    text = read_limited(meta_path, MAX_METADATA_BYTES, "a saved navigator's metadata")
    metadata = _check_format(parse_metadata(text, where), where, expected_format)
    schema.check(metadata, where, "")
    Record({"tables": tables_schema(npz_name)}, open=True).check(metadata, where, "")
    described = metadata["tables"]
    expected = arrays_of(metadata)
    _check_described(described["arrays"], expected, where)
    largest = sum(spec.nbytes + MAX_HEADER_BYTES for spec in expected.values()) + _ARCHIVE_OVERHEAD
    declared = described["bytes"]
    if declared > largest:
        raise PolicyFormatError(
            f"{where}: tables.bytes: expected at most {largest} bytes for its arrays, "
            f"found {declared}"
        )
    data = read_limited(npz_path, largest, f"the tables of {meta_path.name}")
    if len(data) != declared:
        raise PolicyFormatError(
            f"{npz_path}: truncated or overwritten: expected {declared} bytes, found {len(data)}"
        )
    if sha256(data) != described["sha256"]:
        raise PolicyFormatError(
            f"{npz_path}: corrupt: its sha256 differs from the one in {meta_path.name}"
        )
    return read_arrays(data, expected, str(npz_path)), metadata
