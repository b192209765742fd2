"""The ``mazesim`` command run as a process of its own, for the tests of its exit codes and
output."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

__all__ = ["mazesim_command"]


def mazesim_command(
    *args: str, cwd: Path, env: dict[str, str] | None = None, timeout: float = 300
) -> subprocess.CompletedProcess[str]:
    """``python -m mazesim ARGS`` run in ``cwd`` (with the environment ``env``, else this
    process's), its output captured as text."""
    return subprocess.run(
        [sys.executable, "-m", "mazesim", *args],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )
