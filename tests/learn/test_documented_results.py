"""Issue 37: the shipped navigator's figures on seed-maze that docs/hrl.md's results table and
the README's headline table show are what ``mazesim eval --episodes 1000`` prints (the run is
deterministic: episode seed 0)."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HRL_PAGE = ROOT / "docs" / "hrl.md"
README = ROOT / "README.md"
#: A guard against a run that hangs, not a speed requirement.
TIMEOUT_S = 600


def _section(printed: str, title: str) -> dict[str, str]:
    """The ``name  value`` lines of one section of ``mazesim eval``'s summary."""
    text = printed.split(title, 1)[1].split("checkpoint events", 1)[0]
    fields = {}
    for line in text.splitlines():
        match = re.match(r"^  (\w[\w ]*?)\s{2,}(\S+)", line)
        if match:
            fields[match[1]] = match[2]
    return fields


@pytest.fixture(scope="module")
def evaluation() -> tuple[dict[str, str], dict[str, str]]:
    """The ground truth's and the robust decoder's sections of the shipped navigator's run."""
    finished = subprocess.run(
        [str(Path(sys.executable).parent / "mazesim"), "eval", "--episodes", "1000"],
        capture_output=True,
        text=True,
        timeout=TIMEOUT_S,
        check=True,
    )
    return (
        _section(finished.stdout, "checkpoint events from the ground truth"),
        _section(finished.stdout, "checkpoint events read by the robust barcode decoder"),
    )


def test_the_hrl_pages_row_of_the_shipped_navigator_is_the_runs(
    evaluation: tuple[dict[str, str], dict[str, str]],
) -> None:
    row = re.search(
        r"^\| hierarchical, shipped \| seed-maze \| 1,000 \| \*\*([\d.]+) %\*\* \(([\d.]+) %\) "
        r"\| \*\*([\d.]+) %\*\* \(([\d.]+) %\) \| ([\d.]+) \| ([\d.]+) \(([\d.]+)\) \|",
        HRL_PAGE.read_text(encoding="utf-8"),
        re.MULTILINE,
    )
    assert row is not None
    truth, robust = evaluation
    success, success_robust, clean, clean_robust, contacts, path, path_robust = row.groups()
    assert (truth["success rate"], robust["success rate"]) == (f"{success}%", f"{success_robust}%")
    assert (truth["without collision"], robust["without collision"]) == (
        f"{clean}%",
        f"{clean_robust}%",
    )
    assert truth["mean collisions"] == contacts
    assert (truth["mean path ratio"], robust["mean path ratio"]) == (path, path_robust)


def test_the_readmes_headline_of_the_shipped_navigator_is_the_runs(
    evaluation: tuple[dict[str, str], dict[str, str]],
) -> None:
    row = re.search(
        r"1,000 episodes \| \*\*([\d.]+) %\*\* success, none touching a wall; path ([\d.]+) x",
        README.read_text(encoding="utf-8"),
    )
    assert row is not None
    truth, _ = evaluation
    assert truth["success rate"] == f"{row[1]}%"
    assert truth["without collision"] == "100.0%"
    assert truth["mean path ratio"] == row[2]
