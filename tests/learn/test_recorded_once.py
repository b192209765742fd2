"""An evaluation that records its first episodes (the demo's one episode, ``mazesim eval``'s
paths, trace and replay) runs each episode once, the recorded ones read from the core's
per-step trace, and records what stepping them one at a time records."""

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


def test_an_evaluation_steps_its_recorded_episodes_once(monkeypatch: pytest.MonkeyPatch) -> None:
    CountingBatch.made = []
    monkeypatch.setattr(evaluate_module, "EpisodeBatch", CountingBatch)
    record = EvaluationRecord(paths=2, trace=True, recorder=Recording(2))
    policy = load_policy(None)
    world = mazesim.load_world("seed-maze")
    summary = evaluate_navigator(policy, [world], 4, seed=1, record=record, max_steps=900)
    stepped = sum(int(batch.batch.simulator.steps().sum()) for batch in CountingBatch.made)
    assert len(CountingBatch.made) == 1
    assert stepped == summary["truth"].env_steps > 400
    assert sorted(record.outcomes) == [0, 1] and record.run is not None
    assert len(record.run.episodes) == 2 and len(record.trace_lines) > 100


def test_one_pass_records_what_stepping_one_at_a_time_records() -> None:
    policy = load_policy(None)
    world = mazesim.load_world("seed-maze")
    once = EvaluationRecord(paths=1, trace=True, recorder=Recording(1))
    twice = EvaluationRecord(paths=1, trace=True, recorder=Recording(1))
    # The core runs both episodes and records the first from its trace; one step at a time.
    alone = evaluate_navigator(policy, [world], 2, seed=5, record=once, max_steps=400)
    beside = evaluate_navigator(
        policy, [world], 2, seed=5, record=twice, max_steps=400, multi_step=False
    )
    assert alone == beside and alone["truth"].episodes == 2
    assert once.outcomes == twice.outcomes and sorted(once.outcomes) == [0]
    assert once.trace_lines == twice.trace_lines and len(once.trace_lines) > 400
    assert once.marks == twice.marks
    np.testing.assert_array_equal(once.episode_paths[0], twice.episode_paths[0])
    assert once.run is not None and twice.run is not None
    assert once.run.as_json() == twice.run.as_json()
