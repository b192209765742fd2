"""Writes the compatibility page: the projects' table and the PROTO census."""

from __future__ import annotations

from collections import Counter
from pathlib import Path

from mazesim._atomic import atomic_file
from webots_corpus.census import Census
from webots_corpus.runner import Row

INTRO = """\
# Webots compatibility

Public e-puck Webots projects (a world and its controllers) that mazesim is measured against:
wall and line followers, fuzzy and PID controllers, supervisors, course mazes and swarms, from
{repos} repositories. The manifest, `tests/webots_corpus/manifest.toml`, names each project's
repository, commit and paths and the behaviour a run in Webots shows, as facts; no third-party
code is kept here. `make webots-compat MIRRORS=DIR` exports each project from a local git mirror
(DIR holds one per repository; a missing one is skipped and named), imports its world, runs its
first controller with `mazesim webots run` for the project's simulated time (a C or C++
controller is built with gcc or g++ against mazesim's implementation of Webots' C API), checks
the facts against the run's `summary.json` and `trajectory.csv`, and writes this page.

Measured on {stamp} at commit `{revision}`: {counts}; the whole corpus took {elapsed:.0f} s.

Results: **pass**, every fact held; **fail**, a fact did not (the cause says which and what
was measured, and ends with what is known of why, `known:`, when the manifest says it);
**timeout**, the run was stopped; **not run**, the run said at its start that a
Webots feature or a Python package the controller needs is missing, and the facts did not hold,
or that the controller is in a language mazesim does not run (MATLAB, Java), whatever
the facts (the cause is that statement, the run's `missing_features`); **broken itself**, the
project does not work in Webots either (the cause says why); **skipped**, no mirror; **error**,
the world could not be exported or imported, or the controller could not be built. A cause also
quotes the first thing the import said it lost.
"""

CENSUS_INTRO = """\
## PROTO census

The PROTO types in the corpus's worlds (each world counted once), their instances, and what the
import made of them: dropped (the import said it lost it: a warning on its line, or the run's
summary), stood in (the import said a named stand-in replaced it), or imported (expanded, built
in, or with nothing to simulate: the import reported no loss). An instance inside a dropped one
is dropped too; one inside a plain `Robot` that is not simulated is not counted as lost.

Coverage: {covered} of {instances} instances import ({share:.0%}).
"""


def _cell(text: str) -> str:
    """Text for a table cell: one line, pipes escaped, and ``<extern>`` kept as text (not an
    HTML tag)."""
    text = text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    return text.replace("|", "\\|").replace("\n", " ").strip()


def render(rows: list[Row], census: Census, stamp: str, revision: str, elapsed_s: float) -> str:
    """The page's Markdown."""
    results = Counter(row.result for row in rows)
    counts = ", ".join(f"{n} {result}" for result, n in sorted(results.items()))
    repos = len({row.project.repo for row in rows})
    lines = [
        INTRO.format(
            repos=repos,
            stamp=stamp,
            revision=revision,
            counts=counts or "no projects",
            elapsed=elapsed_s,
        ),  # fmt: skip
        "| project | what it does | result | cause |",
        "|---|---|---|---|",
    ]
    for row in rows:
        project = row.project
        link = f"[{project.name}](https://github.com/{project.repo}/tree/{project.commit})"
        lines.append(f"| {link} | {_cell(project.does)} | {row.result} | {_cell(row.cause)} |")
    total = census.totals()
    lines += [
        "",
        CENSUS_INTRO.format(
            covered=total.imported + total.stood_in,
            instances=total.instances,
            share=census.coverage(),
        ),
        "| PROTO | worlds | instances | imported | stood in | dropped |",
        "|---|---|---|---|---|---|",
    ]
    ranked = sorted(census.types.items(), key=lambda item: (-item[1].instances, item[0]))
    for name, count in ranked:
        lines.append(
            f"| {name} | {len(count.worlds)} | {count.instances} | {count.imported} | "
            f"{count.stood_in} | {count.dropped} |"
        )
    return "\n".join(lines) + "\n"


def write_report(
    path: Path, rows: list[Row], census: Census, stamp: str, revision: str, elapsed_s: float
) -> None:
    """Writes the page atomically."""
    with atomic_file(str(path)) as handle:
        handle.write(render(rows, census, stamp, revision, elapsed_s).encode("utf-8"))
