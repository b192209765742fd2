"""What the ROS 2 tests share: the skip when the extra is missing, and processes run in a private
network namespace with only the loopback interface (``unshare -n``), so no DDS traffic leaves the
machine."""

from __future__ import annotations

import importlib.util
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

DRIVER = Path(__file__).parent / "ros2" / "cyclone_driver.py"
MAZESIM = [sys.executable, "-m", "mazesim"]

#: A world of two e-pucks facing each other, one named as no ROS name may be (``east-1``).
TWO_ROBOTS = """format = "mazesim-world"
version = 1
name = "two-robots"

[[robots]]
name = "west"
x = -0.2
y = 0.0

[[robots]]
name = "east-1"
x = 0.2
y = 0.0
yaw = 3.141592653589793
"""

_MISSING = [name for name in ("cyclonedds", "rosbags") if importlib.util.find_spec(name) is None]
needs_ros2 = pytest.mark.skipif(
    bool(_MISSING), reason=f"mazesim[ros2] is not installed ({', '.join(_MISSING)}): make ros2-deps"
)


def _namespace_works() -> bool:
    if shutil.which("unshare") is None or shutil.which("ip") is None:
        return False
    probe = subprocess.run(
        ["unshare", "-n", "ip", "link", "set", "lo", "up"], capture_output=True, timeout=300
    )
    return probe.returncode == 0


NAMESPACE = _namespace_works()
needs_namespace = pytest.mark.skipif(
    not NAMESPACE, reason="needs unshare -n and ip (root, or user namespaces) for a private network"
)


#: What a run in the namespace may take at most: a ceiling that only bounds a hang (each test's
#: processes end on what they wait for, never on a time), so a loaded machine never reaches it.
CEILING_S = 600.0

#: Python that defines ``await_background(index, *texts)``: returns once the ``index``-th
#: background command of :func:`run_in_namespace` has written each of ``texts`` to its stderr,
#: so that a foreground node lives until the bridge has seen it (and not for a guessed time).
AWAIT_BACKGROUND = """
import os as _os, time as _time
def await_background(index, *texts):
    path = _os.path.join(_os.environ["TMPDIR_NS"], f"bg{index}.err")
    ceiling = _time.monotonic() + 300
    while True:
        with open(path, encoding="utf-8", errors="replace") as stream:
            written = stream.read()
        if all(text in written for text in texts):
            return
        assert _time.monotonic() < ceiling, f"background {index} never wrote {texts}: {written}"
        _time.sleep(0.05)
"""


def run_in_namespace(
    background: list[list[str]],
    foreground: list[str],
    timeout: float = CEILING_S,
    grace: float = 30.0,
) -> subprocess.CompletedProcess[str]:
    """Runs ``background`` commands and then ``foreground`` in one new network namespace (only
    ``lo``, brought up); after the foreground one ends, waits for the background ones (SIGTERM
    after ``grace`` seconds; the exit status then counts 100 more for each that failed) and
    returns the foreground's result, the background's stderr appended. The foreground finds the
    ``index``-th background command's stderr in ``$TMPDIR_NS/bg<index>.err`` while it runs."""
    script = ["ip link set lo up", "pids="]
    for index, command in enumerate(background):
        quoted = " ".join(_quote(part) for part in command)
        script.append(f'{quoted} 2>"$TMPDIR_NS/bg{index}.err" & pids="$pids $!"')
    script.append(" ".join(_quote(part) for part in foreground))
    script.append("status=$?")
    script.append(f"( sleep {grace}; kill -TERM $pids ) >/dev/null 2>&1 & watchdog=$!")
    script.append("for pid in $pids; do wait $pid || status=$((status + 100)); done")
    script.append("kill $watchdog 2>/dev/null")
    script.append('cat "$TMPDIR_NS"/bg*.err >&2 2>/dev/null; exit $status')
    return subprocess.run(
        ["unshare", "-n", "bash", "-c", "export TMPDIR_NS=$(mktemp -d); " + "\n".join(script)],
        capture_output=True,
        text=True,
        timeout=timeout,
    )


def _quote(text: str) -> str:
    return "'" + text.replace("'", "'\\''") + "'"
