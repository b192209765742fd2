"""Atomic file writes: write a temporary file in the target's folder, then rename it over.

The temporary file of a target ``NAME`` is ``.NAME.<pid>-<token>.tmp`` in the same folder, as
the core's writer (``World.save``) names its own. A process killed in the middle of a write
leaves it behind; the next write of the same target, by either writer (or
:func:`remove_stale_temporaries`), removes it when it is clearly orphaned: made by a process that
no longer runs, or by this process outside a write still in progress (this writer also removes
one last changed before this process started). Temporaries of older mazesim versions
(``.NAME.<8 characters>.tmp``) go when they are older than this process; those of the older
core's writer (``.NAME.tmp-<pid>-<count>``) by the same rule as today's, by their pid.

The code runs on Linux, macOS and Windows: the temporary file is created with the user's usual
permissions, so no ``os.fchmod`` is needed (Windows has none before Python 3.13); files are
flushed with ``F_FULLFSYNC`` where it exists (macOS) and ``fsync`` elsewhere; the rename is
flushed by syncing the folder only where folders can be opened (POSIX); and a process id is
probed only where that is harmless (POSIX: ``os.kill(pid, 0)``; on Windows it would end the
process).

What the path names decides how it is written (:func:`output_target`):

- a regular file, or nothing yet: the file is replaced (or created) atomically as above;
- a symbolic link: it is followed, and the file it leads to is replaced; the link stays a link;
- a device, a FIFO or a terminal (``/dev/null``, ``/dev/tty``), or a path that leads through
  ``/proc`` (``/dev/stdout``, ``/proc/self/fd/1``, whatever they are open on): the content is
  written into it as a stream, appended (a descriptor of this process, such as ``/dev/stdout``,
  through a copy of itself), never replaced; a FIFO no process reads is refused at once rather
  than waited on;
- a folder or a socket: refused.

Temporary names fit the file system's limit of 255 bytes a name: a long target name is cut and
marked with a digest of the whole name. Every failure is a :class:`~mazesim.errors.MazesimIOError`
naming the user's path (never the temporary file) with the system's reason, a full disk included.
"""

from __future__ import annotations

import contextlib
import errno
import io
import os
import re
import secrets
import stat
import sys
import time
from collections.abc import Iterator
from typing import IO, NamedTuple

from mazesim._core import _temporary_writing
from mazesim.errors import MazesimIOError, _path_of

try:
    import fcntl
except ImportError:  # Windows
    fcntl = None  # type: ignore[assignment]

__all__ = [
    "OutputTarget",
    "atomic_file",
    "output_target",
    "remove_stale_temporaries",
    "temporary_name",
    "write_failure",
]

#: True on Windows, where folders cannot be opened to sync them and ``os.kill`` is not a probe.
_WINDOWS = sys.platform == "win32"
#: When this process started writing files (module import), in the clock of file times.
_PROCESS_STARTED = time.time()
_SUFFIX = ".tmp"


#: The longest file name (in bytes) of the usual file systems (ext4, XFS, APFS, NTFS).
NAME_MAX = 255
#: Bytes a temporary name adds to its stem: the dot before it, ``.<10 digits>-<8 hex>.tmp``,
#: and room for a suffix of up to 8 bytes a writer may add (``.mp4``).
_ADDED = 1 + 1 + 10 + 1 + 8 + len(_SUFFIX) + 8
#: Bytes the older core's temporary names (``.NAME.tmp-<pid>-<count>``) added to their stem.
_OLD_CORE_ADDED = 1 + 5 + 10 + 1 + 20
#: Where the system shows the files processes have open (``/dev/stdout`` leads there): a path
#: through it is written into, never replaced.
_PROCESS_FILES = "/proc/"


