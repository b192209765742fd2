"""Issue 6: saved navigators: round trip, and clear errors for mismatched or damaged files."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import mazesim
from mazesim.errors import MazesimError, PolicyFormatError
from mazesim.learn.lower import lower_table_shape
from mazesim.learn.tables import TrainedPolicy, load_policy, save_policy
from mazesim.maze import world_hash
from mazesim_process import mazesim_command


def random_policy(seed: int = 0) -> TrainedPolicy:
    rng = np.random.default_rng(seed)
    world = mazesim.load_world("seed-maze")
    lower = rng.normal(size=lower_table_shape())
    lower[0, 4096:] = 0.0  # Corridors and Corners has no phases: only its first rows are saved
    return TrainedPolicy(
        kind="hierarchical",
        world_name=world.name,
        world_sha256=world_hash(world),
        checkpoint_ids=[1, 2, 3, 4, 5, 6, 7],
        lower_q=lower,
        higher_q=rng.normal(size=(14, 4)),
        training={"seed": seed, "note": "made up for a test"},
    )


def test_save_load_round_trip(tmp_path: Path) -> None:
    policy = random_policy()
    save_policy(policy, tmp_path / "navigator")
    loaded = load_policy(tmp_path / "navigator")
    assert loaded.kind == "hierarchical"
    assert loaded.world_name == "seed-maze"
    assert loaded.checkpoint_ids == policy.checkpoint_ids
    assert loaded.training == policy.training
    assert loaded.lower_q is not None and loaded.higher_q is not None
    assert np.array_equal(loaded.lower_q, policy.lower_q)
    assert np.array_equal(loaded.higher_q, policy.higher_q)
    loaded.check_world(mazesim.load_world("seed-maze"))
    metadata = json.loads((tmp_path / "navigator" / "policy.json").read_text())
    assert metadata["format"] == "mazesim-policy" and metadata["version"] == 1
    assert metadata["state_encoding"]["level_edges_cm"] == [7.0, 13.0, 20.0]
    assert [a["code"] for a in metadata["actions"]][:3] == ["00", "11", "22"]
    assert [s["name"] for s in metadata["subtasks"]] == [
        "Corridors and Corners",
        "Right turn on a door",
        "Left turn on a door",
        "Going forward on a door",
    ]
    assert metadata["world"]["sha256"] == world_hash(mazesim.load_world("seed-maze"))
    # No pickle: the archive loads with allow_pickle=False.
    with np.load(tmp_path / "navigator" / "tables.npz", allow_pickle=False) as archive:
        assert set(archive.files) == {"corridor", "right", "left", "forward", "higher"}
        assert archive["corridor"].shape == (4096, 12)
        assert archive["right"].shape == (3 * 4096, 12)


def test_truncated_tables_are_refused(tmp_path: Path) -> None:
    save_policy(random_policy(), tmp_path)
    tables = tmp_path / "tables.npz"
    tables.write_bytes(tables.read_bytes()[:1000])
    with pytest.raises(PolicyFormatError, match="truncated"):
        load_policy(tmp_path)


def test_corrupt_tables_are_refused(tmp_path: Path) -> None:
    save_policy(random_policy(), tmp_path)
    tables = tmp_path / "tables.npz"
    data = bytearray(tables.read_bytes())
    data[len(data) // 2] ^= 0xFF
    tables.write_bytes(bytes(data))
    with pytest.raises(PolicyFormatError, match="corrupt"):
        load_policy(tmp_path)


def test_truncated_metadata_is_refused(tmp_path: Path) -> None:
    save_policy(random_policy(), tmp_path)
    metadata = tmp_path / "policy.json"
    metadata.write_text(metadata.read_text()[:200])
    with pytest.raises(PolicyFormatError, match="not valid JSON"):
        load_policy(tmp_path)


@pytest.mark.parametrize(
    ("key", "change", "reason"),
    [
        ("version", lambda m: 99, "format version"),
        ("state_encoding", lambda m: {**m, "level_edges_cm": [5.0, 13.0, 20.0]}, "state encoding"),
        ("actions", lambda m: m[::-1], "actions"),
        ("subtasks", lambda m: m[:3], "subtasks"),
        # Tables of a version whose Corridors and Corners could reverse.
        ("subtasks", lambda m: [{k: v for k, v in s.items() if k != "actions"} for s in m], "sub"),
    ],
)
def test_mismatched_metadata_is_refused(tmp_path: Path, key: str, change, reason: str) -> None:
    save_policy(random_policy(), tmp_path)
    path = tmp_path / "policy.json"
    metadata = json.loads(path.read_text())
    metadata[key] = change(metadata[key])
    path.write_text(json.dumps(metadata))
    with pytest.raises(PolicyFormatError, match=reason) as caught:
        load_policy(tmp_path)
    assert isinstance(caught.value, MazesimError) and isinstance(caught.value, ValueError)


def test_another_world_is_refused(tmp_path: Path) -> None:
    save_policy(random_policy(), tmp_path)
    policy = load_policy(tmp_path)
    with pytest.raises(PolicyFormatError, match="learned world 'seed-maze'"):
        policy.check_world(mazesim.generate_maze(5, 5, seed=3))


def test_missing_folder_is_refused(tmp_path: Path) -> None:
    with pytest.raises(PolicyFormatError, match="no such file") as refused:
        load_policy(tmp_path / "nowhere")
    assert f"there is no folder {str(tmp_path / 'nowhere')!r}" in str(refused.value)
    assert "'mazesim train --out DIR' writes" in str(refused.value)


def test_eval_command_reports_a_damaged_policy_in_one_line(tmp_path: Path) -> None:
    save_policy(random_policy(), tmp_path)
    (tmp_path / "tables.npz").write_bytes(b"not an archive")
    result = mazesim_command(
        "eval", "--policy", str(tmp_path), "--episodes", "1", cwd=tmp_path, timeout=120
    )
    assert result.returncode == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("mazesim: error: ")
    assert "truncated" in lines[0]
