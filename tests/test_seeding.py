"""Named random streams: distinct for every name and index, and refused when misnamed."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from mazesim._seeding import STREAMS, seed_sequence, stream, stream_seeds
from mazesim.errors import InvalidArgumentError, UnknownNameError


def _keys() -> list[tuple[str, tuple[int, ...]]]:
    keys = []
    for name, (_, arity) in STREAMS.items():
        for index in itertools.product(range(3), repeat=arity):
            keys.append((name, index))
    return keys


def test_every_named_stream_and_index_draws_differently() -> None:
    for seed in (0, 1, 2):
        draws = {}
        for name, index in _keys():
            state = tuple(seed_sequence(seed, name, *index).generate_state(4).tolist())
            assert state not in draws.values(), f"{name}{index} repeats another stream"
            draws[(name, index)] = state
    # Seeds 0 and 1 do not share a stream either.
    firsts = {tuple(stream_seeds(s, n, 2, *i).tolist()) for s in (0, 1) for n, i in _keys()}
    assert len(firsts) == 2 * len(_keys())


def test_tags_are_unique() -> None:
    tags = [tag for tag, _ in STREAMS.values()]
    assert len(set(tags)) == len(tags)


def test_the_zero_padding_trap_cannot_recur() -> None:
    # numpy pads entropy lists with zeros: the old ad-hoc lists collided.
    old_round_0 = np.random.default_rng([0, 1, 0]).random(3)
    old_episode_1 = np.random.default_rng([0, 1]).random(3)
    assert np.array_equal(old_round_0, old_episode_1)
    # The named streams of the same roles do not.
    assert not np.array_equal(
        stream(0, "lower/round", 0).random(3), stream(0, "evaluate/episode", 1).random(3)
    )
    assert not np.array_equal(
        stream(0, "higher/explore").random(3), stream(0, "higher/episode", 2).random(3)
    )


@pytest.mark.parametrize(
    ("name", "index", "message"),
    [
        ("lower/rounds", (0,), "name of a random stream to be one of"),
        ("lower/round", (), "expected 1 index"),
        ("lower/round", (0, 0), "expected 1 index"),
        ("lower/mazes", (1,), "expected 0 index"),
        ("evaluate/episode", (-1,), "non-negative"),
    ],
)
def test_misnamed_streams_are_refused(name: str, index: tuple[int, ...], message: str) -> None:
    with pytest.raises((InvalidArgumentError, UnknownNameError), match=message):
        stream(0, name, *index)


def test_every_stream_the_package_uses_is_listed() -> None:
    # The package's stream names, found in its source, are all keys of STREAMS, and every key
    # is used somewhere: no ad-hoc stream and no stale entry.
    import pathlib
    import re

    import mazesim

    root = pathlib.Path(mazesim.__file__).parent
    used = set()
    pattern = re.compile(r"""(?:stream|seed_sequence)[^"'\n]*["']([a-z]+/[a-z]+)["']""")
    for path in root.rglob("*.py"):
        if path.name != "_seeding.py":
            used.update(pattern.findall(path.read_text()))
    assert used == set(STREAMS)
