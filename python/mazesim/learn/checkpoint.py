"""The checkpoint of a training run: complete or absent at every instant.

A checkpoint is one file, ``DIR/checkpoint.npz``: the lower-level tables (``q``), their update
counts (``visits``) and a ``checkpoint.json`` member with the run's settings, the round to
continue from, the rounds' summaries and the seconds spent. It is written to a temporary file in
``DIR`` and switched in with one atomic rename (:func:`mazesim._atomic.atomic_file`), so at every
instant ``DIR/checkpoint.npz`` is either the previous whole checkpoint or the new whole one; a
crash leaves at most a temporary file, removed on the next run.

Checkpoints of mazesim 0.1 (``checkpoint.npz`` with the tables and a separate
``checkpoint.json``) are still read; the next checkpoint replaces them with the one-file form.

:class:`RunFolder` is a training run's folder, which :func:`mazesim.learn.train.train` writes
through (its ``checkpoint`` argument): the checkpoint to continue from with ``--resume``, the
checkpoints as the run goes, and the navigator at the end
(:func:`mazesim.learn.tables.save_policy`). Training itself writes nothing; ``mazesim train``
hands it a folder.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import zipfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from mazesim._atomic import atomic_file, remove_stale_temporaries
from mazesim.errors import InvalidArgumentError, PolicyFormatError
from mazesim.learn.archive import MAX_HEADER_BYTES, ArraySpec, read_archive, write_archive
from mazesim.learn.bundle import FORMAT_VERSION, read_bundle, read_limited
from mazesim.learn.lower import LowerTables, lower_table_shape
from mazesim.learn.schema import (
    MAX_METADATA_BYTES,
    AnyJson,
    ListOf,
    Number,
    Record,
    Text,
    Whole,
    differing,
    parse_metadata,
)
from mazesim.learn.tables import TrainedPolicy, save_policy

__all__ = [
    "CHECKPOINT_FILE",
    "CHECKPOINT_FORMAT",
    "Checkpoint",
    "RunFolder",
    "checkpoint_exists",
    "read_checkpoint",
    "remove_checkpoint_leftovers",
    "write_checkpoint",
]

CHECKPOINT_FORMAT = "mazesim-training-checkpoint"
CHECKPOINT_FILE = "checkpoint.npz"
#: The metadata member inside the checkpoint (and the separate file of mazesim 0.1).
METADATA_MEMBER = "checkpoint.json"
#: The most lower-level rounds a run may have.
MAX_ROUNDS = 10**9


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


def _arrays(door_distance: bool = False) -> dict[str, ArraySpec]:
    shape = lower_table_shape(door_distance)
    return {"q": ArraySpec(shape, "float64"), "visits": ArraySpec(shape, "int64")}


def _schema() -> Record:
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
    return (folder / CHECKPOINT_FILE).exists() or (folder / METADATA_MEMBER).exists()


def remove_checkpoint_leftovers(folder: Path) -> None:
    """Removes the temporary files an interrupted checkpoint write left in ``folder``."""
    remove_stale_temporaries(folder / CHECKPOINT_FILE)
    remove_stale_temporaries(folder / METADATA_MEMBER)


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
        {METADATA_MEMBER: (json.dumps(metadata, indent=1) + "\n").encode("utf-8")},
    )
    with atomic_file(folder / CHECKPOINT_FILE) as handle:
        handle.write(data)
    # A checkpoint of mazesim 0.1 kept its metadata beside it; the new file supersedes it.
    with contextlib.suppress(FileNotFoundError):
        (folder / METADATA_MEMBER).unlink()


def _holds_metadata(data: bytes) -> bool:
    """Whether an archive has the metadata member (False for a mazesim 0.1 checkpoint)."""
    try:
        with zipfile.ZipFile(io.BytesIO(data)) as archive:
            return METADATA_MEMBER in archive.namelist()
    except (zipfile.BadZipFile, OSError, ValueError, EOFError):
        return True  # malformed: read as a one-file checkpoint, which says what is wrong


def _read_one_file(
    path: Path, door_distance: bool = False
) -> tuple[dict[str, Any], dict[str, Any]] | None:
    """The arrays and metadata of a one-file checkpoint, or None for a mazesim 0.1 one."""
    arrays = _arrays(door_distance)
    largest = sum(spec.nbytes + MAX_HEADER_BYTES for spec in arrays.values()) + MAX_METADATA_BYTES
    data = read_limited(path, largest, "a training checkpoint")
    if (path.parent / METADATA_MEMBER).exists() and not _holds_metadata(data):
        return None
    tables, documents = read_archive(
        data, arrays, str(path), documents={METADATA_MEMBER: MAX_METADATA_BYTES}
    )
    where = f"{path}:{METADATA_MEMBER}"
    metadata = parse_metadata(documents[METADATA_MEMBER], where)
    _schema().check(metadata, where, "")
    return tables, metadata


def _read_tables(folder: Path, door_distance: bool) -> tuple[dict[str, Any], dict[str, Any]]:
    """The checkpoint's arrays (tables with or without distance phases) and metadata."""
    path = folder / CHECKPOINT_FILE
    found = _read_one_file(path, door_distance) if path.exists() else None
    if found is None:
        found = read_bundle(
            folder,
            CHECKPOINT_FILE,
            METADATA_MEMBER,
            CHECKPOINT_FORMAT,
            schema=_schema(),
            arrays_of=lambda metadata: _arrays(door_distance),
        )
    return found


