"""Named random streams: every random draw of training and evaluation comes from one of these.

A stream is ``numpy.random.SeedSequence(seed, spawn_key=(tag, *index))``: the run's seed, the
stream's tag and a fixed number of indices (a round, an episode). Tags and index counts are listed
once, in :data:`STREAMS`, and a name must always be given its number of indices, so two streams
never share a key: not two names, not two indices of a name, and not ``(k,)`` and ``(k, 0)``
(spawn keys of different lengths differ anyway, but a fixed count keeps every key unambiguous).
Ad-hoc seed lists are not used: numpy pads short entropy lists with zeros, so
``default_rng([s, 1, 0])`` is ``default_rng([s, 1])``.

Example:
    >>> from mazesim._seeding import stream
    >>> rng = stream(0, "lower/round", 3)
    >>> 0.0 <= float(rng.random()) < 1.0
    True
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from mazesim.errors import InvalidArgumentError, RegisteredName, _known_name, _shown

__all__ = ["STREAMS", "seed_sequence", "stream", "stream_seeds"]

#: Every named stream: its tag in the spawn key and the number of indices that follow it.
STREAMS: dict[str, tuple[int, int]] = {
    # The pool of generated mazes the lower level trains on.
    "lower/mazes": (1, 0),
    # A lower-level round: its episodes' starts, noise seeds and exploration (index: round).
    "lower/round": (2, 1),
    # A higher-level training episode's start jitter and noise seed (index: episode number).
    "higher/episode": (3, 1),
    # The higher level's exploration draws.
    "higher/explore": (4, 0),
    # A flat learner's training episode (index: episode number).
    "flat/episode": (5, 1),
    # The flat learner's exploration draws.
    "flat/explore": (6, 0),
    # An evaluation episode's start jitter and noise seed (index: episode number).
    "evaluate/episode": (7, 1),
    # The unseen generated mazes of the transfer test.
    "evaluate/mazes": (8, 0),
    # A transfer study's episode, the same in every cell (index: episode number).
    "transfer/episode": (9, 1),
    # The wake-ups of a transfer study's unsynchronised link.
    "transfer/link": (10, 0),
    # The perturbed robot of each env of a domain-randomised round (index: round).
    "randomise/profiles": (11, 1),
    # The base robot profile of each env of a domain-randomised round (index: round).
    "randomise/robots": (12, 1),
}


def seed_sequence(seed: int, name: RegisteredName, *index: int) -> np.random.SeedSequence:
    """The seed sequence of stream ``name`` of a run's ``seed``.

    Args:
        seed: The run's seed (a non-negative int).
        name: A key of :data:`STREAMS`.
        *index: The stream's indices, as many as :data:`STREAMS` lists for it.

    Raises:
        InvalidArgumentError: An unknown name, a wrong number of indices, or a negative value.
    """
    _known_name(name, "the name of a random stream", tuple(STREAMS))
    tag, arity = STREAMS[name]
    if len(index) != arity:
        raise InvalidArgumentError(
            f"expected {arity} index(es) for random stream {_shown(name)}, found {len(index)}"
        )
    values = (int(seed), *(int(i) for i in index))
    if min(values) < 0:
        raise InvalidArgumentError(
            f"expected a non-negative seed and indices for random stream {_shown(name)}, found "
            f"{values}"
        )
    return np.random.SeedSequence(int(seed), spawn_key=(tag, *values[1:]))


def stream(seed: int, name: str, *index: int) -> np.random.Generator:
    """A generator drawing from stream ``name`` (see :func:`seed_sequence`)."""
    return np.random.default_rng(seed_sequence(seed, name, *index))


def stream_seeds(seed: int, name: str, count: int, *index: int) -> npt.NDArray[np.uint64]:
    """``count`` 64-bit seeds from stream ``name`` (for simulators and generated mazes)."""
    state = seed_sequence(seed, name, *index).generate_state(count, np.uint64)
    return np.asarray(state, dtype=np.uint64)
