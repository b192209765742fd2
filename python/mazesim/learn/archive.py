"""Reading ``.npz`` archives of Q-tables within the shapes their metadata allows.

:func:`read_arrays` never lets a file decide how much memory is taken: it opens the archive's
directory, checks that the members are exactly the expected arrays, stored or deflated, with a
declared size that fits the expected shape; then reads each member's ``.npy`` header (shape,
dtype, order) and refuses one that differs from what is expected, or holds Python objects,
before reading exactly the bytes the expected shape needs. Anything malformed (not a zip, a
truncated member, a bad CRC, a lying header) raises :class:`mazesim.errors.PolicyFormatError`.
"""

from __future__ import annotations

import io
import struct
import tokenize
import zipfile
import zlib
from collections.abc import Mapping
from dataclasses import dataclass
from typing import IO, Any

import numpy as np
import numpy.typing as npt

from mazesim.errors import PolicyFormatError

__all__ = ["MAX_HEADER_BYTES", "ArraySpec", "read_archive", "read_arrays", "write_archive"]

#: The longest ``.npy`` header read (numpy writes 128 bytes for these tables).
MAX_HEADER_BYTES = 4096
#: What reading a malformed archive can raise, besides the checks here.
_MALFORMED = (
    zipfile.BadZipFile,
    zipfile.LargeZipFile,
    zlib.error,
    struct.error,
    EOFError,
    OSError,
    ValueError,
    KeyError,
    NotImplementedError,
    RuntimeError,
    SyntaxError,
    tokenize.TokenError,
    TypeError,
    UnicodeDecodeError,
)


@dataclass(frozen=True)
class ArraySpec:
    """The shape and dtype an archive member must have.

    Attributes:
        shape: The array's shape.
        dtype: Its dtype's name (``"float64"``, ``"int64"``, ``"uint8"``).
    """

    shape: tuple[int, ...]
    dtype: str

    @property
    def nbytes(self) -> int:
        """The size of the array's data in bytes."""
        return int(np.prod(self.shape, dtype=np.int64)) * np.dtype(self.dtype).itemsize


def _read_header(
    stream: IO[bytes], name: str, where: str
) -> tuple[tuple[int, ...], np.dtype[Any], bool]:
    version = np.lib.format.read_magic(stream)
    if version == (1, 0):
        header = np.lib.format.read_array_header_1_0(stream, max_header_size=MAX_HEADER_BYTES)
    elif version in ((2, 0), (3, 0)):
        header = np.lib.format.read_array_header_2_0(stream, max_header_size=MAX_HEADER_BYTES)
    else:
        raise PolicyFormatError(f"{where}: member {name!r}: unknown .npy version {version}")
    shape, fortran_order, dtype = header
    return tuple(shape), dtype, bool(fortran_order)


def _read_member(
    archive: zipfile.ZipFile, info: zipfile.ZipInfo, spec: ArraySpec, where: str
) -> npt.NDArray[Any]:
    name = info.filename[: -len(".npy")]
    if info.compress_type not in (zipfile.ZIP_STORED, zipfile.ZIP_DEFLATED):
        raise PolicyFormatError(
            f"{where}: member {name!r}: expected stored or deflated data, "
            f"found compression method {info.compress_type}"
        )
    largest = spec.nbytes + MAX_HEADER_BYTES + 16
    if not spec.nbytes <= info.file_size <= largest:
        raise PolicyFormatError(
            f"{where}: member {name!r}: expected {spec.nbytes} to {largest} bytes for "
            f"{spec.dtype} {list(spec.shape)}, found a declared size of {info.file_size}"
        )
    with archive.open(info) as stream:
        shape, dtype, fortran_order = _read_header(stream, name, where)
        if dtype.hasobject:
            raise PolicyFormatError(
                f"{where}: member {name!r}: expected {spec.dtype} numbers, found Python objects"
            )
        if shape != spec.shape or dtype != np.dtype(spec.dtype) or fortran_order:
            found = f"{dtype} {list(shape)}{' (Fortran order)' if fortran_order else ''}"
            raise PolicyFormatError(
                f"{where}: member {name!r}: expected {spec.dtype} {list(spec.shape)}, found {found}"
            )
        data = stream.read(spec.nbytes)
        if len(data) != spec.nbytes or stream.read(1):
            raise PolicyFormatError(
                f"{where}: member {name!r}: expected {spec.nbytes} bytes of data, "
                f"found {len(data)}{' and more' if len(data) == spec.nbytes else ''}"
            )
    return np.frombuffer(data, dtype=dtype).reshape(spec.shape).copy()


def _read_document(archive: zipfile.ZipFile, member: str, limit: int, where: str) -> bytes:
    info = archive.getinfo(member)
    if info.file_size > limit:
        raise PolicyFormatError(
            f"{where}: member {member!r}: expected at most {limit} bytes, "
            f"found a declared size of {info.file_size}"
        )
    with archive.open(info) as stream:
        data = stream.read(limit + 1)
    if len(data) > limit:
        raise PolicyFormatError(f"{where}: member {member!r}: expected at most {limit} bytes")
    return data


def read_archive(
    data: bytes,
    expected: Mapping[str, ArraySpec],
    where: str,
    documents: Mapping[str, int] | None = None,
) -> tuple[dict[str, npt.NDArray[Any]], dict[str, bytes]]:
    """Reads an ``.npz`` archive that must hold exactly ``expected`` (and ``documents``).

    Args:
        data: The archive's bytes.
        expected: Each array's name and its shape and dtype.
        where: The file, for messages.
        documents: Members that are not arrays (``"checkpoint.json"``), each with the most
            bytes it may hold.

    Returns:
        The arrays by name, and the documents' bytes by member name.

    Raises:
        PolicyFormatError: The archive is malformed or its members are not the expected ones.
    """
    documents = documents or {}
    wanted = sorted([f"{name}.npy" for name in expected] + list(documents))
    try:
        with zipfile.ZipFile(io.BytesIO(data)) as archive:
            infos = archive.infolist()
            names = sorted(info.filename for info in infos)
            if names != wanted:
                raise PolicyFormatError(
                    f"{where}: expected the members {wanted}, found {names[:8]}"
                    f"{' ...' if len(names) > 8 else ''}"
                )
            texts = {
                member: _read_document(archive, member, limit, where)
                for member, limit in documents.items()
            }
            arrays = {
                name: _read_member(archive, archive.getinfo(f"{name}.npy"), spec, where)
                for name, spec in expected.items()
            }
            return arrays, texts
    except PolicyFormatError:
        raise
    except _MALFORMED as error:
        raise PolicyFormatError(
            f"{where}: not a readable .npz file: {type(error).__name__}: {error}"
        ) from None


def read_arrays(
    data: bytes, expected: Mapping[str, ArraySpec], where: str
) -> dict[str, npt.NDArray[Any]]:
    """The arrays of an ``.npz`` archive that must hold exactly ``expected``
    (:func:`read_archive` without documents)."""
    return read_archive(data, expected, where)[0]


def write_archive(arrays: Mapping[str, npt.NDArray[Any]], documents: Mapping[str, bytes]) -> bytes:
    """An ``.npz`` archive (deflated, as :func:`numpy.savez_compressed` writes) of ``arrays``,
    with ``documents`` as further members."""
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", compression=zipfile.ZIP_DEFLATED) as archive:
        for name, array in arrays.items():
            member = io.BytesIO()
            np.lib.format.write_array(member, np.asanyarray(array), allow_pickle=False)
            archive.writestr(f"{name}.npy", member.getvalue())
        for member_name, text in documents.items():
            archive.writestr(member_name, text)
    return buffer.getvalue()
