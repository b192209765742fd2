"""Issue 21: door sub-tasks whose phase also counts the distance driven (``--door-distance``), and
Corridors and Corners driving forward where no sensor sees a wall (``--blind-forward``)."""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest

import mazesim
from mazesim.actions import ACTION_CODES
from mazesim.cli import main
from mazesim.errors import InvalidArgumentError, PolicyFormatError
from mazesim.learn.checkpoint import RunFolder
from mazesim.learn.core_episodes import stretches_apply
from mazesim.learn.discretise import NUM_STATES
from mazesim.learn.evaluate import evaluate_navigator
from mazesim.learn.higher import HigherLevel
from mazesim.learn.lower import (
    LowerTrainer,
    drive_on_when_blind,
    lower_table_shape,
)
from mazesim.learn.policy import HierarchicalPolicy
from mazesim.learn.subtasks import (
    BLIND_STATE,
    DISTANCE_EDGES,
    DISTANCE_PHASES,
    MAX_PHASES,
    NUM_PHASES,
    SubTask,
    door_distance_of,
)
from mazesim.learn.tables import load_policy, save_policy
from mazesim.learn.train import train
from navigator_oracle import SubTaskTracker, distance_bins, mirrored_states
from training_settings import E_PUCK_ROUND, TINY, trained, trained_alike_at_one_and_two_threads

FORWARD = ACTION_CODES.index("00")


def _random_paths(seed: int, count: int, steps: int) -> tuple[np.ndarray, np.ndarray]:
    """Sub-tasks and ``steps`` poses of ``count`` robots that drive, turn and back up at random."""
    rng = np.random.default_rng(seed)
    subtasks = rng.integers(0, 4, count)
    poses = np.zeros((steps + 1, count, 3))
    poses[0, :, :2] = rng.uniform(0.0, 1.0, (count, 2))
    poses[0, :, 2] = rng.uniform(-math.pi, math.pi, count)
    for t in range(steps):
        turn = rng.normal(0.0, 0.08, count)
        speed = rng.uniform(-0.004, 0.012, count)
        yaw = poses[t, :, 2] + turn
        poses[t + 1, :, 0] = poses[t, :, 0] + speed * np.cos(yaw)
        poses[t + 1, :, 1] = poses[t, :, 1] + speed * np.sin(yaw)
        poses[t + 1, :, 2] = (yaw + math.pi) % (2.0 * math.pi) - math.pi
    return subtasks, poses


def test_the_distance_bins_follow_their_edges() -> None:
    edges = np.asarray(DISTANCE_EDGES)
    assert distance_bins(edges).tolist() == list(range(1, len(edges) + 1))
    assert distance_bins(edges - 1e-9).tolist() == list(range(len(edges)))
    assert distance_bins([-1.0, 0.0, 10.0]).tolist() == [0, 0, len(edges)]
    assert DISTANCE_PHASES == (1,) + (MAX_PHASES * (len(edges) + 1),) * 3


def test_distance_phases_add_the_distance_ahead_to_the_heading_phases() -> None:
    # Along any path, the phase with the distance is the heading phase plus 3 times the bin of
    # the distance driven along the sub-task's first heading; the ends do not change.
    subtasks, poses = _random_paths(4, 300, 120)
    plain, counted = SubTaskTracker(300), SubTaskTracker(300, door_distance=True)
    everyone = np.ones(300, dtype=bool)
    plain.begin(everyone, subtasks, poses[0])
    counted.begin(everyone, subtasks, poses[0])
    start = poses[0]
    seen_bins = set()
    for t in range(1, poses.shape[0]):
        assert [a.tolist() for a in plain.update(poses[t])] == [
            a.tolist() for a in counted.update(poses[t])
        ]
        ahead = (poses[t, :, 0] - start[:, 0]) * np.cos(start[:, 2]) + (
            poses[t, :, 1] - start[:, 1]
        ) * np.sin(start[:, 2])
        bins = np.where(subtasks == SubTask.CORRIDOR, 0, distance_bins(ahead))
        seen_bins.update(bins.tolist())
        assert np.array_equal(counted.heading_phase, plain.phase)
        assert np.array_equal(counted.phase, plain.phase + MAX_PHASES * bins)
        assert np.all(counted.phase < np.asarray(DISTANCE_PHASES)[subtasks])
    assert seen_bins == set(range(len(DISTANCE_EDGES) + 1))


