"""Issue 15: every malformed navigator file raises PolicyFormatError, and no file decides how much
memory loading it takes."""

from __future__ import annotations

import io
import json
import shutil
import tracemalloc
import zipfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import mazesim
from mazesim.errors import PolicyFormatError
from mazesim.learn.lower import lower_table_shape
from mazesim.learn.tables import TrainedPolicy, load_policy, save_policy, sha256
from mazesim.maze import world_hash
from mazesim_process import mazesim_command

POLICY_JSON = "policy.json"
TABLES_NPZ = "tables.npz"


def small_policy(kind: str = "hierarchical") -> TrainedPolicy:
    rng = np.random.default_rng(1)
    world = mazesim.load_world("seed-maze")
    checkpoints = [1, 2, 3, 4, 5, 6, 7]
    lower = rng.normal(size=lower_table_shape())
    lower[0, 4096:] = 0.0
    return TrainedPolicy(
        kind=kind,
        world_name=world.name,
        world_sha256=world_hash(world),
        checkpoint_ids=checkpoints,
        lower_q=lower if kind == "hierarchical" else None,
        higher_q=rng.normal(size=(14, 4)) if kind == "hierarchical" else None,
        flat_q=rng.normal(size=(15 * 4096, 12)) if kind == "flat" else None,
        training={"note": "made up for a test"},
    )


@pytest.fixture(scope="module")
def saved(tmp_path_factory: pytest.TempPathFactory) -> Path:
    folder = tmp_path_factory.mktemp("saved")
    save_policy(small_policy(), folder)
    return folder


@pytest.mark.parametrize("damage", ["nan", "checkpoint id 0", "repeated checkpoint"])
def test_a_navigator_its_loader_would_refuse_is_not_saved(tmp_path: Path, damage: str) -> None:
    policy = small_policy()
    assert policy.lower_q is not None
    if damage == "nan":
        policy.lower_q[1, 5, 3] = np.nan
    elif damage == "checkpoint id 0":
        policy.checkpoint_ids = [0, 2, 3, 4, 5, 6, 7]
    else:
        policy.checkpoint_ids = [1, 1, 3, 4, 5, 6, 7]
    with pytest.raises(PolicyFormatError):
        save_policy(policy, tmp_path / "nav")
    assert not (tmp_path / "nav").exists(), "nothing written"


def _copy(saved: Path, folder: Path) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    for name in (POLICY_JSON, TABLES_NPZ):
        shutil.copyfile(saved / name, folder / name)
    return folder


def _paths(document: Any, prefix: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    """Every place in a JSON document, except the free-form ones (training notes, world name)."""
    if prefix in (("training",), ("world", "name")):
        return []
    found = [prefix] if prefix else []
    if isinstance(document, dict):
        for key, value in document.items():
            found += _paths(value, (*prefix, key))
    elif isinstance(document, list):
        for index, value in enumerate(document[:3]):
            found += _paths(value, (*prefix, index))
    return found


def _replace(document: Any, path: tuple[Any, ...], value: Any) -> Any:
    if not path:
        return value
    head, rest = path[0], path[1:]
    if isinstance(document, dict):
        return {**document, head: _replace(document[head], rest, value)}
    copy = list(document)
    copy[head] = _replace(copy[head], rest, value)
    return copy


def _remove(document: Any, path: tuple[Any, ...]) -> Any:
    head, rest = path[0], path[1:]
    if rest:
        copy: Any = dict(document) if isinstance(document, dict) else list(document)
        copy[head] = _remove(document[head], rest)
        return copy
    if isinstance(document, dict):
        return {key: value for key, value in document.items() if key != head}
    return [value for index, value in enumerate(document) if index != head]


def _nested(depth: int) -> Any:
    value: Any = 1
    for level in range(depth):
        value = [value] if level % 2 else {"a": value}
    return value


HOSTILE_VALUES = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(min_value=-(10**30), max_value=10**30),
    st.sampled_from([10**400, -(10**300), 2**63, 2**64 + 1]),
    st.floats(allow_nan=True, allow_infinity=True),
    st.text(max_size=12),
    st.lists(st.integers(), max_size=3),
    st.dictionaries(st.text(max_size=4), st.integers(), max_size=2),
    st.integers(min_value=33, max_value=600).map(_nested),
)


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_malformed_metadata_raises_policy_format_error(saved: Path, data: st.DataObject) -> None:
    original = json.loads((saved / POLICY_JSON).read_text())
    paths = _paths(original)
    path = data.draw(st.sampled_from(paths), label="path")
    if data.draw(st.booleans(), label="remove"):
        mutated = _remove(original, path)
    else:
        value = data.draw(HOSTILE_VALUES, label="value")
        mutated = _replace(original, path, value)
    assume(mutated != original)
    folder = Path(saved.parent / "mutated-metadata")
    _copy(saved, folder)
    (folder / POLICY_JSON).write_text(json.dumps(mutated))
    with pytest.raises(PolicyFormatError):
        load_policy(folder)