def _fnv1a(data: bytes) -> int:
    """The 64-bit FNV-1a hash of ``data``, as the core's writer marks a cut name."""
    value = 0xCBF29CE484222325
    for byte in data:
        value = ((value ^ byte) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return value


def _temporary_stem(base: str, added: int = _ADDED) -> str:
    """The part of a temporary name taken from the target's name ``base``: the name itself, or
    when the temporary name (which adds ``added`` bytes to it) would pass :data:`NAME_MAX`
    bytes, its start cut at a character boundary and marked with ``~`` and the 16 hex digits
    of the FNV-1a hash of the whole name (the same stem as the core's writer, so either removes
    the other's orphans)."""
    encoded = base.encode("utf-8", "surrogateescape")
    if len(encoded) + added <= NAME_MAX:
        return base
    digest = f"{_fnv1a(encoded):016x}"
    room = NAME_MAX - added - 1 - len(digest)
    start = encoded[:room].decode("utf-8", "ignore")
    return f"{start}~{digest}"


def temporary_name(target: str) -> str:
    """A fresh temporary path for ``target``, in its folder, named after it and this process
    (at most :data:`NAME_MAX` bytes long less 8, whatever the target's name)."""
    folder, base = os.path.split(os.path.abspath(target))
    stem = _temporary_stem(base)
    return os.path.join(folder, f".{stem}.{os.getpid()}-{secrets.token_hex(4)}{_SUFFIX}")


def _temporary_pattern(base: str) -> re.Pattern[str]:
    """Names of the temporaries of ``base`` (this module's, the core's, and those of older
    versions of either): group ``pid`` set unless of the older Python writer's style."""
    return re.compile(
        rf"\.{re.escape(_temporary_stem(base))}\.(?:(?P<pid>[0-9]{{1,10}})-[0-9a-f]{{8}}"
        rf"|[a-z0-9_]{{8}}){re.escape(_SUFFIX)}"
        rf"|\.{re.escape(_temporary_stem(base, _OLD_CORE_ADDED))}\.tmp-(?P<old_pid>[0-9]{{1,10}})"
        rf"-[0-9]{{1,20}}"
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
        # Not a write in progress of this process, by this writer or by the core's: one set of
        # them, kept by the core, so that neither takes the other's temporary for an orphan.
        return not _temporary_writing(os.path.basename(path))
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
        writer = found["pid"] or found["old_pid"]
        pid = int(writer) if writer is not None else None
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


class OutputTarget(NamedTuple):
    """What an output path names, and so how it is written.

    Attributes:
        path: The file to write: the path itself for a stream, else the regular file (existing
            or not yet) it leads to once symbolic links are followed.
        stream: Whether it is written into as a stream (a device, a FIFO, a terminal, a path
            through ``/proc``) instead of replaced.
    """

    path: str
    stream: bool


def _replaced_mode(user_path: str, path: str) -> int | None:
    """The permission bits of the regular file at ``path`` that a write replaces, None when
    there is none.

    Raises:
        MazesimIOError: The file may not be written by anyone (``0o444``): a plain write of it
            fails, and its replacement must not either.
    """
    try:
        found = os.stat(path)
    except OSError:
        return None
    if not stat.S_ISREG(found.st_mode):
        return None
    mode = stat.S_IMODE(found.st_mode)
    if not mode & (stat.S_IWUSR | stat.S_IWGRP | stat.S_IWOTH):
        error = PermissionError(errno.EACCES, os.strerror(errno.EACCES), user_path)
        raise write_failure(
            user_path, error, "it is read-only (make it writable, or save under another name)"
        )
    return mode


def write_failure(path: str | os.PathLike[str], error: OSError, what: str = "") -> MazesimIOError:
    """The error of a failed write of ``path``: its message names the user's path (not a
    temporary file) and the system's reason; ``errno``, ``strerror`` and ``filename`` are set.

    Args:
        path: The path as the user gave it.
        error: What the system raised.
        what: Why, when the system's reason alone would not say (``"it is a folder"``).
    """
    name = os.fspath(path)
    reason = what or error.strerror or str(error)
    failure = MazesimIOError(f"{name}: cannot write the file: {reason}")
    failure.errno = error.errno
    failure.strerror = reason
    failure.filename = name
    return failure


def _link_chain(path: str) -> list[str]:
    """``path`` made absolute and each path its symbolic links lead to in turn (at most 40, as
    the system follows)."""
    chain = [os.path.abspath(path)]
    for _ in range(40):
        try:
            following = os.readlink(chain[-1])
        except (OSError, ValueError):
            break
        chain.append(os.path.normpath(os.path.join(os.path.dirname(chain[-1]), following)))
    return chain


def output_target(path: str | os.PathLike[str]) -> OutputTarget:
    """How ``path`` is written (see the module's docs).

    Raises:
        MazesimIOError: ``path`` is a folder or a socket, or cannot be looked at.
    """
    name = os.fspath(path)
    if any(step.startswith(_PROCESS_FILES) for step in _link_chain(name)):
        return OutputTarget(name, True)
    try:
        mode = os.stat(name).st_mode
    except FileNotFoundError:
        return OutputTarget(os.path.realpath(name), False)
    except OSError as error:
        raise write_failure(name, error) from None
    if stat.S_ISDIR(mode):
        raise write_failure(name, IsADirectoryError(errno.EISDIR, "is a folder"), "it is a folder")
    if stat.S_ISSOCK(mode):
        raise write_failure(
            name,
            OSError(errno.ENXIO, "is a socket"),
            "expected a file, a device or a FIFO, found a socket",
        )
    if stat.S_ISREG(mode):
        return OutputTarget(os.path.realpath(name), False)
    return OutputTarget(name, True)


def _own_descriptor(path: str) -> int | None:
    """The descriptor of this process that ``path`` leads to, if it does (``/dev/stdout``
    leads to ``/proc/self/fd/1``)."""
    own = re.compile(rf"/proc/(?:self|thread-self|{os.getpid()})/fd/([0-9]+)")
    for step in _link_chain(path):
        found = own.fullmatch(step)
        if found is not None:
            return int(found[1])
    return None


def _descriptor_of(stream: IO[str]) -> int | None:
    try:
        return stream.fileno()
    except (OSError, ValueError, AttributeError):
        return None


def _open_stream(path: str) -> int:
    """Opens a device, FIFO or system path to write into, appending, without waiting for a FIFO
    reader that is not there; the descriptor is then blocking, like any file's. A descriptor of
    this process (``/dev/stdout``) is written through a copy of itself, at its own position, so
    that what the process prints to it afterwards follows the content instead of overwriting
    it."""
    own = _own_descriptor(path)
    if own is not None:
        # What Python printed there before comes first.
        for stream in (sys.stdout, sys.stderr):
            if stream is not None and _descriptor_of(stream) == own:
                with contextlib.suppress(OSError, ValueError):
                    stream.flush()
        try:
            return os.dup(own)
        except OSError as error:
            raise write_failure(path, error) from None
    flags = os.O_WRONLY | os.O_APPEND | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        descriptor = os.open(path, flags)
    except OSError as error:
        if error.errno == errno.ENXIO:
            raise write_failure(
                path, error, "it is a FIFO that no process reads (start its reader first)"
            ) from None
        raise write_failure(path, error) from None
    if fcntl is not None:
        status = fcntl.fcntl(descriptor, fcntl.F_GETFL)
        fcntl.fcntl(descriptor, fcntl.F_SETFL, status & ~os.O_NONBLOCK)
    return descriptor


def _write_all(descriptor: int, data: bytes) -> None:
    view = memoryview(data)
    while view:
        view = view[os.write(descriptor, view) :]


@contextlib.contextmanager
def _streamed(path: str) -> Iterator[IO[bytes]]:
    """Collects what the block writes, then writes it into the stream ``path`` in one go."""
    descriptor = _open_stream(path)
    try:
        buffer = io.BytesIO()
        yield buffer
        try:
            _write_all(descriptor, buffer.getvalue())
        except OSError as error:
            raise write_failure(path, error) from None
    finally:
        os.close(descriptor)


def _own_failure(error: OSError, temporary: str) -> bool:
    """Whether an error inside a write block came from writing the temporary file (a full disk,
    a quota) rather than from something else the block did."""
    return error.errno is not None and error.filename in (None, temporary)


@contextlib.contextmanager
def atomic_file(path: str | os.PathLike[str]) -> Iterator[IO[bytes]]:
    """Opens a file object whose content replaces ``path`` when the block ends without an error.

    Readers of a regular file see either the old content or the complete new one, never a
    partial file. If the block raises, the temporary file is removed and ``path`` is left
    untouched. Orphaned temporaries of ``path`` from interrupted runs are removed first. A
    symbolic link is followed; a device, FIFO or system path is written into, not replaced (see
    the module's docs).

    Args:
        path: The file to (re)write; its folder must exist.

    Yields:
        A binary file object to write the new content to.

    Raises:
        MazesimIOError: The file cannot be written (naming ``path`` and the system's reason).
    """
    user_path = _path_of(path, "path")  # as every path argument: bytes refused
    target = output_target(user_path)
    if target.stream:
        with _streamed(target.path) as buffer:
            yield buffer
        return
    kept = _replaced_mode(user_path, target.path)
    remove_stale_temporaries(target.path)
    temporary = temporary_name(target.path)
    _temporary_writing(os.path.basename(temporary), True)
    try:
        try:
            # Created with the user's usual permissions (``0o666`` less the umask); the file it
            # replaces keeps its own (a private file stays private).
            handle = open(temporary, "xb")  # noqa: SIM115 - closed below, before the rename
            if kept is not None:
                os.fchmod(handle.fileno(), kept)
        except OSError as error:
            raise write_failure(user_path, error) from None
        with handle:
            try:
                yield handle
                handle.flush()
                _sync_file(handle.fileno())
            except OSError as error:
                if _own_failure(error, temporary):
                    raise write_failure(user_path, error) from None
                raise
        try:
            os.replace(temporary, target.path)
        except OSError as error:
            raise write_failure(user_path, error) from None
        _sync_folder(os.path.dirname(target.path))
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(temporary)
        raise
    finally:
        _temporary_writing(os.path.basename(temporary), False)
