"""What episodes measured: :class:`Summary`, the one result type of an evaluation, and
:func:`summarise`, the one place that turns episodes into measures.

Every measure of a navigator comes from here: ``mazesim eval`` (one summary per source of
checkpoint events), the transfer study's cells (one summary per setting), a sweep's evaluation
values, the evaluation spread over Ray (the chunks hand back their
:class:`~mazesim.episodes.EpisodeResult` lists, summarised once when joined), and the share of
a training run's last episodes that reached the goal.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from mazesim.episodes import EpisodeResult
from mazesim.learn.subtasks import SUBTASK_CODES

__all__ = ["Summary", "summarise"]

#: Fields of :class:`Summary` that are not among the ``--json`` output's values.
_NOT_IN_JSON = ("decisions", "events", "world_success", "mean_steps_all", "env_steps", "adapted")


@dataclass
class Summary:
    """What a set of episodes measured.

    Attributes:
        episodes: Episodes run.
        success_rate: Share of them that reached the goal.
        mean_collisions: Wall bumps (contacts the simulator counts) per episode.
        mean_steps: Mean control steps of the arrived episodes (``None`` when none arrived).
        mean_path_ratio: Mean ratio of an arrived episode's steps to its world's shortest path's
            (``None`` when none arrived).
        collision_free_rate: Share of episodes without a bump.
        events: Where the checkpoint events came from (``"truth"`` or ``"robust"``).
        decisions: Per checkpoint event (``"+3"``: arrival at checkpoint 3), how often the
            higher level chose each sub-task.
        world_success: Each world's share of episodes that reached the goal.
        mean_steps_all: Mean steps over every episode, a failed one counted at its limit (a
            sweep's ``mean_steps``).
        env_steps: Control steps of all the episodes together.
        adapted: Whether the higher level was trained in these worlds first (worlds it had not
            learned).
    """

    episodes: int
    success_rate: float
    mean_collisions: float
    mean_steps: float | None
    mean_path_ratio: float | None
    collision_free_rate: float
    events: str
    decisions: dict[str, dict[str, int]] = field(default_factory=dict)
    world_success: list[float] = field(default_factory=list)
    mean_steps_all: float = 0.0
    env_steps: int = 0
    adapted: bool = False

    def as_json(self) -> dict[str, Any]:
        """The summary as the ``--json`` output's values."""
        values = asdict(self)
        for private in _NOT_IN_JSON:
            values.pop(private)
        return values


def _decision_counts(results: Sequence[EpisodeResult]) -> dict[str, dict[str, int]]:
    """How often each sub-task was chosen at each checkpoint event, events in order of
    checkpoint (arrival before departure), sub-tasks by code."""
    decisions: dict[str, Counter[str]] = {}
    for result in results:
        for event, option in result.decisions:
            key = f"{'+' if event > 0 else '-'}{abs(event)}"
            decisions.setdefault(key, Counter())[SUBTASK_CODES[option]] += 1
    ordered = sorted(decisions.items(), key=lambda item: (abs(int(item[0])), item[0][0] == "-"))
    return {key: dict(sorted(counts.items())) for key, counts in ordered}


def summarise(
    results: Sequence[EpisodeResult], shortest: Sequence[float], events: str = "truth"
) -> Summary:
    """What ``results`` measured: the one computation of every measure of :class:`Summary`.

    Args:
        results: The episodes.
        shortest: The shortest path's control steps of each world (indexed by
            :attr:`~mazesim.episodes.EpisodeResult.world`), for the path ratio.
        events: Where the checkpoint events came from.
    """
    arrived = [r for r in results if r.arrived]
    count = len(results)
    worlds = max((r.world for r in results), default=-1) + 1
    per_world: list[list[bool]] = [[] for _ in range(worlds)]
    for result in results:
        per_world[result.world].append(result.arrived)
    return Summary(
        episodes=count,
        success_rate=len(arrived) / count if count else 0.0,
        mean_collisions=float(np.mean([r.bumps for r in results])) if count else 0.0,
        mean_steps=float(np.mean([r.steps for r in arrived])) if arrived else None,
        mean_path_ratio=(
            float(np.mean([r.steps / shortest[r.world] for r in arrived])) if arrived else None
        ),
        collision_free_rate=sum(1 for r in results if r.bumps == 0) / count if count else 0.0,
        events=events,
        decisions=_decision_counts(results),
        world_success=[float(np.mean(outcomes)) if outcomes else 0.0 for outcomes in per_world],
        mean_steps_all=float(np.mean([r.steps for r in results])) if count else 0.0,
        env_steps=sum(r.steps for r in results),
    )
