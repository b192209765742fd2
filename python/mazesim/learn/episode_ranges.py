"""A navigator's evaluation episodes in chunks that run anywhere (``mazesim eval --address``).

:func:`mazesim.learn.evaluate.evaluate` runs ``episodes_per_world`` greedy episodes in each of its
worlds; episode ``k`` of world ``w`` is numbered ``w * episodes_per_world + k`` and draws its
start jitter and sensor noise from ``(seed, number)`` alone
(:class:`mazesim.episodes.EpisodeBatch`), and a greedy navigator keeps nothing from one
episode to the next. So the episodes numbered ``first`` to ``first + count - 1`` can run anywhere,
in any company, and end the same: :class:`NavigatorEpisodes` holds what they need (the tables,
the worlds as TOML text, the robot profile, which pickles as its TOML text unless it is a
built-in one, so a profile file's robot needs no file where the chunk runs) and runs such a
chunk, handing back its episodes' :class:`~mazesim.episodes.EpisodeResult` list, numbered and
placed as ``evaluate`` numbers and places them. Whoever spreads the chunks (the evaluator's
``spread`` argument, :func:`mazesim.distributed.evaluate_episodes` on Ray) joins the lists in
episode order, and the evaluator summarises them once (:func:`mazesim.learn.summary.summarise`),
as it does the episodes it runs itself.

A chunk runs its episodes side by side, up to :data:`CHUNK_ENVS` at a time, one robot per
episode.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim._core import RobotProfile, World
from mazesim._sizes import index_array
from mazesim.episodes import EpisodeBatch, EpisodeResult, run_episodes
from mazesim.errors import InvalidArgumentError, _known_name, _shown
from mazesim.learn.higher import HigherLevel

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
        slots = index_array(episodes, "episodes", len(self.numbers))
        super().start(envs, self.numbers[slots])


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
        hold_heading: The navigator holds its heading where blind (hierarchical;
            :attr:`mazesim.learn.tables.TrainedPolicy.hold_heading`).
        robot: The profile every robot drives; None: the report's seed robot.
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
    hold_heading: bool = False
    robot: RobotProfile | None = None

    def __post_init__(self) -> None:
        _known_name(self.kind, "a navigator's kind", ("hierarchical", "flat"))
        tables = (self.lower_q, self.higher_q) if self.kind == "hierarchical" else (self.flat_q,)
        if any(t is None for t in tables):
            raise InvalidArgumentError(
                f"expected a hierarchical navigator with lower and higher tables or a flat one "
                f"with its table, found kind {_shown(self.kind)}"
            )
        if self.kind == "flat" and len(self.world_tomls) != 1:
            raise InvalidArgumentError("the flat baseline drives the one world it learned")

    @property
    def episodes(self) -> int:
        """Episodes of the whole evaluation."""
        return len(self.world_tomls) * self.episodes_per_world

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
        return HierarchicalPolicy(self.lower_q, level, robots, hold_heading=self.hold_heading)

    def __call__(self, first: int, count: int) -> list[EpisodeResult]:
        """Runs episodes ``first`` to ``first + count - 1``.

        Returns:
            Their results, in episode order, numbered and placed in worlds as
            :func:`mazesim.learn.evaluate.evaluate` numbers and places them.
        """
        if first < 0 or count < 1 or first + count > self.episodes:
            raise InvalidArgumentError(
                f"expected episodes within 0..{self.episodes - 1}, "
                f"found {first}..{first + count - 1}"
            )
        worlds = [World.from_toml(text) for text in self.world_tomls]
        numbers = np.arange(first, first + count, dtype=np.int64)
        world_of_episode = numbers // self.episodes_per_world
        results: list[EpisodeResult] = []
        for start in range(0, count, CHUNK_ENVS):
            part = numbers[start : start + CHUNK_ENVS]
            slot_worlds = world_of_episode[start : start + part.size]
            nav = _NumberedEpisodes(
                [worlds[w] for w in slot_worlds],
                part,
                seed=self.seed,
                max_steps=self.max_steps,
                events=self.events,
                threads=self.threads,
                robot="seed" if self.robot is None else self.robot,
            )
            navigator = self._navigator(slot_worlds)
            decisions = navigator.record.decisions
            for result in run_episodes(nav, navigator, 1, None, None, decisions):
                world = int(world_of_episode[result.episode - first])
                results.append(dataclasses.replace(result, world=world))
        return sorted(results, key=lambda result: result.episode)

    def check_joined(self, results: Sequence[EpisodeResult]) -> list[EpisodeResult]:
        """The joined results of every chunk, checked to be episodes ``0 .. episodes - 1`` in
        order.

        Raises:
            InvalidArgumentError: An episode is missing, repeated or out of order.
        """
        numbers = [result.episode for result in results]
        if numbers != list(range(self.episodes)):
            raise InvalidArgumentError(
                f"expected the results of episodes 0..{self.episodes - 1} in order, found "
                f"{len(numbers)} results numbered {numbers[:3]}...{numbers[-3:]}"
            )
        return list(results)