@pytest.mark.parametrize(
    "text",
    [
        "",
        "null",
        "[]",
        '"policy"',
        "[" * 100_000 + "]" * 100_000,
        '{"format": ' + "[" * 50 + "]" * 50 + "}",
        '{"format": "mazesim-policy", "version": 1e999}',
        '{"format": "mazesim-policy", "version": ' + "9" * 5000 + "}",
        '{"format": "mazesim-policy", "version": NaN}',
        "\xff\xfe{",
    ],
    ids=lambda text: text[:24],
)
def test_hostile_metadata_text_raises_policy_format_error(
    saved: Path, tmp_path: Path, text: str
) -> None:
    _copy(saved, tmp_path)
    (tmp_path / POLICY_JSON).write_bytes(text.encode("utf-8", "surrogateescape"))
    with pytest.raises(PolicyFormatError):
        load_policy(tmp_path)


def _with_tables(saved: Path, folder: Path, data: bytes) -> Path:
    """A copy of the saved navigator whose tables.npz is ``data`` and whose metadata records its
    true size and sha256, so only the archive's own checks can refuse it."""
    _copy(saved, folder)
    (folder / TABLES_NPZ).write_bytes(data)
    metadata = json.loads((folder / POLICY_JSON).read_text())
    metadata["tables"]["bytes"] = len(data)
    metadata["tables"]["sha256"] = sha256(data)
    (folder / POLICY_JSON).write_text(json.dumps(metadata))
    return folder


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_mutated_tables_raise_policy_format_error_or_load_intact(
    saved: Path, data: st.DataObject
) -> None:
    archive = bytearray((saved / TABLES_NPZ).read_bytes())
    kind = data.draw(st.sampled_from(["flip", "truncate", "splice"]), label="kind")
    where = data.draw(st.integers(0, len(archive) - 1), label="where")
    if kind == "flip":
        archive[where] ^= data.draw(st.integers(1, 255), label="bits")
    elif kind == "truncate":
        del archive[where:]
    else:
        archive[where:where] = data.draw(st.binary(min_size=1, max_size=64), label="bytes")
    folder = _with_tables(saved, saved.parent / "mutated-tables", bytes(archive))
    try:
        policy = load_policy(folder)
    except PolicyFormatError:
        return
    # A change the archive does not depend on (a zip header's time stamp) may load: intact.
    reference = load_policy(saved)
    assert policy.lower_q is not None and reference.lower_q is not None
    assert np.array_equal(policy.lower_q, reference.lower_q)


def _npz(members: dict[str, bytes]) -> bytes:
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", compression=zipfile.ZIP_DEFLATED) as archive:
        for name, data in members.items():
            archive.writestr(name, data)
    return buffer.getvalue()


def _npy(array: Any, **header: Any) -> bytes:
    buffer = io.BytesIO()
    np.lib.format.write_array(buffer, array, allow_pickle=True)
    data = buffer.getvalue()
    if header:
        description = {
            "descr": np.lib.format.dtype_to_descr(np.asarray(array).dtype),
            "fortran_order": False,
            "shape": np.asarray(array).shape,
            **header,
        }
        out = io.BytesIO()
        np.lib.format.write_array_header_1_0(out, description)
        return out.getvalue() + data[len(out.getvalue()) :]
    return data


