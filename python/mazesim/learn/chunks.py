"""A navigator's evaluation episodes in chunks that run anywhere (``mazesim eval --address``).

:func:`mazesim.learn.evaluate.evaluate` runs ``episodes_per_world`` greedy episodes in each of its
worlds; episode ``k`` of world ``w`` is numbered ``w * episodes_per_world + k`` and draws its
start jitter and sensor noise from ``(seed, number)`` alone
(:class:`mazesim.episodes.EpisodeBatch`), and a greedy navigator keeps nothing from one
episode to the next. So the episodes numbered ``first`` to ``first + count - 1`` can run anywhere,
in any company, and end the same: :class:`NavigatorEpisodes` holds what they need (the tables,
the worlds as TOML text) and runs such a chunk; whoever spreads the chunks (the evaluator's
``spread`` argument, :func:`mazesim.distributed.evaluate_episodes` on Ray) joins their arrays,
and :meth:`NavigatorEpisodes.results` turns them back into the
:class:`~mazesim.episodes.EpisodeResult` list that ``evaluate`` returns.

A chunk runs its episodes side by side, up to :data:`mazesim.learn.evaluate.EVALUATION_ENVS` at a
time, one robot per episode. The decisions of an episode come back as counts per (checkpoint
event, sub-task), so its :attr:`~mazesim.episodes.EpisodeResult.decisions` list holds the
same decisions in a fixed order rather than in the order they were taken.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._core import World
from mazesim.episodes import EpisodeBatch, EpisodeResult, run_episodes
from mazesim.errors import InvalidArgumentError
from mazesim.learn.higher import HigherLevel
from mazesim.learn.subtasks import NUM_SUBTASKS

__all__ = ["NavigatorEpisodes"]

#: Robots a chunk steps side by side (at most).
CHUNK_ENVS = 500


class _NumberedEpisodes(EpisodeBatch):
    """A batch whose robot ``i`` is alone in world slot ``i`` and runs episode ``numbers[i]``."""

    def __init__(
        self, worlds: Sequence[World], numbers: npt.NDArray[np.int64], **options: Any
    ) -> None:
        super().__init__(worlds, np.arange(len(worlds)), **options)
        self.numbers = numbers

    def start(self, envs: npt.ArrayLike, episodes: npt.ArrayLike) -> None:
        """Starts the episodes whose slots are ``episodes`` under their evaluation numbers."""
        super().start(envs, self.numbers[np.asarray(episodes, dtype=np.int64)])


@dataclass(frozen=True, eq=False)
class NavigatorEpisodes:
    """An evaluation of a navigator that runs any chunk of its episodes by itself.

    Attributes:
        kind: ``"hierarchical"`` or ``"flat"``.
        world_tomls: The worlds, as :meth:`mazesim.World.to_toml` text.
        episodes_per_world: Episodes in each world.
        seed: Seed of the episodes' start jitter and sensor noise.
        events: ``"truth"`` or ``"robust"``.
        max_steps: Control steps after which an episode fails.
        checkpoint_ids: The checkpoint ids of each world's higher level (of the one world of a
            flat navigator).
        lower_q: The lower-level tables (hierarchical).
        higher_q: The higher-level tables, ``(worlds, states, 4)`` (hierarchical).
        flat_q: The flat table (flat).
        threads: Batch-engine threads of a chunk.
    """

    kind: str
    world_tomls: tuple[str, ...]
    episodes_per_world: int
    seed: int
    events: str
    max_steps: int
    checkpoint_ids: tuple[tuple[int, ...], ...]
    lower_q: npt.NDArray[np.float64] | None = None
    higher_q: npt.NDArray[np.float64] | None = None
    flat_q: npt.NDArray[np.float64] | None = None
    threads: int = 1

    def __post_init__(self) -> None:
        tables = (self.lower_q, self.higher_q) if self.kind == "hierarchical" else (self.flat_q,)
        if self.kind not in ("hierarchical", "flat") or any(t is None for t in tables):
            raise InvalidArgumentError(
                f"expected a hierarchical navigator with lower and higher tables or a flat one "
                f"with its table, found kind {self.kind!r}"
            )
        if self.kind == "flat" and len(self.world_tomls) != 1:
            raise InvalidArgumentError("the flat baseline drives the one world it learned")

    @property
    def episodes(self) -> int:
        """Episodes of the whole evaluation."""
        return len(self.world_tomls) * self.episodes_per_world

    @property
    def _largest_id(self) -> int:
        return max((max(ids) for ids in self.checkpoint_ids if ids), default=0)

    def _navigator(self, slot_worlds: npt.NDArray[np.int64]) -> Any:
        """The navigator of robots that drive in worlds ``slot_worlds`` (one slot each)."""
        robots = np.arange(slot_worlds.size)
        if self.kind == "flat":
            from mazesim.learn.baseline import FlatNavigator

            assert self.flat_q is not None
            return FlatNavigator(self.flat_q, list(self.checkpoint_ids[0]), robots.size)
        from mazesim.learn.policy import HierarchicalPolicy

        assert self.lower_q is not None and self.higher_q is not None
        level = HigherLevel([self.checkpoint_ids[w] for w in slot_worlds])
        level.q[:] = self.higher_q[slot_worlds, : level.num_states]
        return HierarchicalPolicy(self.lower_q, level, robots)

    def __call__(self, first: int, count: int) -> dict[str, npt.NDArray[Any]]:
        """Runs episodes ``first`` to ``first + count - 1``.

        Returns:
            Per-episode arrays: ``world``, ``arrived``, ``steps``, ``bumps``,
            ``contact_steps``, and ``decisions``, ``(count, 2 * largest id + 1, 4)`` counts of
            the sub-task chosen at each checkpoint event (index ``event + largest id``).
        """
        if first < 0 or count < 1 or first + count > self.episodes:
            raise InvalidArgumentError(
                f"expected episodes within 0..{self.episodes - 1}, "
                f"found {first}..{first + count - 1}"
            )
        worlds = [World.from_toml(text) for text in self.world_tomls]
        largest = self._largest_id
        numbers = np.arange(first, first + count, dtype=np.int64)
        arrays: dict[str, npt.NDArray[Any]] = {
            "world": numbers // self.episodes_per_world,
            "arrived": np.zeros(count, dtype=bool),
            "steps": np.zeros(count, dtype=np.int64),
            "bumps": np.zeros(count, dtype=np.int64),
            "contact_steps": np.zeros(count, dtype=np.int64),
            "decisions": np.zeros((count, 2 * largest + 1, NUM_SUBTASKS), dtype=np.int64),
        }
        for start in range(0, count, CHUNK_ENVS):
            part = numbers[start : start + CHUNK_ENVS]
            slot_worlds = arrays["world"][start : start + part.size]
            nav = _NumberedEpisodes(
                [worlds[w] for w in slot_worlds],
                part,
                seed=self.seed,
                max_steps=self.max_steps,
                events=self.events,
                threads=self.threads,
            )
            navigator = self._navigator(slot_worlds)

            def decisions_of(
                navigator: Any = navigator,
            ) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]:
                robots = np.flatnonzero(navigator.record.chosen >= 0)
                return robots, navigator.record.chosen[robots]

            for result in run_episodes(nav, navigator, 1, None, None, decisions_of):
                row = result.episode - first
                arrays["arrived"][row] = result.arrived
                arrays["steps"][row] = result.steps
                arrays["bumps"][row] = result.bumps
                arrays["contact_steps"][row] = result.contact_steps
                for event, option in result.decisions:
                    arrays["decisions"][row, event + largest, option] += 1
        return arrays

    def results(self, arrays: Mapping[str, npt.ArrayLike]) -> list[EpisodeResult]:
        """The episodes of the joined arrays of every chunk (episodes ``0 .. episodes - 1``)."""
        largest = self._largest_id
        columns = {name: np.asarray(values) for name, values in arrays.items()}
        results = []
        for number in range(columns["arrived"].shape[0]):
            counts = columns["decisions"][number]
            decisions = [
                (int(index) - largest, int(option))
                for index, option in zip(*np.nonzero(counts))
                for _ in range(int(counts[index, option]))
            ]
            results.append(
                EpisodeResult(
                    world=int(columns["world"][number]),
                    episode=number,
                    arrived=bool(columns["arrived"][number]),
                    steps=int(columns["steps"][number]),
                    bumps=int(columns["bumps"][number]),
                    contact_steps=int(columns["contact_steps"][number]),
                    decisions=decisions,
                )
            )
        return results
