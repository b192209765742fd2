"""Runs one hostile input in a fresh Python process under a 4 GiB address-space cap and a 120 s
limit (a ceiling that tells a hang from a slow start on a loaded machine), and says how it ended:
a correct result, a MazesimError, or a failure (abort, signal, PanicException, another
exception, hang, memory over the cap)."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from dataclasses import dataclass

ADDRESS_SPACE_CAP = 4 << 30
TIME_LIMIT_S = 120.0

_PRELUDE = """
import resource, signal, sys, time
resource.setrlimit(resource.RLIMIT_AS, ({cap}, {cap}))
# Ctrl-C raises KeyboardInterrupt as in a terminal, even where the tests were started as a
# background job (whose children inherit SIGINT ignored, so Python installs no handler).
signal.signal(signal.SIGINT, signal.default_int_handler)
import numpy as np
import mazesim
from mazesim import _core
HEADER = 'format = "mazesim-world"\\nversion = 1\\n'
def wall(x, y=0.0, sx=0.1, sy=0.1, yaw=0.0):
    return (f"[[walls]]\\ncenter = [{{x!r}}, {{y!r}}]\\nsize = [{{sx!r}}, {{sy!r}}]\\n"
            f"yaw = {{yaw!r}}\\n")
def buffers(batch):
    n = batch.num_envs
    return (np.zeros((n, batch.observation_width), np.float32), np.zeros((n, 3), np.float32),
            np.zeros(n, bool), np.zeros(n, np.int32))
try:
{body}
except mazesim.MazesimError as e:
    print("REFUSED", type(e).__name__, str(e)[:300])
    sys.exit(0)
except BaseException as e:
    print("ESCAPED", type(e).__module__, type(e).__name__, str(e)[:300])
    sys.exit(3)
print("DONE")
"""


@dataclass
class Outcome:
    """How a hostile input ended."""

    returncode: int | None
    stdout: str
    stderr: str

    @property
    def ok(self) -> bool:
        """A correct result or a MazesimError, within the time and memory caps."""
        return self.returncode == 0 and ("DONE" in self.stdout or "REFUSED" in self.stdout)

    @property
    def refused(self) -> bool:
        """Ended in a MazesimError."""
        return self.returncode == 0 and "REFUSED" in self.stdout

    def describe(self) -> str:
        """The outcome for an assertion message."""
        how = "hang" if self.returncode is None else f"exit {self.returncode}"
        return f"{how}\nstdout: {self.stdout[-800:]}\nstderr: {self.stderr[-1500:]}"


def run_hostile(body: str) -> Outcome:
    """Runs `body` (Python statements using np, mazesim, _core, HEADER, wall, buffers) in a fresh
    process under the caps."""
    indented = textwrap.indent(textwrap.dedent(body), "    ")
    code = _PRELUDE.format(cap=ADDRESS_SPACE_CAP, body=indented)
    try:
        done = subprocess.run(
            [sys.executable, "-c", code],
            capture_output=True,
            text=True,
            timeout=TIME_LIMIT_S,
        )
    except subprocess.TimeoutExpired as e:
        out = e.stdout.decode() if isinstance(e.stdout, bytes) else (e.stdout or "")
        return Outcome(None, out, "")
    return Outcome(done.returncode, done.stdout, done.stderr)
