"""The Q-table file format: how navigators and training checkpoints are written, read and checked.

Both are ``.npz`` archives of float64 (and int64) arrays, never pickled, with JSON metadata that
says what the arrays mean; this module is the one place that knows their bytes.

A saved navigator is a folder with two files:

- ``tables.npz``: the Q-tables, deflated (the bytes :func:`numpy.savez_compressed` writes). A
  hierarchical navigator holds ``corridor`` (4096 x 12), ``right``, ``left`` and ``forward``
  (12288 x 12: 4096 distance states times 3 phases; 73728 x 12, 18 phases, with the door
  distance) and ``higher`` (states x 4, the rows of
  :func:`mazesim.learn.higher.event_state_names`); the flat baseline holds ``flat``
  ((1 + 2 * checkpoints) * 4096 x 12).
- ``policy.json``: what the tables mean, checked on loading. ``format`` (``"mazesim-policy"``)
  and ``version`` (:data:`FORMAT_VERSION`); ``kind`` (``"hierarchical"`` or ``"flat"``);
  ``state_encoding`` (sensor order, Table 4.1 level edges in cm, the base-4 formula, the Sharp
  table the volts are inverted with); ``actions`` (codes and wheel speeds as fractions of the motor
  limit); ``control_step_ms``; ``subtasks`` (name, short code, phases and phase rule, table name);
  ``world`` (name, sha256 of :meth:`mazesim.World.to_toml`, checkpoint ids, the higher level's
  state names); ``training`` (the settings and measurements of the run); ``tables`` (each array's
  shape, and the size and sha256 of ``tables.npz``).

The archive is written first and the metadata last, each atomically, so a reader never takes a
half-written pair for a whole one (:func:`write_bundle`).

A training checkpoint is one file, ``DIR/checkpoint.npz``: the lower-level tables (``q``), their
update counts (``visits``) and a ``checkpoint.json`` member with the run's settings, the round to
continue from, the rounds' summaries and the seconds spent, switched in with one atomic rename
(:func:`mazesim._atomic.atomic_file`). Checkpoints of mazesim 0.1 (``checkpoint.npz`` with the
tables and a separate ``checkpoint.json``, a bundle like a navigator's) are still read; the next
checkpoint replaces them with the one-file form.

Reading lets no file decide how much memory is used: the metadata's size and depth
(:func:`mazesim.learn.schema.parse_metadata`), its format and version, its schema; then the arrays
it must describe, the archive's size against them, its sha256, and every member's ``.npy`` header
(shape, dtype, order; no Python objects), before exactly the bytes of the expected shapes are read
(:func:`read_archive`). :func:`load_policy` also checks the state and action encoding against this
mazesim's, and that the tables are finite. Anything else raises
:class:`mazesim.errors.PolicyFormatError` naming the file, the field and the reason: a file
missing, truncated, corrupt (its sha256 differs), malformed, of another format or version, made
for another state or action encoding, or with tables of the wrong shape or non-finite values.
"""

from __future__ import annotations

import contextlib
import errno
import hashlib
import io
import json
import os
import struct
import tokenize
import zipfile
import zlib
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Any

import numpy as np
import numpy.typing as npt

from mazesim._atomic import atomic_file, remove_stale_temporaries
from mazesim._paths import (
    file_described,
    make_output_folder,
    read_input,
    windows_separators,
)
from mazesim.actions import ACTION_CODES, WHEEL_SPEED_FRACTIONS
from mazesim.errors import (
    InvalidArgumentError,
    MazesimIOError,
    PolicyFormatError,
    _closest_name,
    _shown,
)
from mazesim.learn.discretise import LEVEL_EDGES_CM, NUM_STATES, SENSOR_ORDER, SHARP_TABLE
from mazesim.learn.higher import MAX_CHECKPOINT_ID, event_state_names
from mazesim.learn.lower import LowerTables, lower_table_shape
from mazesim.learn.schema import (
    MAX_METADATA_BYTES,
    AnyJson,
    ListOf,
    Node,
    Number,
    Record,
    Text,
    Whole,
    describe,
    differing,
    parse_metadata,
)
from mazesim.learn.subtasks import (
    CONTROL_STEP_MS,
    DISTANCE_EDGES,
    DISTANCE_PHASES,
    FORWARD_PHASE_ANGLE,
    SUBTASK_ACTIONS,
    SUBTASK_CODES,
    SUBTASK_NAMES,
    TURN_PHASE_ANGLES,
    door_distance_of,
    phase_counts,
)
from mazesim.learn.trained_policy import (
    SHIPPED_NAVIGATORS,
    TrainedPolicy,
    navigator_folder,
    shipped_policy_dir,
)

