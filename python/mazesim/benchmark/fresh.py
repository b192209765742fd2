"""One measurement in a fresh interpreter, so that its memory per env is its own.

``python -m mazesim.benchmark.fresh SETTINGS_JSON`` runs :func:`~mazesim.benchmark.measure` on the
settings given as a JSON object, reports its progress on stderr as ``progress DONE TOTAL`` lines
and prints the report as one JSON object on stdout; :func:`measure_in_fresh_process` runs it and
reads both.
"""

from __future__ import annotations

import json
import subprocess
import sys
from dataclasses import asdict
from typing import Any

from mazesim.errors import InvalidArgumentError

from .steady import BenchSettings, Progress, measure

__all__ = ["measure_in_fresh_process"]


def measure_in_fresh_process(
    settings: BenchSettings, progress: Progress | None = None
) -> dict[str, Any]:
    """Runs :func:`~mazesim.benchmark.measure` on ``settings`` in a child interpreter.

    Args:
        settings: What to run (checked here first, so a bad setting fails before the child).
        progress: Called with the steps done and the steps in all as the child reports them.

    Raises:
        InvalidArgumentError: The child failed; the message ends with its last error line.
    """
    settings.check()
    command = [sys.executable, "-m", "mazesim.benchmark.fresh", json.dumps(asdict(settings))]
    errors: list[str] = []
    with subprocess.Popen(
        command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    ) as child:
        assert child.stderr is not None and child.stdout is not None
        for line in child.stderr:
            words = line.split()
            if len(words) == 3 and words[0] == "progress" and progress is not None:
                progress(int(words[1]), int(words[2]))
            elif line.strip():
                errors.append(line.strip())
        report = child.stdout.read()
    if child.returncode != 0:
        raise InvalidArgumentError(
            f"the benchmark at {settings.envs} envs ({settings.workload}, {settings.mazes} "
            f"mazes) failed with exit status {child.returncode}: "
            f"{errors[-1] if errors else 'no message'}"
        )
    result: dict[str, Any] = json.loads(report)
    return result


def _report_progress(done: int, total: int) -> None:
    print(f"progress {done} {total}", file=sys.stderr, flush=True)


def main(argv: list[str]) -> int:
    settings = BenchSettings(**json.loads(argv[0]))
    print(json.dumps(measure(settings, progress=_report_progress)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
