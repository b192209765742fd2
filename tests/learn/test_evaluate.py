"""The evaluator: one result type, the trace of episode 0, and evaluation streams of their own."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

import mazesim
from mazesim.cli import main
from mazesim.episodes import EpisodeResult
from mazesim.learn.evaluate import evaluate_navigator, summarise
from mazesim.learn.tables import load_policy


def test_trace_ends_with_its_episode(tmp_path: Path, capsys: Any) -> None:
    # A robot whose episode ended waits, still stepped, while the others finish theirs; the trace
    # of episode 0 used to follow it on after the goal, and so differed with the episode count.
    traces = [tmp_path / "one.txt", tmp_path / "three.txt"]
    for episodes, trace in zip(("1", "3"), traces):
        assert (
            main(["eval", "--episodes", episodes, "--events", "truth", "--trace", str(trace)]) == 0
        )
    capsys.readouterr()
    assert traces[0].read_text() == traces[1].read_text()
    assert traces[1].read_text().splitlines()[-1].startswith("# goal reached after")


def test_evaluation_episodes_are_not_training_episodes() -> None:
    # Issue 17: evaluation drew the higher level's training episodes (the same seed and stream);
    # now its episodes start from a stream of their own.
    from mazesim.episodes import EpisodeBatch

    world = mazesim.load_world("seed-maze")
    starts = []
    for stream in ("higher/episode", "evaluate/episode"):
        nav = EpisodeBatch([world], num_envs=3, stream=stream)
        nav.start(np.arange(3), np.arange(3))
        starts.append(nav.poses.copy())
    assert not np.any(np.all(starts[0] == starts[1], axis=1))


def test_progress_counts_every_episode() -> None:
    seen: list[tuple[str, int, int]] = []
    summaries = evaluate_navigator(
        load_policy(),
        [mazesim.load_world("seed-maze")],
        3,
        max_steps=200,
        progress=lambda stage, done, total: seen.append((stage, done, total)),
    )
    assert summaries["truth"].episodes == 3
    assert seen[0] == ("evaluate", 0, 3) and seen[-1] == ("evaluate", 3, 3)
    assert [done for _, done, _ in seen] == sorted(done for _, done, _ in seen)


def test_a_summary_counts_steps_of_arrivals_and_of_every_episode() -> None:
    # Issue 17: the sweep reads the evaluator's one result type, whose mean over every episode
    # (a failed one at its limit) is the sweep's mean_steps; mean_steps counts arrivals only.
    results = [
        EpisodeResult(world=0, episode=0, arrived=True, steps=100, bumps=0, contact_steps=0),
        EpisodeResult(world=0, episode=1, arrived=False, steps=400, bumps=3, contact_steps=9),
    ]
    summary = summarise(results, [50.0], "truth")
    assert (summary.success_rate, summary.mean_collisions) == (0.5, 1.5)
    assert (summary.mean_steps, summary.mean_path_ratio) == (100.0, 2.0)
    assert summary.mean_steps_all == 250.0
    assert "mean_steps_all" not in summary.as_json()