__all__ = [
    "CHECKPOINT_FILE",
    "CHECKPOINT_FORMAT",
    "FORMAT",
    "FORMAT_VERSION",
    "METADATA_FILE",
    "SHIPPED_NAVIGATORS",
    "TABLES_FILE",
    "ArraySpec",
    "Checkpoint",
    "TrainedPolicy",
    "checkpoint_exists",
    "encoding_metadata",
    "load_policy",
    "navigator_folder",
    "policy_arrays",
    "policy_schema",
    "read_archive",
    "read_bundle",
    "read_checkpoint_file",
    "remove_checkpoint_leftovers",
    "save_policy",
    "sha256",
    "shipped_policy_dir",
    "write_archive",
    "write_bundle",
    "write_checkpoint",
]

#: The version of the file formats written by this mazesim.
FORMAT_VERSION = 1
FORMAT = "mazesim-policy"
METADATA_FILE = "policy.json"
TABLES_FILE = "tables.npz"
CHECKPOINT_FORMAT = "mazesim-training-checkpoint"
CHECKPOINT_FILE = "checkpoint.npz"
#: The metadata member inside the checkpoint (and the separate file of mazesim 0.1).
CHECKPOINT_MEMBER = "checkpoint.json"
#: The lower-level table of each sub-task, by number.
SUBTASK_TABLES = ("corridor", "right", "left", "forward")
KINDS = ("hierarchical", "flat")
HEX_DIGITS = "0123456789abcdef"
#: The most checkpoints a navigator's world may have (its largest checkpoint id is
#: :data:`mazesim.learn.higher.MAX_CHECKPOINT_ID`).
MAX_CHECKPOINTS = 1024
#: The most lower-level rounds a run may have.
MAX_ROUNDS = 10**9
#: The most dimensions a table may have.
_MAX_DIMENSIONS = 4
#: Bytes an archive may hold beyond its arrays' data (zip headers and directory, .npy headers).
_ARCHIVE_OVERHEAD = 4096
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
        raise PolicyFormatError(f"{where}: member {_shown(name)}: unknown .npy version {version}")
    shape, fortran_order, dtype = header
    return tuple(shape), dtype, bool(fortran_order)


def _read_member(
    archive: zipfile.ZipFile, info: zipfile.ZipInfo, spec: ArraySpec, where: str
) -> npt.NDArray[Any]:
    name = info.filename[: -len(".npy")]
    if info.compress_type not in (zipfile.ZIP_STORED, zipfile.ZIP_DEFLATED):
        raise PolicyFormatError(
            f"{where}: member {_shown(name)}: expected stored or deflated data, "
            f"found compression method {info.compress_type}"
        )
    largest = spec.nbytes + MAX_HEADER_BYTES + 16
    if not spec.nbytes <= info.file_size <= largest:
        raise PolicyFormatError(
            f"{where}: member {_shown(name)}: expected {spec.nbytes} to {largest} bytes for "
            f"{spec.dtype} {list(spec.shape)}, found a declared size of {info.file_size}"
        )
    with archive.open(info) as stream:
        shape, dtype, fortran_order = _read_header(stream, name, where)
        if dtype.hasobject:
            raise PolicyFormatError(
                f"{where}: member {_shown(name)}: expected {spec.dtype} numbers, found Python "
                "objects"
            )
        if shape != spec.shape or dtype != np.dtype(spec.dtype) or fortran_order:
            found = f"{dtype} {list(shape)}{' (Fortran order)' if fortran_order else ''}"
            raise PolicyFormatError(
                f"{where}: member {_shown(name)}: expected {spec.dtype} {list(spec.shape)}, "
                f"found {found}"
            )
        data = stream.read(spec.nbytes)
        if len(data) != spec.nbytes or stream.read(1):
            raise PolicyFormatError(
                f"{where}: member {_shown(name)}: expected {spec.nbytes} bytes of data, "
                f"found {len(data)}{' and more' if len(data) == spec.nbytes else ''}"
            )
    return np.frombuffer(data, dtype=dtype).reshape(spec.shape).copy()


