"""Memory per env: the growth of the process's resident set while a batch is built.

The resident set counts everything the batch made (worlds, bodies, sensor indexes, buffers), but
also whatever else the interpreter allocated meanwhile, and pages freed inside the process stay
counted; so a measurement builds one batch in a fresh process and divides the growth by its envs.
"""

from __future__ import annotations

import os
from typing import Any

__all__ = ["engine_bytes", "resident_bytes"]


def resident_bytes() -> int:
    """The resident set size of this process in bytes (0 where ``/proc`` is not available)."""
    try:
        with open("/proc/self/statm") as statm:
            return int(statm.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    except OSError:
        return 0


def engine_bytes(batch: Any) -> int | None:
    """The bytes the engine itself counts for ``batch``, or None while it counts none.

    This is where the benchmark takes the engine's own count of its bytes, world data shared
    between envs counted once, in preference to the resident set's growth: a
    ``BatchSimulator.memory_bytes()`` method, when the engine has one.
    """
    count = getattr(batch, "memory_bytes", None)
    return int(count()) if callable(count) else None
