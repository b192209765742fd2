"""Atomic file writes: write a temporary file in the target's folder, then rename it over."""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Iterator
from typing import IO


def _umask() -> int:
    """The process's file-creation mask (read by setting and restoring it)."""
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


@contextlib.contextmanager
def atomic_file(path: str | os.PathLike[str]) -> Iterator[IO[bytes]]:
    """Opens a temporary file that replaces ``path`` when the block ends without an error.

    Readers of ``path`` see either the old content or the complete new one, never a partial
    file. If the block raises, the temporary file is removed and ``path`` is left untouched.

    Args:
        path: The file to (re)write; its folder must exist.

    Yields:
        A binary file object to write the new content to.
    """
    target = os.fspath(path)
    folder = os.path.dirname(os.path.abspath(target))
    handle = tempfile.NamedTemporaryFile(
        mode="wb",
        dir=folder,
        prefix=f".{os.path.basename(target)}.",
        suffix=".tmp",
        delete=False,
    )
    try:
        with handle:
            yield handle
            handle.flush()
            # A temporary file is private (0600); give the result the user's usual permissions.
            os.fchmod(handle.fileno(), 0o666 & ~_umask())
            os.fsync(handle.fileno())
        os.replace(handle.name, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(handle.name)
        raise
