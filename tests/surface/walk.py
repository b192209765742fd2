"""Runs a list of hostile calls through the runner (``runner.py``) in child processes and says
how each ended. A call that aborts its process or hangs ends that process: it is recorded and a
new process carries on from the next call, so one walk lists every call that escapes, not only
the first.
"""

from __future__ import annotations

import json
import os
import queue
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent.parent
#: Seconds a call may take once it started (its runner presses Ctrl-C after 2 s; making its
#: instance comes first, outside that watchdog): a call silent for longer hangs. A ceiling for a
#: hang, never a pace: on a loaded machine an endless template stopped by Ctrl-C took over 60 s.
CALL_TIMEOUT = 300.0


def _lines(stream: Any, into: queue.Queue[str | None]) -> None:
    for line in stream:
        into.put(line)
    into.put(None)


def _run_from(
    plans: list[dict[str, Any]], start: int, scratch: Path, results: dict[int, dict[str, Any]]
) -> int:
    """Runs ``plans[start:]`` in one child process until it is done or a call ends it; returns
    where the next process should start (``len(plans)`` when all are done)."""
    plan_file = scratch / f"plans-{start}.json"
    plan_file.write_text(json.dumps(plans[start:]), encoding="utf-8")
    stderr_file = scratch / f"stderr-{start}.txt"
    with stderr_file.open("w+", encoding="utf-8", errors="replace") as stderr:
        with subprocess.Popen(
            [sys.executable, "-m", "surface.runner", str(plan_file)],
            cwd=HERE,
            stdout=subprocess.PIPE,
            stderr=stderr,
            text=True,
            errors="replace",
        ) as child:
            return _follow(child, start, len(plans), stderr, results)


def _follow(
    child: subprocess.Popen[str],
    start: int,
    count: int,
    stderr: Any,
    results: dict[int, dict[str, Any]],
) -> int:
    """Reads the runner's lines until it is done, ends or a call hangs (then kills it); returns
    where the next process should start."""
    lines: queue.Queue[str | None] = queue.Queue()
    reader = threading.Thread(target=_lines, args=(child.stdout, lines), daemon=True)
    reader.start()
    current, next_start = start, None
    deadline = time.monotonic() + CALL_TIMEOUT
    while next_start is None:
        try:
            line = lines.get(timeout=max(0.0, deadline - time.monotonic()))
        except queue.Empty:
            child.kill()
            results[current] = {"how": "escaped", "what": "hung (no end after Ctrl-C)"}
            next_start = current + 1
            break
        if line is None:
            code = child.wait()
            stderr.seek(0)
            tail = stderr.read()[-600:]
            results[current] = {"how": "escaped", "what": f"process ended {code}: {tail}"}
            next_start = current + 1
        elif line.startswith("CALL "):
            current = start + int(line.split()[1])
            deadline = time.monotonic() + CALL_TIMEOUT
        elif line.startswith("RESULT "):
            outcome = json.loads(line[len("RESULT ") :])
            results[start + outcome.pop("index")] = outcome
        elif line.startswith("ALL DONE"):
            next_start = count
    child.wait()
    reader.join(timeout=300)  # the pipe ends with the process (and any child it left)
    return next_start


def walk(plans: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """How each call of ``plans`` ended: ``{"how": "ended" | "refused" | "escaped", "what":
    ...}``, one per plan, in order."""
    results: dict[int, dict[str, Any]] = {}
    with tempfile.TemporaryDirectory(prefix="surface-") as scratch:
        start = 0
        while start < len(plans):
            start = _run_from(plans, start, Path(scratch), results)
    missing = {"how": "escaped", "what": "no result"}
    return [results.get(i, missing) for i in range(len(plans))]


def main() -> None:
    """``python -m surface.walk PLANS.json``: prints each escape (for a walk outside pytest)."""
    plans = json.loads(Path(sys.argv[1]).read_text(encoding="utf-8"))
    for plan, outcome in zip(plans, walk(plans)):  # noqa: B905 - one result per plan
        if outcome["how"] == "escaped":
            print(json.dumps(plan), outcome["what"], sep="\n    ", flush=True)
    os._exit(0)


if __name__ == "__main__":
    main()
