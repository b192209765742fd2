"""Issue 15: a damaged ``run.json`` in a sweep's output means the run is done again, not a crash."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from mazesim.distributed.config import Setting
from mazesim.distributed.output import RUNS_DIR, read_finished_run

SETTING = Setting(id="abc-s0", group="abc", label="all", params={"seed": 0, "envs": 8})


def _write_run_file(out: Path, text: str) -> None:
    folder = out / RUNS_DIR / SETTING.id
    folder.mkdir(parents=True)
    (folder / "run.json").write_text(text)


def test_a_finished_run_is_read_back(tmp_path: Path) -> None:
    document = {"setting": {"params": dict(SETTING.params)}, "result": {"success_rate": 0.5}}
    _write_run_file(tmp_path, json.dumps(document))
    assert read_finished_run(str(tmp_path), SETTING) == {"success_rate": 0.5}


@pytest.mark.parametrize(
    "text",
    [
        '{"setting": [], "result": {}}',
        '{"setting": "x", "result": {}}',
        '{"setting": {"params": {"seed": 1, "envs": 8}}, "result": {}}',
        '{"result": []}',
        "[" * 100_000 + "]" * 100_000,
        "{",
        "",
    ],
    ids=lambda text: text[:20] or "empty",
)
def test_a_damaged_run_file_means_the_run_is_not_done(tmp_path: Path, text: str) -> None:
    _write_run_file(tmp_path, text)
    assert read_finished_run(str(tmp_path), SETTING) is None


def test_a_task_output_prints_its_files_by_name_and_size_not_their_bytes() -> None:
    """A search loop that prints what ``train_and_evaluate`` returned sees the result and the
    files' sizes, not megabytes of a table's bytes."""
    from mazesim.distributed import TaskOutput

    output = TaskOutput(
        {"success_rate": 0.75}, {"tables.npz": b"\0" * 1_000_000, "run.json": b"{}"}
    )
    shown = repr(output)
    assert len(shown) < 200, shown
    assert "'success_rate': 0.75" in shown
    assert "'tables.npz': <1,000,000 bytes>" in shown and "'run.json': <2 bytes>" in shown
