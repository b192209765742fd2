"""The bytes per env the performance page and the README show are what the engine counts for the
same batches: 4,096 distinct generated 5 x 5 mazes (the bench's mazes) and 4,096 envs of one of
them."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

import mazesim
from mazesim.benchmark.steady import make_worlds

ROOT = Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "performance.md"
ENVS = 4096


def _documented() -> dict[str, int]:
    """The "now" column of the page's bytes-per-env table, by batch."""
    rows = re.findall(
        r"^\| 4,096 (distinct generated 5 x 5 mazes|envs of one maze) \| [^|]+ \| ([\d,]+) \|$",
        PAGE.read_text(encoding="utf-8"),
        re.MULTILINE,
    )
    assert len(rows) == 2, rows
    return {batch: int(figure.replace(",", "")) for batch, figure in rows}


@pytest.fixture(scope="module")
def worlds() -> list[mazesim.World]:
    return make_worlds(ENVS, "distinct", seed=0)


def test_the_pages_bytes_per_env_are_the_engines_count(worlds: list[mazesim.World]) -> None:
    documented = _documented()
    distinct = mazesim.BatchSimulator(worlds, robot="e-puck", seeds=0).bytes_per_env()
    shared = mazesim.BatchSimulator(worlds[0], num_envs=ENVS, robot="e-puck", seeds=0)
    # The page rounds to three significant figures.
    assert documented["distinct generated 5 x 5 mazes"] == round(distinct, -2), distinct
    assert documented["envs of one maze"] == round(shared.bytes_per_env(), -1), shared
    # The README's headline row, in kB.
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    row = re.search(
        r"^\| memory per env, 4,096 distinct / 4,096 shared [^|]+\| ([\d.]+) kB / ([\d.]+) kB",
        readme,
        re.MULTILINE,
    )
    assert row is not None
    assert float(row.group(1)) == round(distinct / 1000, 1), distinct
    assert float(row.group(2)) == round(shared.bytes_per_env() / 1000, 2), shared
