"""An evaluation that records every one of its episodes (the demo's one episode) runs each
episode once, and records what the faster path's second run of it recorded."""

from __future__ import annotations

import argparse
import io
import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import mazesim
from mazesim.cli.demo_hrl import run_hrl_demo
from mazesim.learn import evaluate as evaluate_module
from mazesim.learn.evaluate import EvaluationRecord, evaluate_navigator
from mazesim.learn.tables import load_policy
from mazesim.replay.navigator import Recording


class CountingBatch(evaluate_module.EpisodeBatch):  # type: ignore[misc]
    """An episode batch that remembers every instance made, to count the steps they took."""

    made: list[CountingBatch] = []

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        CountingBatch.made.append(self)


def test_the_demo_steps_its_episode_once(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    CountingBatch.made = []
    monkeypatch.setattr(evaluate_module, "EpisodeBatch", CountingBatch)
    args = argparse.Namespace(world="seed-maze", seconds=20.0, seed=0, out=str(tmp_path))
    assert run_hrl_demo(args, io.StringIO()) == 0
    summary = json.loads((tmp_path / "summary.json").read_text())
    stepped = sum(int(batch.batch.simulator.steps().sum()) for batch in CountingBatch.made)
    assert summary["steps"] > 100
    assert len(CountingBatch.made) == 1
    assert stepped == summary["steps"]


def test_one_pass_records_what_the_second_run_recorded() -> None:
    policy = load_policy(None)
    world = mazesim.load_world("seed-maze")
    once = EvaluationRecord(paths=1, trace=True, recorder=Recording(1))
    twice = EvaluationRecord(paths=1, trace=True, recorder=Recording(1))
    # One episode, all recorded: one pass. Two episodes: the core runs both, then the first runs
    # again to be recorded.
    alone = evaluate_navigator(policy, [world], 1, seed=5, record=once, max_steps=400)
    beside = evaluate_navigator(policy, [world], 2, seed=5, record=twice, max_steps=400)
    assert alone["truth"].episodes == 1 and beside["truth"].episodes == 2
    assert once.outcomes == twice.outcomes and sorted(once.outcomes) == [0]
    assert once.trace_lines == twice.trace_lines and len(once.trace_lines) > 400
    assert once.marks == twice.marks
    np.testing.assert_array_equal(once.episode_paths[0], twice.episode_paths[0])
    assert once.run is not None and twice.run is not None
    assert once.run.as_json() == twice.run.as_json()