def _members_of(saved: Path) -> dict[str, bytes]:
    with zipfile.ZipFile(saved / TABLES_NPZ) as archive:
        return {name: archive.read(name) for name in archive.namelist()}


def _tables_with(saved: Path, **replaced: bytes) -> Callable[[], bytes]:
    def build() -> bytes:
        members = _members_of(saved)
        members.update({f"{name}.npy": data for name, data in replaced.items()})
        return _npz(members)

    return build


@pytest.mark.parametrize(
    ("case", "reason"),
    [
        # The header claims 100,000 x 100,000 float64 (80 GB) over 1 kB of data.
        ("huge shape", "expected float64 \\[14, 4\\]"),
        ("object dtype", "Python objects|declared size"),
        ("declared size out of bounds", "declared size"),
        ("extra member", "expected the members"),
        ("fortran order", "Fortran"),
        ("not a zip", "not a readable .npz"),
    ],
)
def test_hostile_tables_are_refused_before_allocation(
    saved: Path, tmp_path: Path, case: str, reason: str
) -> None:
    higher = np.zeros((14, 4))
    builds: dict[str, Callable[[], bytes]] = {
        "huge shape": _tables_with(saved, higher=_npy(higher, shape=(100_000, 100_000))),
        "object dtype": _tables_with(saved, higher=_npy(np.array([[None] * 4] * 14, dtype=object))),
        # 64 MB of zeros deflate to 64 kB: a declared size far beyond a (14, 4) table.
        "declared size out of bounds": _tables_with(
            saved, higher=_npy(higher) + bytes(64 * 1024 * 1024)
        ),
        "extra member": _tables_with(saved, extra=_npy(higher)),
        "fortran order": _tables_with(saved, higher=_npy(higher, fortran_order=True)),
        "not a zip": lambda: b"PK\x03\x04" + bytes(2000),
    }
    folder = _with_tables(saved, tmp_path, builds[case]())
    tracemalloc.start()
    try:
        with pytest.raises(PolicyFormatError, match=reason):
            load_policy(folder)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 32 * 1024 * 1024, peak


def test_metadata_that_promises_huge_tables_is_refused_before_reading_them(
    saved: Path, tmp_path: Path
) -> None:
    _copy(saved, tmp_path)
    metadata = json.loads((tmp_path / POLICY_JSON).read_text())
    metadata["world"]["checkpoints"] = list(range(1, 1025))
    metadata["world"]["higher_states"] = [f"{sign}{c}" for c in range(1, 1025) for sign in "+-"]
    metadata["tables"]["arrays"]["higher"]["shape"] = [2048, 4]
    (tmp_path / POLICY_JSON).write_text(json.dumps(metadata))
    # The metadata is self-consistent, but the archive's member is not the promised table.
    with pytest.raises(PolicyFormatError, match="float64 \\[2048, 4\\], found a declared size"):
        load_policy(tmp_path)
    metadata["world"]["checkpoints"] = [10**9]
    metadata["world"]["higher_states"] = ["+1000000000", "-1000000000"]
    (tmp_path / POLICY_JSON).write_text(json.dumps(metadata))
    with pytest.raises(PolicyFormatError, match=r"world\.checkpoints\[0\]"):
        load_policy(tmp_path)


def test_flat_navigators_and_the_shipped_one_still_load(tmp_path: Path) -> None:
    save_policy(small_policy("flat"), tmp_path)
    flat = load_policy(tmp_path)
    assert flat.kind == "flat" and flat.flat_q is not None
    assert flat.flat_q.shape == (15 * 4096, 12)
    shipped = load_policy()
    assert shipped.kind == "hierarchical" and shipped.higher_q is not None


def test_eval_command_reports_malformed_metadata_in_one_line(saved: Path, tmp_path: Path) -> None:
    _copy(saved, tmp_path)
    metadata = json.loads((tmp_path / POLICY_JSON).read_text())
    metadata["world"] = ["not", "an", "object"]
    (tmp_path / POLICY_JSON).write_text(json.dumps(metadata))
    result = mazesim_command(
        "eval", "--policy", str(tmp_path), "--episodes", "1", cwd=tmp_path, timeout=120
    )
    assert result.returncode == 2, result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("mazesim: error: ")
    assert "world: expected an object, found a list" in lines[0]
