"""Spreading the episodes of one evaluation over Ray workers.

An evaluation is given as a function ``evaluate_chunk(first, count)`` that runs episodes
``first`` to ``first + count - 1`` and returns their results, one per episode in order (the
navigator's chunks, :class:`mazesim.learn.episode_ranges.NavigatorEpisodes`, return
:class:`~mazesim.episodes.EpisodeResult` lists). When episode ``e``'s outcome depends only on
``e`` and the evaluation's seed (as :func:`mazesim.learn.evaluate.evaluate_navigator`
guarantees), any split into chunks gives the same episodes: :func:`evaluate_episodes` runs the
chunks as Ray tasks, each on its own batch engine, and joins their results in episode order; the
evaluator summarises them once (:func:`mazesim.learn.summary.summarise`).

Example (``policy`` a saved navigator, ``world`` its world)::

    from mazesim.distributed.episodes import ray_spreader
    from mazesim.learn.evaluate import evaluate_navigator

    summaries = evaluate_navigator(policy, [world], 10_000, spread=ray_spreader("auto"))
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

from mazesim.distributed.cluster import local_cpus, ray_session
from mazesim.errors import InvalidArgumentError, MazesimError

__all__ = ["EpisodeChunk", "evaluate_episodes", "ray_spreader", "split_episodes"]

#: Runs episodes ``first`` to ``first + count - 1`` as ``chunk(first, count)`` and returns their
#: results, one per episode in order.
EpisodeChunk = Callable[[int, int], Sequence[Any]]


def split_episodes(episodes: int, chunks: int) -> list[tuple[int, int]]:
    """Splits episodes ``0 .. episodes - 1`` into at most ``chunks`` runs of consecutive episodes
    of nearly equal length, as ``(first, count)`` pairs."""
    if episodes < 1 or chunks < 1:
        raise InvalidArgumentError(
            f"expected at least one episode and one chunk, found {episodes} and {chunks}"
        )
    chunks = min(chunks, episodes)
    bounds = [episodes * index // chunks for index in range(chunks + 1)]
    return [(bounds[i], bounds[i + 1] - bounds[i]) for i in range(chunks)]


def _run_chunk(evaluate_chunk: EpisodeChunk, first: int, count: int) -> list[Any]:
    return list(evaluate_chunk(first, count))


def _join(parts: list[list[Any]], chunks: list[tuple[int, int]]) -> list[Any]:
    """The chunks' results in episode order, each chunk checked to hold one per episode."""
    for part, (first, count) in zip(parts, chunks):
        if len(part) != count:
            raise InvalidArgumentError(
                f"episodes {first}..{first + count - 1}: expected {count} results, "
                f"found {len(part)}"
            )
    return [result for part in parts for result in part]


def evaluate_episodes(
    evaluate_chunk: EpisodeChunk,
    episodes: int,
    address: str | None = None,
    *,
    chunks: int | None = None,
    cpus_per_chunk: int = 1,
    max_retries: int = 2,
    cpus: int | None = None,
) -> list[Any]:
    """Runs the episodes of an evaluation as Ray tasks and joins their results.

    Args:
        evaluate_chunk: ``evaluate_chunk(first, count)`` -> the ``count`` episodes' results,
            in order; it must be picklable (a module-level function or a
            :func:`functools.partial` of one).
        episodes: Number of episodes.
        address: A Ray cluster to join; ``None`` or ``"local"`` starts a local Ray instance
            (Ray already initialised in this process is used as it is).
        chunks: Number of tasks (by default two per CPU of the cluster).
        cpus_per_chunk: CPUs each task asks Ray for.
        max_retries: Times a task whose worker died is run again.
        cpus: CPUs of a local Ray instance (by default this machine's cores).

    Returns:
        The results of every episode, in episode order.

    Raises:
        MazesimError: A chunk failed on every attempt (the message names its episodes).
        MissingDependencyError: Ray is not installed.
    """
    with ray_session(address, cpus or local_cpus()) as ray:
        if chunks is None:
            chunks = 2 * max(1, int(ray.cluster_resources().get("CPU", 1)))
        plan = split_episodes(episodes, chunks)
        shared = ray.put(evaluate_chunk)
        remote = ray.remote(_run_chunk).options(
            num_cpus=cpus_per_chunk, max_retries=max_retries, retry_exceptions=False
        )
        references = [remote.remote(shared, first, count) for first, count in plan]
        parts = []
        for reference, (first, count) in zip(references, plan):
            try:
                parts.append(ray.get(reference))
            except ray.exceptions.RayError as error:
                for other in references:
                    ray.cancel(other, force=True)
                raise MazesimError(
                    f"evaluation episodes {first}..{first + count - 1} failed: "
                    f"{type(error).__name__}: {str(error).splitlines()[0] if str(error) else ''}"
                ) from error
    return _join(parts, plan)


def ray_spreader(address: str | None) -> Callable[[EpisodeChunk, int], list[Any]]:
    """:func:`evaluate_episodes` at ``address``, as the ``spread`` argument of
    :func:`mazesim.learn.evaluate.evaluate_navigator` takes it."""

    def spread(evaluate_chunk: EpisodeChunk, episodes: int) -> list[Any]:
        return evaluate_episodes(evaluate_chunk, episodes, address=address)

    return spread