def test_a_turn_driven_straight_on_passes_through_every_bin() -> None:
    tracker = SubTaskTracker(1, door_distance=True)
    tracker.begin(np.ones(1, dtype=bool), SubTask.RIGHT, np.array([[0.2, 0.3, math.pi / 2]]))
    phases = []
    # Northwards in steps of 1 cm, half a centimetre off the edges (12, 18, 22, 26, 30 cm).
    for k in range(1, 41):
        tracker.update(np.array([[0.2, 0.3 + 0.005 + 0.01 * k, math.pi / 2]]))
        phases.append(int(tracker.phase[0]))
    bins = [0] * 11 + [1] * 6 + [2] * 4 + [3] * 4 + [4] * 4 + [5] * 11
    assert phases == [3 * b for b in bins]
    # Turning right on the spot then moves the heading phase and keeps the bin.
    tracker.update(np.array([[0.2, 0.705, math.pi / 2 - math.radians(45.0)]]))
    assert int(tracker.phase[0]) == 1 + 3 * 5


def test_mirror_images_keep_the_distance_and_swap_forward_sides() -> None:
    rng = np.random.default_rng(3)
    subtasks = rng.integers(1, 4, 2000)
    phases = rng.integers(0, DISTANCE_PHASES[1], 2000)
    states = rng.integers(0, NUM_STATES, 2000) + NUM_STATES * phases
    mirrored = mirrored_states(states, subtasks)
    assert np.array_equal(mirrored_states(mirrored, subtasks), states)
    mirrored_phase = mirrored // NUM_STATES
    assert np.array_equal(mirrored_phase // MAX_PHASES, phases // MAX_PHASES)
    forward = subtasks == SubTask.FORWARD
    assert np.array_equal(mirrored_phase[forward] % 3, 2 - phases[forward] % 3)
    assert np.array_equal(mirrored_phase[~forward], phases[~forward])


def test_the_tables_shape_says_which_phases_they_use() -> None:
    assert door_distance_of(lower_table_shape()[1]) is False
    assert door_distance_of(lower_table_shape(True)[1]) is True
    assert lower_table_shape(True)[1] == max(DISTANCE_PHASES) * NUM_STATES
    with pytest.raises(InvalidArgumentError, match="rows per sub-task"):
        door_distance_of(5 * NUM_STATES)
    level = HigherLevel([[1, 2]])
    assert HierarchicalPolicy(np.zeros(lower_table_shape(True)), level, [0]).door_distance
    assert not HierarchicalPolicy(np.zeros(lower_table_shape()), level, [0]).door_distance
    with pytest.raises(InvalidArgumentError, match="door_distance"):
        HierarchicalPolicy(np.zeros((4, 5 * NUM_STATES, 12)), level, [0])


def test_driving_on_when_blind_changes_the_blind_row_alone() -> None:
    rng = np.random.default_rng(1)
    q = rng.normal(0.0, 1.0, lower_table_shape(True))
    q[0, BLIND_STATE, FORWARD] = -3.0
    before = q.copy()
    drive_on_when_blind(q)
    row = q[0, BLIND_STATE]
    assert int(np.argmax(row)) == FORWARD and row[FORWARD] == -3.0
    assert np.all(np.delete(row, FORWARD) < -3.0)
    changed = np.argwhere(q != before)
    assert {(int(k), int(s)) for k, s, _ in changed} == {(0, BLIND_STATE)}
    again = q.copy()
    drive_on_when_blind(again)
    assert np.array_equal(again, q)


def test_the_blind_rule_and_distance_phases_train_alike_at_any_thread_count() -> None:
    one = trained_alike_at_one_and_two_threads(E_PUCK_ROUND)
    assert one.tables.q.shape == lower_table_shape(True)
    visits = one.tables.visits
    # The e-puck sees no wall from a corridor's middle: there it only ever drove forward.
    assert visits[0, BLIND_STATE, FORWARD] > 0
    assert visits[0, BLIND_STATE].sum() == visits[0, BLIND_STATE, FORWARD]
    # The door sub-tasks learned in distance bins beyond the first.
    door_rows = visits[1:].sum(axis=2).reshape(3, -1, NUM_STATES).sum(axis=2)
    assert np.all(door_rows[:, MAX_PHASES:].sum(axis=1) > 0)
    # Without the options a trainer of the same robots keeps the heading phases and learns
    # other actions in the blind state.
    plain = dataclasses.replace(E_PUCK_ROUND, door_distance=False, blind_forward=False)
    other = trained(plain, threads=1)
    assert other.tables.q.shape == lower_table_shape()
    blind = other.tables.visits[0, BLIND_STATE]
    assert blind.sum() > blind[FORWARD]


def test_either_option_alone_trains_in_the_core() -> None:
    plain = dataclasses.replace(E_PUCK_ROUND, door_distance=False, blind_forward=False)
    for door_distance, blind_forward in ((False, False), (True, False), (False, True)):
        settings = dataclasses.replace(
            plain, door_distance=door_distance, blind_forward=blind_forward
        )
        trainer = LowerTrainer(settings)
        assert trainer._core_settings(0.1)["phases"] == (
            "heading_and_distance" if door_distance else "heading"
        )
        assert trainer._core_settings(0.1)["blind"] == ("forward" if blind_forward else "table")
        assert trainer.tables.q.shape == lower_table_shape(door_distance)


def test_a_trainer_refuses_tables_of_the_other_phases() -> None:
    from mazesim.learn.lower import LowerTables

    with pytest.raises(InvalidArgumentError, match="door_distance=True"):
        LowerTrainer(E_PUCK_ROUND, tables=LowerTables.zeros(False))


DOOR_TINY = dataclasses.replace(TINY, door_distance=True, blind_forward=True)


def test_a_navigator_with_distance_phases_saves_loads_resumes_and_drives(tmp_path: Path) -> None:
    whole = train(DOOR_TINY, RunFolder(tmp_path / "whole"))
    assert whole is not None and whole.lower_q is not None
    assert whole.lower_q.shape == lower_table_shape(True)
    blind = whole.lower_q[0, BLIND_STATE]
    assert int(np.argmax(blind)) == FORWARD
    # Stopped after a round and resumed, it ends with the same tables.
    assert train(DOOR_TINY, RunFolder(tmp_path / "parts"), stop_after_rounds=1) is None
    with pytest.raises(PolicyFormatError, match="other settings"):
        train(TINY, RunFolder(tmp_path / "parts", resume=True))
    resumed = train(DOOR_TINY, RunFolder(tmp_path / "parts", resume=True))
    assert resumed is not None and resumed.lower_q is not None
    assert np.array_equal(whole.lower_q, resumed.lower_q)

    loaded = load_policy(tmp_path / "whole")
    assert loaded.lower_q is not None and np.array_equal(loaded.lower_q, whole.lower_q)
    metadata = json.loads((tmp_path / "whole" / "policy.json").read_text())
    assert [s["phases"] for s in metadata["subtasks"]] == list(DISTANCE_PHASES)
    assert "12 cm" in metadata["subtasks"][1]["phase_rule"]
    settings = metadata["training"]["settings"]
    assert settings["door_distance"] is True and settings["blind_forward"] is True
    assert metadata["training"]["lower"]["door_distance"] is True

    # It drives through the per-step loop (the core's multi-step call knows heading phases only).
    world = mazesim.load_world("seed-maze")
    results = evaluate_navigator(loaded, [world], 3, seed=2, max_steps=200)
    assert results["truth"].episodes == 3


def test_a_policy_file_whose_phases_do_not_match_its_tables_is_refused(tmp_path: Path) -> None:
    policy = load_policy()
    assert policy.lower_q is not None
    save_policy(policy, tmp_path / "plain")
    meta_path = tmp_path / "plain" / "policy.json"
    metadata = json.loads(meta_path.read_text())
    assert [s["phases"] for s in metadata["subtasks"]] == list(NUM_PHASES)
    for subtask, phases in zip(metadata["subtasks"], DISTANCE_PHASES):
        subtask["phases"] = phases
    meta_path.write_text(json.dumps(metadata))
    with pytest.raises(PolicyFormatError):
        load_policy(tmp_path / "plain")


def test_stretches_take_navigators_of_distance_phases_too() -> None:
    from mazesim.episodes import EpisodeBatch

    world = mazesim.load_world("seed-maze")
    nav = EpisodeBatch([world], num_envs=2)
    level = HigherLevel([load_policy().checkpoint_ids])
    plain = HierarchicalPolicy(np.zeros(lower_table_shape()), level, [0, 0])
    counted = HierarchicalPolicy(np.zeros(lower_table_shape(True)), level, [0, 0])
    assert stretches_apply(nav, plain) and stretches_apply(nav, counted)


def test_train_options_reach_the_help_and_flat_refuses_them(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["train", "--help"]) == 0
    text = capsys.readouterr().out
    assert "--door-distance" in text and "--blind-forward" in text
    code = main(
        ["train", "--flat", "--door-distance", "--out", str(tmp_path / "f"), "--no-progress"]
    )
    assert code == 2
    assert "hierarchical navigators only" in capsys.readouterr().err
    assert not (tmp_path / "f" / "tables.npz").exists()
