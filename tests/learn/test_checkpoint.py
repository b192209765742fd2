"""Issue 15: a training checkpoint is complete or absent at every instant.

A crash is simulated at every file replacement of a training run (the k-th ``os.replace``
raises and nothing is cleaned up, as after ``kill -9``); the run is then continued with
``resume`` and must end with the tables of a run never interrupted.
"""

from __future__ import annotations

import dataclasses
import json
import os
import shutil
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from mazesim.errors import PolicyFormatError, _command_line
from mazesim.learn.checkpoint import (
    CHECKPOINT_FILE,
    CHECKPOINT_FORMAT,
    Checkpoint,
    RunFolder,
    checkpoint_exists,
    read_checkpoint,
    write_checkpoint,
)
from mazesim.learn.lower import LowerTables
from mazesim.learn.tables import (
    FORMAT_VERSION,
    TrainedPolicy,
    load_policy,
    write_archive,
    write_bundle,
)
from mazesim.learn.train import TrainSettings, train
from training_settings import assert_same_navigator

#: Three lower-level rounds, a checkpoint after each.
RUN = TrainSettings(
    envs=32,
    steps=32 * 500 * 3,
    seed=3,
    maze_pool=4,
    higher_episodes=2,
    higher_envs=2,
    higher_max_steps=200,
    checkpoint_seconds=0.0,
)
ROUNDS = 3


class SimulatedCrash(BaseException):
    """The process dies here (a BaseException, so no ``except Exception`` catches it)."""


@pytest.fixture(scope="module")
def uninterrupted_run(tmp_path_factory: pytest.TempPathFactory) -> tuple[TrainedPolicy, int]:
    """The navigator of a run never interrupted, and how many times the run replaced a file."""
    folder = tmp_path_factory.mktemp("uninterrupted")
    calls = []
    real_replace = os.replace

    def counting_replace(source: Any, target: Any) -> None:
        calls.append(target)
        real_replace(source, target)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(os, "replace", counting_replace)
        policy = train(RUN, RunFolder(folder), progress=None, threads=1)
    assert policy is not None
    return load_policy(folder), len(calls)


@pytest.fixture(scope="module")
def uninterrupted(uninterrupted_run: tuple[TrainedPolicy, int]) -> TrainedPolicy:
    return uninterrupted_run[0]


