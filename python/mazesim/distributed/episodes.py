"""Spreading the episodes of one evaluation over Ray workers.

An evaluation is given as a function ``evaluate_chunk(first, count)`` that runs episodes
``first`` to ``first + count - 1`` and returns per-episode arrays (``reached``, ``steps``, ...),
each of length ``count``. When episode ``e``'s outcome depends only on ``e`` and the
evaluation's seed (as :func:`mazesim.learn.evaluate.evaluate_navigator` guarantees), any split
into chunks gives the same episodes: :func:`evaluate_episodes` runs the chunks as Ray tasks, each
on its own batch engine, and joins their arrays in episode order.

Example (``policy`` a saved navigator, ``world`` its world)::

    from mazesim.distributed.episodes import ray_spreader
    from mazesim.learn.evaluate import evaluate_navigator

    report = evaluate_navigator(policy, [world], 10_000, spread=ray_spreader("auto"))
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim.distributed.cluster import local_cpus, ray_session
from mazesim.errors import InvalidArgumentError, MazesimError

__all__ = ["EpisodeChunk", "evaluate_episodes", "ray_spreader", "split_episodes"]

EpisodeChunk = Callable[[int, int], Mapping[str, npt.ArrayLike]]


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


def _run_chunk(evaluate_chunk: EpisodeChunk, first: int, count: int) -> dict[str, Any]:
    return {name: np.asarray(values) for name, values in evaluate_chunk(first, count).items()}


def _join(parts: list[dict[str, Any]], chunks: list[tuple[int, int]]) -> dict[str, Any]:
    names = set(parts[0])
    for part, (first, count) in zip(parts, chunks):
        if set(part) != names or any(np.shape(values)[:1] != (count,) for values in part.values()):
            shapes = {name: np.shape(values) for name, values in part.items()}
            raise InvalidArgumentError(
                f"episodes {first}..{first + count - 1}: expected arrays {sorted(names)} of "
                f"length {count}, found {shapes}"
            )
    return {name: np.concatenate([part[name] for part in parts]) for name in parts[0]}


def evaluate_episodes(
    evaluate_chunk: EpisodeChunk,
    episodes: int,
    address: str | None = None,
    *,
    chunks: int | None = None,
    cpus_per_chunk: int = 1,
    max_retries: int = 2,
    cpus: int | None = None,
) -> dict[str, npt.NDArray[Any]]:
    """Runs the episodes of an evaluation as Ray tasks and joins their per-episode arrays.

    Args:
        evaluate_chunk: ``evaluate_chunk(first, count)`` -> per-episode arrays of length
            ``count``; it must be picklable (a module-level function or a
            :func:`functools.partial` of one).
        episodes: Number of episodes.
        address: A Ray cluster to join; ``None`` or ``"local"`` starts a local Ray instance
            (Ray already initialised in this process is used as it is).
        chunks: Number of tasks (by default two per CPU of the cluster).
        cpus_per_chunk: CPUs each task asks Ray for.
        max_retries: Times a task whose worker died is run again.
        cpus: CPUs of a local Ray instance (by default this machine's cores).

    Returns:
        Each array of the chunks, joined in episode order.

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


def ray_spreader(address: str | None) -> Callable[[EpisodeChunk, int], dict[str, Any]]:
    """:func:`evaluate_episodes` at ``address``, as the ``spread`` argument of
    :func:`mazesim.learn.evaluate.evaluate_navigator` takes it."""

    def spread(evaluate_chunk: EpisodeChunk, episodes: int) -> dict[str, Any]:
        return evaluate_episodes(evaluate_chunk, episodes, address=address)

    return spread
