"""Memory per env: the growth of the process's resident set while a batch is built.

The resident set counts everything the batch made (worlds, bodies, sensor indexes, buffers), but
also whatever else the interpreter allocated meanwhile, and pages freed inside the process stay
counted; so a measurement builds one batch in a fresh process and divides the growth by its envs.
"""

from __future__ import annotations

import os
from typing import Any

__all__ = ["resident_bytes"]


def resident_bytes() -> int:
    """The resident set size of this process in bytes (0 where ``/proc`` is not available)."""
    try:
        with open("/proc/self/statm") as statm:
            return int(statm.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    except OSError:
        return 0


def engine_bytes(batch: Any) -> int:
    """The bytes the engine itself counts for ``batch`` (``BatchSimulator.bytes_per_env()`` times
    its envs): world data shared between envs counted once, the per-env state, the per-thread
    scratch space. Preferred to the resident set's growth, which also counts the allocator's
    slack and numpy's buffers."""
    return int(batch.bytes_per_env()) * len(batch)
