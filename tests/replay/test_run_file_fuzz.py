"""Fuzzing the run-file reader: a real run's JSON with a field replaced by a hostile value
(non-finite and extreme numbers, wrong types, deep nesting, long lists), fields deleted, or its
bytes mutated, is read into a run or refused with a ``MazesimError``; never another exception.
Both formats are fuzzed: a run of one robot (1.0) and a run of three robots (1.1)."""

from __future__ import annotations

import gzip
import json
import math
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from robots_world import record_three_robots
from test_replay_run import long_run

import mazesim
from mazesim.errors import RunFormatError
from mazesim.replay import load_run, save_run
from mazesim.replay.run import run_from_json

HOSTILE: list[Any] = [
    math.nan,
    math.inf,
    -math.inf,
    1e300,
    -1e300,
    2**70,
    -1,
    0,
    True,
    None,
    "",
    "x" * 1000,
    [],
    {},
    [[[[[[[[]]]]]]]],
    list(range(1000)),
    {"a": {"b": {"c": 1}}},
]


@pytest.fixture(scope="module", params=["one robot", "three robots"])
def run_json(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> Any:
    """A run of one robot (format 1.0) and one of three robots (1.1: its ``robots`` and each
    episode's tracks of the others), as their JSON."""
    if request.param == "one robot":
        return json.loads(json.dumps(long_run(60).as_json()))
    recorded = record_three_robots(tmp_path_factory.mktemp("three"))
    values = json.loads(gzip.decompress(recorded["run"].read_bytes()))
    assert values["version"] == "1.1"
    return values


def _places(value: Any, path: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    """Every place in a JSON value (dict keys and list indices), the first few items of lists."""
    found = [path]
    if isinstance(value, dict):
        for key, item in value.items():
            found += _places(item, (*path, key))
    elif isinstance(value, list):
        for index, item in enumerate(value[:3]):
            found += _places(item, (*path, index))
    return found


def _replaced(values: Any, place: tuple[Any, ...], new: Any, delete: bool) -> Any:
    copy = json.loads(json.dumps(values))
    if not place:
        return new
    parent = copy
    for key in place[:-1]:
        parent = parent[key]
    if delete:
        del parent[place[-1]]
    else:
        parent[place[-1]] = new
    return copy


@settings(
    max_examples=150, deadline=None, suppress_health_check=list(HealthCheck), derandomize=True
)
@given(data=st.data())
def test_a_damaged_run_is_read_or_refused(run_json: dict[str, Any], data: st.DataObject) -> None:
    place = data.draw(st.sampled_from(_places(run_json)))
    new = data.draw(st.sampled_from(HOSTILE))
    delete = bool(place) and data.draw(st.booleans())
    try:
        run_from_json(_replaced(run_json, place, new, delete), "fuzz.json")
    except mazesim.MazesimError:
        pass


@settings(max_examples=60, deadline=None, suppress_health_check=list(HealthCheck), derandomize=True)
@given(data=st.data())
def test_mutated_run_file_bytes_are_read_or_refused(
    run_json: dict[str, Any], tmp_path_factory: pytest.TempPathFactory, data: st.DataObject
) -> None:
    text = bytearray(json.dumps(run_json).encode("utf-8"))
    for _ in range(data.draw(st.integers(1, 6))):
        at = data.draw(st.integers(0, len(text)))
        how = data.draw(st.sampled_from(["flip", "cut", "insert"]))
        if how == "flip" and at < len(text):
            text[at] ^= data.draw(st.integers(1, 255))
        elif how == "cut":
            del text[at : at + data.draw(st.integers(1, 64))]
        else:
            text[at:at] = data.draw(st.sampled_from([b"[", b"{", b"1e999", b"-", b'"', b"\x00"]))
    path = tmp_path_factory.mktemp("runs") / "fuzz.json"
    path.write_bytes(bytes(text))
    try:
        load_run(path)
    except mazesim.MazesimError:
        pass


def test_the_unmutated_run_is_read(run_json: dict[str, Any], tmp_path: Path) -> None:
    run = run_from_json(run_json, "fuzz.json")
    save_run(run, tmp_path / "again.json")
    assert load_run(tmp_path / "again.json").as_json() == run.as_json()


@pytest.mark.parametrize("after", [b"garbage", b"\x00" * 512, b"\x1f\x8b"])
def test_a_compressed_run_with_bytes_after_its_end_is_refused(
    run_json: dict[str, Any], tmp_path: Path, after: bytes
) -> None:
    """Bytes after the end of a compressed run (a damaged or appended-to file) were passed over
    and the file read as whole (#35)."""
    path = tmp_path / "run.json.gz"
    whole = gzip.compress(json.dumps(run_json).encode("utf-8"))
    path.write_bytes(whole)
    load_run(path)
    path.write_bytes(whole + after)
    with pytest.raises(RunFormatError, match=f"{len(after)} bytes after the end"):
        load_run(path)
