"""Atomic file writes: write a temporary file in the target's folder, then rename it over.

The temporary file of a target ``NAME`` is ``.NAME.<pid>-<token>.tmp`` in the same folder. A
process killed in the middle of a write leaves it behind; the next write of the same target (or
:func:`remove_stale_temporaries`) removes it when it is clearly orphaned: made by a process that
no longer runs, by this process outside a write still in progress, or last changed before this
process started. Temporaries of older mazesim versions (``.NAME.<8 characters>.tmp``) go when
they are older than this process.

The code runs on Linux, macOS and Windows: the temporary file is created with the user's usual
permissions, so no ``os.fchmod`` is needed (Windows has none before Python 3.13); files are
flushed with ``F_FULLFSYNC`` where it exists (macOS) and ``fsync`` elsewhere; the rename is
flushed by syncing the folder only where folders can be opened (POSIX); and a process id is
probed only where that is harmless (POSIX: ``os.kill(pid, 0)``; on Windows it would end the
process).
"""

from __future__ import annotations

import contextlib
import os
import re
import secrets
import sys
import time
from collections.abc import Iterator
from typing import IO

try:
    import fcntl
except ImportError:  # Windows
    fcntl = None  # type: ignore[assignment]

__all__ = ["atomic_file", "remove_stale_temporaries", "temporary_name"]

#: True on Windows, where folders cannot be opened to sync them and ``os.kill`` is not a probe.
_WINDOWS = sys.platform == "win32"
#: When this process started writing files (module import), in the clock of file times.
_PROCESS_STARTED = time.time()
#: The temporary files this process is writing right now (absolute paths).
_WRITING: set[str] = set()
_SUFFIX = ".tmp"


def temporary_name(target: str) -> str:
    """A fresh temporary path for ``target``, in its folder, named after it and this process."""
    folder, base = os.path.split(os.path.abspath(target))
    return os.path.join(folder, f".{base}.{os.getpid()}-{secrets.token_hex(4)}{_SUFFIX}")


def _temporary_pattern(base: str) -> re.Pattern[str]:
    """Names of this module's temporaries of ``base``: group ``pid`` set unless of old style."""
    return re.compile(
        rf"\.{re.escape(base)}\.(?:(?P<pid>[0-9]{{1,10}})-[0-9a-f]{{8}}|[a-z0-9_]{{8}})"
        rf"{re.escape(_SUFFIX)}"
    )


def _process_is_gone(pid: int) -> bool:
    """True when no process ``pid`` runs (known on POSIX only; False when unsure)."""
    if _WINDOWS or pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    except OSError:
        return False
    return False


def _is_orphaned(path: str, pid: int | None) -> bool:
    """Whether a temporary file is left over from a write that will never finish."""
    if pid == os.getpid():
        return path not in _WRITING
    if pid is not None and _process_is_gone(pid):
        return True
    try:
        return os.stat(path).st_mtime < _PROCESS_STARTED
    except OSError:
        return False


def remove_stale_temporaries(path: str | os.PathLike[str]) -> list[str]:
    """Removes the orphaned temporary files of ``path`` (see the module's docs).

    Only files named like this module's temporaries of ``path`` are considered; nothing else in
    the folder is touched, and a file that cannot be removed is left.

    Returns:
        The paths removed.
    """
    folder, base = os.path.split(os.path.abspath(os.fspath(path)))
    pattern = _temporary_pattern(base)
    removed: list[str] = []
    try:
        names = os.listdir(folder)
    except OSError:
        return removed
    for name in names:
        found = pattern.fullmatch(name)
        if found is None:
            continue
        candidate = os.path.join(folder, name)
        pid = int(found["pid"]) if found["pid"] is not None else None
        if _is_orphaned(candidate, pid):
            with contextlib.suppress(OSError):
                os.unlink(candidate)
                removed.append(candidate)
    return removed


def _sync_file(descriptor: int) -> None:
    """Flushes a file to the disk itself (macOS's ``fsync`` stops at the drive's cache)."""
    full_sync = getattr(fcntl, "F_FULLFSYNC", None) if fcntl is not None else None
    if full_sync is not None:
        with contextlib.suppress(OSError):
            fcntl.fcntl(descriptor, full_sync)
            return
    os.fsync(descriptor)


def _sync_folder(folder: str) -> None:
    """Flushes a rename in ``folder`` to disk where the system lets a folder be synced."""
    if _WINDOWS:
        return
    try:
        descriptor = os.open(folder, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
    except OSError:
        return
    try:
        with contextlib.suppress(OSError):
            os.fsync(descriptor)
    finally:
        os.close(descriptor)


@contextlib.contextmanager
def atomic_file(path: str | os.PathLike[str]) -> Iterator[IO[bytes]]:
    """Opens a temporary file that replaces ``path`` when the block ends without an error.

    Readers of ``path`` see either the old content or the complete new one, never a partial
    file. If the block raises, the temporary file is removed and ``path`` is left untouched.
    Orphaned temporaries of ``path`` from interrupted runs are removed first.

    Args:
        path: The file to (re)write; its folder must exist.

    Yields:
        A binary file object to write the new content to.
    """
    target = os.path.abspath(os.fspath(path))
    remove_stale_temporaries(target)
    temporary = temporary_name(target)
    _WRITING.add(temporary)
    try:
        # Created with the user's usual permissions (``0o666`` less the umask): no chmod needed.
        with open(temporary, "xb") as handle:
            yield handle
            handle.flush()
            _sync_file(handle.fileno())
        os.replace(temporary, target)
        _sync_folder(os.path.dirname(target))
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(temporary)
        raise
    finally:
        _WRITING.discard(temporary)