def _read_document(archive: zipfile.ZipFile, member: str, limit: int, where: str) -> bytes:
    info = archive.getinfo(member)
    if info.file_size > limit:
        raise PolicyFormatError(
            f"{where}: member {_shown(member)}: expected at most {limit} bytes, "
            f"found a declared size of {info.file_size}"
        )
    with archive.open(info) as stream:
        data = stream.read(limit + 1)
    if len(data) > limit:
        raise PolicyFormatError(f"{where}: member {_shown(member)}: expected at most {limit} bytes")
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


def write_archive(
    arrays: Mapping[str, npt.ArrayLike],
    documents: Mapping[str, bytes] | None = None,
    compression: int = zipfile.ZIP_DEFLATED,
) -> bytes:
    """An ``.npz`` archive of ``arrays`` (C order, no Python objects), with ``documents`` as
    further members, the same bytes for the same arrays: unlike :func:`numpy.savez`, every
    member carries a fixed date.

    Args:
        arrays: The arrays by name.
        documents: Members that are not arrays, by member name.
        compression: :data:`zipfile.ZIP_DEFLATED` (checkpoints) or :data:`zipfile.ZIP_STORED`.

    Raises:
        InvalidArgumentError: An array holds Python objects.
    """
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as archive:

        def member(name: str) -> IO[bytes]:
            info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = compression
            return archive.open(info, "w", force_zip64=True)

        for name, values in arrays.items():
            array = np.ascontiguousarray(values)
            if array.dtype.hasobject:
                raise InvalidArgumentError(f"table {_shown(name)}: expected numbers, found objects")
            with member(f"{name}.npy") as handle:
                np.lib.format.write_array(handle, array, allow_pickle=False)
        for member_name, text in (documents or {}).items():
            with member(member_name) as handle:
                handle.write(text)
    return buffer.getvalue()


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

    The ``.npz`` is deflated (the bytes :func:`numpy.savez_compressed` writes); the JSON gets a
    ``tables`` entry with each array's shape and dtype and the ``.npz``'s size and sha256, and
    is written after the ``.npz``.
    """
    path = Path(folder)
    make_output_folder(path)
    data = write_archive(arrays)
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
            f"{where}: expected format {_shown(expected_format)}, found {describe(found)}"
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
    return read_archive(data, expected, str(npz_path))[0], metadata


def encoding_metadata(door_distance: bool = False) -> dict[str, Any]:
    """The state and action encoding this version of mazesim uses, as saved and checked; with
    ``door_distance`` the door sub-tasks' phases count the distance driven too
    (:data:`mazesim.learn.subtasks.DISTANCE_PHASES`)."""
    phase_rules = [
        "none",
        f"heading turned towards the side: < {np.degrees(TURN_PHASE_ANGLES[0]):.0f} deg -> 0, "
        f"< {np.degrees(TURN_PHASE_ANGLES[1]):.0f} deg -> 1, else 2",
        f"heading turned towards the side: < {np.degrees(TURN_PHASE_ANGLES[0]):.0f} deg -> 0, "
        f"< {np.degrees(TURN_PHASE_ANGLES[1]):.0f} deg -> 1, else 2",
        f"heading change: < -{np.degrees(FORWARD_PHASE_ANGLE):.0f} deg -> 0, "
        f"> {np.degrees(FORWARD_PHASE_ANGLE):.0f} deg -> 2, else 1",
    ]
    if door_distance:
        edges = ", ".join(
            f"< {100 * edge:.0f} cm -> {place}" for place, edge in enumerate(DISTANCE_EDGES)
        )
        phase_rules[1:] = [
            f"({rule}) + 3 * (metres ahead of the start along its heading: {edges}, "
            f"else {len(DISTANCE_EDGES)})"
            for rule in phase_rules[1:]
        ]
    phases = phase_counts(door_distance)
    return {
        "state_encoding": {
            "sensors": list(SENSOR_ORDER),
            "level_edges_cm": list(LEVEL_EDGES_CM),
            "levels": len(LEVEL_EDGES_CM) + 1,
            "formula": "state = sum(level[i] * 4**i), i = place in sensors",
            "states": NUM_STATES,
            "volts_to_cm": "inverse of sharp_table, piecewise linear, clamped",
            "sharp_table": [list(row) for row in SHARP_TABLE],
        },
        "actions": [
            {"code": code, "left": float(left), "right": float(right)}
            for code, (left, right) in zip(ACTION_CODES, WHEEL_SPEED_FRACTIONS)
        ],
        "control_step_ms": CONTROL_STEP_MS,
        "subtasks": [
            {
                "number": number,
                "name": SUBTASK_NAMES[number],
                "code": SUBTASK_CODES[number],
                "phases": phases[number],
                "phase_rule": phase_rules[number],
                "table": SUBTASK_TABLES[number],
                "state": "distance_state + 4096 * phase",
                "actions": [
                    code for code, allowed in zip(ACTION_CODES, SUBTASK_ACTIONS[number]) if allowed
                ],
            }
            for number in range(len(SUBTASK_NAMES))
        ],
    }


def save_policy(policy: TrainedPolicy, folder: str | os.PathLike[str]) -> None:
    """Writes a navigator into ``folder`` as ``tables.npz`` and ``policy.json``.

    Raises:
        PolicyFormatError: The navigator holds what :func:`load_policy` would refuse (a NaN
            in a table, a checkpoint id below 1): nothing is written.
    """
    arrays: dict[str, npt.NDArray[Any]] = {}
    door_distance = False
    if policy.kind == "hierarchical":
        if policy.lower_q is None or policy.higher_q is None:
            raise PolicyFormatError("a hierarchical navigator needs lower and higher tables")
        try:
            door_distance = door_distance_of(int(policy.lower_q.shape[1]))
        except InvalidArgumentError as error:
            raise PolicyFormatError(str(error)) from None
        for number, name in enumerate(SUBTASK_TABLES):
            rows = phase_counts(door_distance)[number] * NUM_STATES
            arrays[name] = np.ascontiguousarray(policy.lower_q[number, :rows], dtype=np.float64)
        arrays["higher"] = np.asarray(policy.higher_q, dtype=np.float64)
    elif policy.kind == "flat":
        if policy.flat_q is None:
            raise PolicyFormatError("a flat navigator needs its table")
        arrays["flat"] = np.asarray(policy.flat_q, dtype=np.float64)
    else:
        raise PolicyFormatError(f"expected a kind in {KINDS}, found {_shown(policy.kind)}")
    metadata: dict[str, Any] = {"format": FORMAT, "version": FORMAT_VERSION, "kind": policy.kind}
    metadata.update(encoding_metadata(door_distance))
    metadata["world"] = {
        "name": policy.world_name,
        "sha256": policy.world_sha256,
        "checkpoints": list(policy.checkpoint_ids),
        "higher_states": event_state_names(policy.checkpoint_ids),
    }
    if policy.world_file is not None:
        metadata["world"]["file"] = policy.world_file
    metadata["training"] = policy.training
    _readable(arrays, metadata, Path(os.fspath(folder)))
    write_bundle(folder, TABLES_FILE, METADATA_FILE, arrays, metadata)


def _readable(arrays: dict[str, npt.NDArray[Any]], metadata: dict[str, Any], where: Path) -> None:
    """Refuses, before anything is written, a navigator :func:`load_policy` would refuse: the
    loader's own checks of its tables (finite) and of its world's entries (checkpoint ids, the
    higher states), so that a save never leaves a folder its loader cannot read.

    Raises:
        PolicyFormatError: What the loader would say of the saved folder.
    """
    for name, table in arrays.items():
        _finite(table, name, where)
    world_schema = policy_schema().fields["world"]
    world_schema.check(json.loads(json.dumps(metadata["world"])), str(where), "world")
    _check_world(metadata["world"], where)


def policy_schema() -> Record:
    """The schema of ``policy.json`` (the encoding entries are compared with this mazesim's)."""
    return Record(
        {
            "format": Text(choices=(FORMAT,)),
            "version": Whole(FORMAT_VERSION, FORMAT_VERSION),
            "kind": Text(choices=KINDS),
            "state_encoding": AnyJson(),
            "actions": AnyJson(),
            "control_step_ms": AnyJson(),
            "subtasks": AnyJson(),
            "world": Record(
                {
                    "name": Text(max_length=256),
                    "sha256": Text(length=64, alphabet=HEX_DIGITS),
                    "checkpoints": ListOf(Whole(1, MAX_CHECKPOINT_ID), 0, MAX_CHECKPOINTS),
                    "higher_states": ListOf(Text(max_length=16), 0, 2 * MAX_CHECKPOINTS),
                    "file": Text(max_length=4096),
                },
                optional=frozenset({"file"}),
            ),
            "training": Record({}, open=True, others=AnyJson()),
            "tables": tables_schema(TABLES_FILE),
        }
    )


def _encoding_keys(metadata: dict[str, Any], expected: dict[str, Any]) -> str | None:
    """The first encoding entry of ``metadata`` that differs from ``expected``, if any."""
    for key in ("state_encoding", "actions", "control_step_ms", "subtasks"):
        if metadata.get(key) != expected[key]:
            return key
    return None


def _check_encoding(metadata: dict[str, Any], where: Path) -> bool:
    """Checks the encoding against this mazesim's, with heading phases or with the distance;
    returns whether the tables count the distance (``door_distance``)."""
    plain = encoding_metadata()
    if _encoding_keys(metadata, encoding_metadata(True)) is None:
        return True
    key = _encoding_keys(metadata, plain)
    if key is not None:
        raise PolicyFormatError(
            f"{where}: made for another {key.replace('_', ' ')} than this mazesim uses "
            f"({differing(json.dumps(plain[key]), json.dumps(metadata.get(key)))})"
        )
    return False


def _check_world(world: dict[str, Any], where: Path) -> None:
    checkpoints = world["checkpoints"]
    if len(set(checkpoints)) != len(checkpoints):
        raise PolicyFormatError(
            f"{where}: world.checkpoints: expected distinct ids, found {checkpoints[:20]}"
        )
    if world["higher_states"] != event_state_names(checkpoints):
        expected, found = event_state_names(checkpoints), world["higher_states"]
        raise PolicyFormatError(
            f"{where}: world.higher_states: {differing(json.dumps(expected), json.dumps(found))}"
        )


def policy_arrays(metadata: dict[str, Any]) -> dict[str, ArraySpec]:
    """The tables a navigator's archive must hold, from its checked metadata."""
    actions = len(ACTION_CODES)
    checkpoints = len(metadata["world"]["checkpoints"])
    if metadata["kind"] == "flat":
        return {"flat": ArraySpec(((1 + 2 * checkpoints) * NUM_STATES, actions), "float64")}
    phases = [int(subtask["phases"]) for subtask in metadata["subtasks"]]
    arrays = {
        name: ArraySpec((phases[number] * NUM_STATES, actions), "float64")
        for number, name in enumerate(SUBTASK_TABLES)
    }
    arrays["higher"] = ArraySpec((2 * checkpoints, 4), "float64")
    return arrays


def _checked_policy_arrays(where: Path) -> Any:
    """:func:`policy_arrays` after the checks that need this mazesim's encoding and world rules."""

    def arrays_of(metadata: dict[str, Any]) -> dict[str, ArraySpec]:
        _check_encoding(metadata, where)
        _check_world(metadata["world"], where)
        return policy_arrays(metadata)

    return arrays_of


def _closest_navigator(path: Path) -> str | None:
    """The navigator a missing ``path`` likely meant: the closest of the navigators' folders
    beside it (holding a navigator or a run's checkpoint) and, for a bare name, of the shipped
    ones."""
    parent = path.parent
    try:
        beside = [
            entry.name
            for entry in sorted(parent.iterdir())
            if entry.is_dir() and ((entry / METADATA_FILE).exists() or checkpoint_exists(entry))
        ][:MOST_NAVIGATORS_COMPARED]
    except OSError:
        beside = []
    shipped = list(SHIPPED_NAVIGATORS) if path.name == str(path) else []
    closest = _closest_name(path.name, [*beside, *shipped])
    if closest is None or closest in shipped:
        return closest
    return str(parent / closest)


#: The most folders beside a missing navigator's that are compared with its name.
MOST_NAVIGATORS_COMPARED = 1000


def load_policy(folder: str | os.PathLike[str] | None = None) -> TrainedPolicy:
    """Loads a navigator saved by :func:`save_policy` (by default the one shipped for seed-maze;
    ``"randomised"``: the one trained with domain randomisation, see :func:`navigator_folder`).

    Raises:
        PolicyFormatError: The folder does not hold a usable navigator (the message says why).
    """
    path = navigator_folder(folder)
    meta_path = path / METADATA_FILE
    if path.exists() and not path.is_dir():
        raise PolicyFormatError(
            f"{path}: expected a navigator's folder (the folder 'mazesim train --out DIR' "
            f"writes), found {file_described(path)}"
        )
    if not path.exists():
        where = "" if path.is_absolute() else f" in {os.getcwd()}"
        shipped = ", ".join(repr(name) for name in SHIPPED_NAVIGATORS)
        windows = windows_separators(str(path), os.getcwd())
        meant = None if windows else _closest_navigator(path)
        raise PolicyFormatError(
            f"{meta_path}: no such file: there is no folder {_shown(str(path))}{where}"
            f"{windows}; a navigator is "
            f"the folder 'mazesim train --out DIR' writes, or a shipped one ({shipped}; without "
            "--policy, the seed-maze navigator)"
            + (f"; did you mean {_shown(meant)}?" if meant else "")
        )
    if not meta_path.exists() and checkpoint_exists(path):
        raise PolicyFormatError(
            f"{meta_path}: no such file: {_shown(str(path))} holds the checkpoint of a "
            "'mazesim train' "
            "that has not finished (interrupted, or still running): run that command again with "
            "--resume to finish it, then evaluate it"
        )
    arrays, metadata = read_bundle(
        path,
        TABLES_FILE,
        METADATA_FILE,
        FORMAT,
        schema=policy_schema(),
        arrays_of=_checked_policy_arrays(meta_path),
    )
    kind = metadata["kind"]
    world = metadata["world"]
    checkpoints = [int(c) for c in world["checkpoints"]]
    policy = TrainedPolicy(
        kind=str(kind),
        world_name=str(world["name"]),
        world_sha256=str(world["sha256"]),
        checkpoint_ids=checkpoints,
        world_file=str(world["file"]) if "file" in world else None,
        training=dict(metadata["training"]),
        source=str(path),
    )
    npz_path = path / TABLES_FILE
    lower_settings = policy.training.get("lower")
    if isinstance(lower_settings, dict) and "hold_heading" in lower_settings:
        if not isinstance(lower_settings["hold_heading"], bool):
            raise PolicyFormatError(
                f"{meta_path}: expected training.lower.hold_heading to be true or false, "
                f"found {_shown(lower_settings['hold_heading'])}"
            )
    if kind == "hierarchical":
        # The encoding was checked against both (``arrays_of``): its phases say which it is.
        door_distance = tuple(s["phases"] for s in metadata["subtasks"]) == DISTANCE_PHASES
        lower = np.zeros(lower_table_shape(door_distance))
        for number, name in enumerate(SUBTASK_TABLES):
            rows = phase_counts(door_distance)[number] * NUM_STATES
            lower[number, :rows] = _finite(arrays[name], name, npz_path)
        policy.lower_q = lower
        policy.higher_q = _finite(arrays["higher"], "higher", npz_path)
    else:
        policy.flat_q = _finite(arrays["flat"], "flat", npz_path)
    return policy


def _finite(table: npt.NDArray[Any], name: str, where: Path) -> npt.NDArray[np.float64]:
    """A table of the archive (its shape and dtype checked by :func:`read_archive`), if finite."""
    if not np.all(np.isfinite(table)):
        raise PolicyFormatError(f"{where}: table {_shown(name)} holds NaN or infinite values")
    return table


@dataclass
class Checkpoint:
    """What a checkpoint holds.

    Attributes:
        tables: The lower-level tables and their update counts.
        next_round: The lower-level round to continue from.
        history: One summary per round done.
        lower_seconds: Wall-clock seconds spent on the lower level so far.
    """

    tables: LowerTables
    next_round: int
    history: list[dict[str, Any]]
    lower_seconds: float


def _checkpoint_arrays(door_distance: bool = False) -> dict[str, ArraySpec]:
    shape = lower_table_shape(door_distance)
    return {"q": ArraySpec(shape, "float64"), "visits": ArraySpec(shape, "int64")}


def _checkpoint_schema() -> Record:
    return Record(
        {
            "format": Text(choices=(CHECKPOINT_FORMAT,)),
            "version": Whole(FORMAT_VERSION, FORMAT_VERSION),
            "settings": Record({}, open=True, others=AnyJson()),
            "next_round": Whole(0, MAX_ROUNDS),
            "history": ListOf(Record({}, open=True, others=AnyJson()), 0, MAX_ROUNDS),
            "lower_seconds": Number(0.0, 1e12),
            # Only in a mazesim 0.1 checkpoint's separate file (checked by read_bundle).
            "tables": AnyJson(),
        },
        optional=frozenset({"tables"}),
    )


def checkpoint_exists(folder: Path) -> bool:
    """Whether ``folder`` holds a checkpoint (of this or an older mazesim)."""
    return (folder / CHECKPOINT_FILE).exists() or (folder / CHECKPOINT_MEMBER).exists()


def remove_checkpoint_leftovers(folder: Path) -> None:
    """Removes the temporary files an interrupted checkpoint write left in ``folder``."""
    remove_stale_temporaries(folder / CHECKPOINT_FILE)
    remove_stale_temporaries(folder / CHECKPOINT_MEMBER)


def write_checkpoint(folder: Path, settings: dict[str, Any], checkpoint: Checkpoint) -> None:
    """Writes ``folder/checkpoint.npz`` in one atomic step (the folder must exist).

    Args:
        folder: The run's folder.
        settings: The run's settings that must match to continue it.
        checkpoint: What to save.
    """
    metadata = {
        "format": CHECKPOINT_FORMAT,
        "version": FORMAT_VERSION,
        "settings": settings,
        "next_round": checkpoint.next_round,
        "history": checkpoint.history,
        "lower_seconds": checkpoint.lower_seconds,
    }
    data = write_archive(
        {"q": checkpoint.tables.q, "visits": checkpoint.tables.visits},
        {CHECKPOINT_MEMBER: (json.dumps(metadata, indent=1) + "\n").encode("utf-8")},
    )
    with atomic_file(folder / CHECKPOINT_FILE) as handle:
        handle.write(data)
    # A checkpoint of mazesim 0.1 kept its metadata beside it; the new file supersedes it.
    with contextlib.suppress(FileNotFoundError):
        (folder / CHECKPOINT_MEMBER).unlink()


def _holds_metadata(data: bytes) -> bool:
    """Whether an archive has the metadata member (False for a mazesim 0.1 checkpoint)."""
    try:
        with zipfile.ZipFile(io.BytesIO(data)) as archive:
            return CHECKPOINT_MEMBER in archive.namelist()
    except (zipfile.BadZipFile, OSError, ValueError, EOFError):
        return True  # malformed: read as a one-file checkpoint, which says what is wrong


def _read_one_file(
    path: Path, door_distance: bool = False
) -> tuple[dict[str, Any], dict[str, Any]] | None:
    """The arrays and metadata of a one-file checkpoint, or None for a mazesim 0.1 one."""
    arrays = _checkpoint_arrays(door_distance)
    largest = sum(spec.nbytes + MAX_HEADER_BYTES for spec in arrays.values()) + MAX_METADATA_BYTES
    data = read_limited(path, largest, "a training checkpoint")
    if (path.parent / CHECKPOINT_MEMBER).exists() and not _holds_metadata(data):
        return None
    tables, documents = read_archive(
        data, arrays, str(path), documents={CHECKPOINT_MEMBER: MAX_METADATA_BYTES}
    )
    where = f"{path}:{CHECKPOINT_MEMBER}"
    metadata = parse_metadata(documents[CHECKPOINT_MEMBER], where)
    _checkpoint_schema().check(metadata, where, "")
    return tables, metadata


def read_checkpoint_file(folder: Path, door_distance: bool) -> tuple[Checkpoint, dict[str, Any]]:
    """The checkpoint in ``folder`` and the settings of its run, checked against the tables of a
    run with or without the door distance's phases (``mazesim train --door-distance``).

    Raises:
        PolicyFormatError: No checkpoint, or a malformed one (the message says why).
    """
    path = folder / CHECKPOINT_FILE
    found = _read_one_file(path, door_distance) if path.exists() else None
    if found is None:
        found = read_bundle(
            folder,
            CHECKPOINT_FILE,
            CHECKPOINT_MEMBER,
            CHECKPOINT_FORMAT,
            schema=_checkpoint_schema(),
            arrays_of=lambda metadata: _checkpoint_arrays(door_distance),
        )
    arrays, metadata = found
    if not np.all(np.isfinite(arrays["q"])) or np.any(arrays["visits"] < 0):
        raise PolicyFormatError(
            f"{path}: expected finite tables and counts of at least 0, found others"
        )
    checkpoint = Checkpoint(
        tables=LowerTables(arrays["q"], arrays["visits"]),
        next_round=int(metadata["next_round"]),
        history=list(metadata["history"]),
        lower_seconds=float(metadata["lower_seconds"]),
    )
    return checkpoint, metadata["settings"]