def _read_tables_or_none(
    folder: Path, door_distance: bool
) -> tuple[dict[str, Any], dict[str, Any]] | None:
    try:
        return _read_tables(folder, door_distance)
    except PolicyFormatError:
        return None


def _settings_difference(asked: dict[str, Any], saved: dict[str, Any]) -> str:
    """The settings that differ between a run asked for and a checkpoint's, each as
    ``name: expected <the checkpoint's>, found <asked>`` (long values clipped where they differ,
    by :func:`mazesim.learn.schema.differing`)."""
    missing = object()
    names = sorted(set(asked) | set(saved))
    parts = []
    for name in names:
        theirs, ours = saved.get(name, missing), asked.get(name, missing)
        if theirs != ours:
            expected, found = (
                "(not set)" if value is missing else json.dumps(value) for value in (theirs, ours)
            )
            parts.append(f"{name}: {differing(expected, found)}")
    return "; ".join(parts)


def read_checkpoint(folder: Path, settings: dict[str, Any]) -> Checkpoint:
    """Reads and checks the checkpoint in ``folder``.

    Args:
        folder: The run's folder.
        settings: The settings of the run to continue; the checkpoint's must be the same.

    Raises:
        PolicyFormatError: No checkpoint, a malformed one, or one of a run with other settings.
    """
    path = folder / CHECKPOINT_FILE
    # The tables' shape follows the run's door sub-task phases (``mazesim train --door-distance``).
    door_distance = bool(settings.get("door_distance", False))
    try:
        arrays, metadata = _read_tables(folder, door_distance)
    except PolicyFormatError:
        # Tables of the other phases are a run with other settings, said below.
        other = _read_tables_or_none(folder, not door_distance)
        if other is None or other[1]["settings"] == settings:
            raise
        arrays, metadata = other
    if metadata["settings"] != settings:
        raise PolicyFormatError(
            f"{path}: the checkpoint is of a run with other settings "
            f"({_settings_difference(settings, metadata['settings'])}); resume it with those, "
            "or start afresh in another folder"
        )
    if not np.all(np.isfinite(arrays["q"])) or np.any(arrays["visits"] < 0):
        raise PolicyFormatError(
            f"{path}: expected finite tables and counts of at least 0, found others"
        )
    return Checkpoint(
        tables=LowerTables(arrays["q"], arrays["visits"]),
        next_round=int(metadata["next_round"]),
        history=list(metadata["history"]),
        lower_seconds=float(metadata["lower_seconds"]),
    )


class RunFolder:
    """A training run's folder: its checkpoints, the one to continue from, and the navigator.

    Args:
        folder: The folder (created when the run starts, if missing).
        resume: Continue the run whose checkpoint is in ``folder``; otherwise the folder must hold
            no checkpoint.
    """

    def __init__(self, folder: str | os.PathLike[str], resume: bool = False) -> None:
        self.folder = Path(folder)
        self.resume = resume

    def start(self, settings: dict[str, Any]) -> Checkpoint | None:
        """Prepares the folder for a run with ``settings`` (its identity) and returns the
        checkpoint to continue from, or None for a fresh run.

        Raises:
            InvalidArgumentError: The folder is a file.
            PolicyFormatError: ``resume`` without a usable checkpoint of the same settings, or a
                checkpoint already in the folder without ``resume``.
        """
        folder = self.folder
        if folder.exists() and not folder.is_dir():
            raise InvalidArgumentError(
                f"expected a folder for the navigator, found a file: {folder}"
            )
        saved = None
        if self.resume:
            if not checkpoint_exists(folder):
                raise PolicyFormatError(f"{folder / CHECKPOINT_FILE}: no checkpoint to resume from")
            saved = read_checkpoint(folder, settings)
        elif checkpoint_exists(folder):
            raise PolicyFormatError(
                f"{folder} holds the checkpoint of another run; pass --resume to continue it, "
                "or choose another --out"
            )
        folder.mkdir(parents=True, exist_ok=True)
        remove_checkpoint_leftovers(folder)
        return saved

    def save(self, settings: dict[str, Any], checkpoint: Checkpoint) -> None:
        """Writes the run's checkpoint (:func:`write_checkpoint`)."""
        write_checkpoint(self.folder, settings, checkpoint)

    def finish(self, policy: TrainedPolicy) -> None:
        """Saves the trained navigator into the folder and names it as its source."""
        self.folder.mkdir(parents=True, exist_ok=True)
        save_policy(policy, self.folder)
        policy.source = str(self.folder)