@pytest.fixture(scope="module")
def one_round(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A run folder stopped after its first round (its checkpoint), made once: each test that
    starts from there gets a copy (:func:`_copy_of`)."""
    folder = tmp_path_factory.mktemp("one-round") / "run"
    assert train(RUN, RunFolder(folder), progress=None, threads=1, stop_after_rounds=1) is None
    assert (folder / CHECKPOINT_FILE).is_file()
    return folder


def _copy_of(one_round: Path, folder: Path) -> Path:
    """``folder``, a copy of the run folder stopped after its first round."""
    shutil.copytree(one_round, folder, dirs_exist_ok=True)
    return folder


def _crash_at(folder: Path, crash_call: int, monkeypatch: pytest.MonkeyPatch) -> None:
    """Runs training in ``folder`` until the ``crash_call``-th file replacement, which dies."""
    calls = 0
    real_replace = os.replace

    def crashing_replace(source: Any, target: Any) -> None:
        nonlocal calls
        calls += 1
        if calls == crash_call:
            raise SimulatedCrash
        real_replace(source, target)

    with monkeypatch.context() as patch:
        patch.setattr(os, "replace", crashing_replace)
        # A killed process cleans nothing up: its temporary files stay.
        patch.setattr(os, "unlink", lambda *args, **kwargs: None)
        with pytest.raises(SimulatedCrash):
            train(RUN, RunFolder(folder), progress=None, threads=1)


def test_a_crash_at_any_file_replacement_resumes_to_the_same_tables(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, uninterrupted_run: tuple[TrainedPolicy, int]
) -> None:
    uninterrupted, replacements = uninterrupted_run
    # One per checkpoint, then the navigator's two files.
    assert replacements == ROUNDS + 2
    for crash_call in range(1, replacements + 1):
        folder = tmp_path / f"crash-{crash_call}"
        _crash_at(folder, crash_call, monkeypatch)
        leftovers = [name for name in os.listdir(folder) if name.endswith(".tmp")]
        assert leftovers, "the simulated crash should leave its temporary file"
        # The checkpoint on disk is the last whole one: absent before the first was switched in.
        whole_checkpoints = min(crash_call - 1, ROUNDS)
        if whole_checkpoints == 0:
            assert not checkpoint_exists(folder)
            with pytest.raises(PolicyFormatError, match="no checkpoint"):
                train(RUN, RunFolder(folder, resume=True), progress=None, threads=1)
            resumed = train(RUN, RunFolder(folder), progress=None, threads=1)
        else:
            saved = read_checkpoint(folder, RUN.identity())
            assert saved.next_round == whole_checkpoints
            assert len(saved.history) == whole_checkpoints
            resumed = train(RUN, RunFolder(folder, resume=True), progress=None, threads=1)
        assert resumed is not None
        assert_same_navigator(load_policy(folder), uninterrupted)
        assert [name for name in os.listdir(folder) if name.endswith(".tmp")] == []


def _metadata(saved: Checkpoint) -> dict[str, Any]:
    """The metadata of a checkpoint of ``RUN`` that holds ``saved``."""
    return {
        "format": CHECKPOINT_FORMAT,
        "version": FORMAT_VERSION,
        "settings": RUN.identity(),
        "next_round": saved.next_round,
        "history": saved.history,
        "lower_seconds": saved.lower_seconds,
    }


def test_a_checkpoint_of_mazesim_0_1_still_resumes(
    tmp_path: Path, uninterrupted: TrainedPolicy, one_round: Path
) -> None:
    folder = _copy_of(one_round, tmp_path / "old")
    saved = read_checkpoint(folder, RUN.identity())
    (folder / CHECKPOINT_FILE).unlink()
    write_bundle(
        folder,
        CHECKPOINT_FILE,
        "checkpoint.json",
        {"q": saved.tables.q, "visits": saved.tables.visits},
        _metadata(saved),
    )
    assert train(RUN, RunFolder(folder, resume=True), progress=None, threads=1) is not None
    assert_same_navigator(load_policy(folder), uninterrupted)
    # The first new checkpoint replaced the two old files with one.
    assert not (folder / "checkpoint.json").exists()


@pytest.mark.parametrize(
    ("change", "reason"),
    [
        (lambda m: {**m, "next_round": -1}, "next_round"),
        (lambda m: {**m, "next_round": 1e300}, "next_round"),
        (lambda m: {**m, "lower_seconds": 10**400}, "lower_seconds"),
        (lambda m: {**m, "history": {"a": 1}}, "history"),
        (lambda m: {**m, "lower_seconds": float("nan")}, "lower_seconds"),
        (lambda m: {k: v for k, v in m.items() if k != "settings"}, "settings"),
        (lambda m: {**m, "settings": {**m["settings"], "seed": 4}}, "other settings"),
    ],
)
def test_a_malformed_checkpoint_is_refused(
    tmp_path: Path, one_round: Path, change: Any, reason: str
) -> None:
    _copy_of(one_round, tmp_path)
    saved = read_checkpoint(tmp_path, RUN.identity())
    data = write_archive(
        {"q": saved.tables.q, "visits": saved.tables.visits},
        {"checkpoint.json": json.dumps(change(_metadata(saved))).encode()},
    )
    (tmp_path / CHECKPOINT_FILE).write_bytes(data)
    with pytest.raises(PolicyFormatError, match=reason):
        train(RUN, RunFolder(tmp_path, resume=True), progress=None, threads=1)


def test_resuming_where_no_run_wrote_a_checkpoint_says_to_start_without_resume(
    tmp_path: Path,
) -> None:
    with pytest.raises(PolicyFormatError) as refused:
        RunFolder(tmp_path / "never-trained", resume=True).start({"seed": 0})
    message = str(refused.value)
    assert message.startswith(f"{tmp_path / 'never-trained' / CHECKPOINT_FILE}: no checkpoint")
    assert message.endswith("start a fresh run there without resume")
    with _command_line(), pytest.raises(PolicyFormatError) as refused:
        RunFolder(tmp_path / "never-trained", resume=True).start({"seed": 0})
    assert str(refused.value).endswith("start a fresh run there without --resume")
    assert not (tmp_path / "never-trained").exists()


def test_other_settings_cannot_resume(tmp_path: Path, one_round: Path) -> None:
    _copy_of(one_round, tmp_path)
    other = dataclasses.replace(RUN, seed=RUN.seed + 1)
    with pytest.raises(PolicyFormatError, match="other settings"):
        train(other, RunFolder(tmp_path, resume=True), progress=None, threads=1)


def test_other_settings_name_each_setting_that_differs(tmp_path: Path, one_round: Path) -> None:
    _copy_of(one_round, tmp_path)
    other = dataclasses.replace(RUN, seed=RUN.seed + 1)
    with pytest.raises(PolicyFormatError) as refused:
        train(other, RunFolder(tmp_path, resume=True), progress=None, threads=1)
    message = str(refused.value)
    assert f"(seed: expected {RUN.seed}, found {RUN.seed + 1})" in message
    # Only the setting that differs, however long the others are.
    assert "steps" not in message.split("other settings", 1)[1]


def test_a_long_setting_that_differs_is_shown_where_it_differs() -> None:
    from mazesim.learn.checkpoint import _settings_difference

    saved = {"pool": list(range(100)), "seed": 1, "old": True}
    asked = {"pool": [*range(99), 7], "seed": 1, "new": 2}
    shown = _settings_difference(asked, saved)
    assert shown.startswith("new: expected (not set), found 2; old: expected true, found (not set)")
    pool = shown.split("pool: ", 1)[1]
    assert "99]" in pool and "7]" in pool and "differ from character" in pool
    assert "seed" not in shown


def test_the_same_checkpoint_is_written_as_the_same_bytes(tmp_path: Path) -> None:
    tables = LowerTables.zeros(False)
    tables.q[1, 2, 3] = -0.25
    tables.visits[1, 2, 3] = 7
    saved = Checkpoint(tables, 3, [{"round": 2}], 1.5)
    written = []
    for name in ("one", "two"):
        (tmp_path / name).mkdir()
        write_checkpoint(tmp_path / name, {"seed": 4}, saved)
        written.append((tmp_path / name / CHECKPOINT_FILE).read_bytes())
    assert written[0] == written[1]
    again = read_checkpoint(tmp_path / "two", {"seed": 4})
    assert again.next_round == 3 and again.history == [{"round": 2}]
    assert np.array_equal(again.tables.q, tables.q)
    assert np.array_equal(again.tables.visits, tables.visits)
