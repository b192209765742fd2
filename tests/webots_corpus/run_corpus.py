"""Runs the Webots compatibility corpus from local mirrors and writes ``docs/webots-compat.md``.

Usage: ``python tests/webots_corpus/run_corpus.py --mirrors DIR [--out FILE] [--only NAME ...]
[--budget SECONDS]`` (``make webots-compat MIRRORS=DIR``). Each project of ``manifest.toml`` is
exported from its repository's mirror in DIR into a temporary folder, its world imported and its
first controller run with ``mazesim webots run`` for the project's simulated time; the facts it is
expected to show are checked against the run's ``summary.json`` and ``trajectory.csv``. A
project whose mirror is missing is skipped, and the table says which. A compiled core older
than its Rust sources (a checkout not built again since it took in Rust changes) is refused
before any project runs (:mod:`webots_corpus.core_build`). The whole run stops
starting projects once ``--budget`` wall-clock seconds (default 2400) have passed: the three
muesli-bt projects each build a C++ library of about 30 files with their own CMakeLists.txt
first, 9 minutes each on the shared 2-core machine under a load average of 11-13
(2026-11-29).
"""

from __future__ import annotations

import argparse
import datetime
import subprocess
import sys
import tempfile
import time
from pathlib import Path

if __package__ in (None, ""):  # run as a script: import the package from tests/
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from webots_corpus.census import Census
from webots_corpus.core_build import core_file, stale_core_message
from webots_corpus.manifest import load_manifest
from webots_corpus.report import write_report
from webots_corpus.runner import Row, run_project

ROOT = Path(__file__).resolve().parents[2]
DEFAULT_OUT = ROOT / "docs" / "webots-compat.md"
DEFAULT_BUDGET_S = 2400.0


def _revision() -> str:
    found = subprocess.run(
        ["git", "-C", str(ROOT), "rev-parse", "--short=12", "HEAD"],
        capture_output=True,
        text=True,
        check=False,
    )
    return found.stdout.strip() or "unknown"


def main(argv: list[str] | None = None) -> int:
    """Runs the corpus; 0 when every project ran or was skipped for a stated reason, 2 (before
    running any) when the compiled core is older than its sources in the checkout."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--mirrors", type=Path, required=True, help="folder of git mirrors")
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT, help="the page to write")
    parser.add_argument("--only", nargs="*", default=None, help="project names to run")
    parser.add_argument("--budget", type=float, default=DEFAULT_BUDGET_S, help="wall-clock s")
    args = parser.parse_args(argv)
    core = core_file()
    stale = stale_core_message(core, ROOT) if core is not None else None
    if stale is not None:
        print(f"run_corpus: {stale}", file=sys.stderr)
        return 2
    projects = load_manifest()
    if args.only:
        projects = [p for p in projects if p.name in set(args.only)]
    census = Census()
    rows: list[Row] = []
    started = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="mazesim-corpus-") as work:
        for project in projects:
            if time.monotonic() - started > args.budget:
                rows.append(Row(project, "skipped", f"the {args.budget:.0f} s budget was spent"))
                continue
            row = run_project(project, args.mirrors, Path(work), census)
            rows.append(row)
            print(f"{row.result:14} {row.wall_s:6.1f} s  {project.name}  {row.cause}", flush=True)
    elapsed = time.monotonic() - started
    stamp = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d")
    write_report(args.out, rows, census, stamp=stamp, revision=_revision(), elapsed_s=elapsed)
    print(f"wrote {args.out} ({len(rows)} projects, {elapsed:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
