"""Issue 21: Corridors and Corners holding its heading on the maze's grid where no sensor sees a
wall (``mazesim train --hold-heading``)."""

from __future__ import annotations

import dataclasses
import importlib
import json
import math
from pathlib import Path

import numpy as np
import pytest

from mazesim.actions import ACTION_CODES, WHEEL_SPEED_FRACTIONS
from mazesim.cli import main
from mazesim.errors import PolicyFormatError
from mazesim.learn.checkpoint import RunFolder
from mazesim.learn.core_episodes import stretches_apply
from mazesim.learn.discretise import NUM_SENSORS, distance_levels, encode_state
from mazesim.learn.higher import HigherLevel
from mazesim.learn.lower import lower_table_shape
from mazesim.learn.policy import DeadReckoningNavigator, HierarchicalPolicy
from mazesim.learn.subtasks import BLIND_STATE, SubTask
from mazesim.learn.tables import load_policy, save_policy
from mazesim.learn.train import train
from navigator_oracle import HOLD_TOLERANCE, begin_subtask, grid_error, hold_actions
from training_settings import E_PUCK_ROUND, TINY, trained, trained_alike_at_one_and_two_threads

FORWARD, GENTLE_RIGHT, GENTLE_LEFT = (ACTION_CODES.index(c) for c in ("00", "11", "55"))
SPIN_RIGHT, SPIN_LEFT = ACTION_CODES.index("aa"), ACTION_CODES.index("bb")
BLIND_CM = np.full(NUM_SENSORS, 80.0)


def test_the_grid_error_is_the_turn_to_the_nearest_right_angle() -> None:
    yaw = np.random.default_rng(3).uniform(-10.0, 10.0, 5000)
    error = grid_error(yaw)
    assert np.all(np.abs(error) <= math.pi / 4 + 1e-12)
    quarters = (yaw - error) / (math.pi / 2)
    assert np.allclose(quarters, np.round(quarters), atol=1e-9)
    assert grid_error(math.radians(100.0)) == pytest.approx(math.radians(10.0))
    assert grid_error(math.radians(-175.0)) == pytest.approx(math.radians(5.0))


def test_the_rule_steers_back_drives_on_and_finishes_a_spin() -> None:
    rng = np.random.default_rng(4)
    yaw = rng.uniform(-math.pi, math.pi, 4000)
    previous = rng.integers(-1, len(ACTION_CODES), yaw.size)
    action = hold_actions(yaw, previous)
    error = grid_error(yaw)
    off = np.abs(error) > HOLD_TOLERANCE
    spinning = np.isin(previous, (SPIN_RIGHT, SPIN_LEFT))
    assert np.all(action[~off] == FORWARD)
    assert np.all(action[off & spinning] == previous[off & spinning])
    steer = off & ~spinning
    assert np.all(action[steer & (error > 0)] == GENTLE_RIGHT)
    assert np.all(action[steer & (error < 0)] == GENTLE_LEFT)


def _drive(yaw: float, previous: int, steps: int, axle: float = 0.053) -> list[tuple[int, float]]:
    """Runs the rule alone on a robot of the e-puck's geometry for ``steps`` 64 ms steps."""
    wheel, speed, dt = 0.02, 6.28, 0.064
    out = []
    for _ in range(steps):
        action = int(hold_actions(np.array([yaw]), np.array([previous]))[0])
        left, right = WHEEL_SPEED_FRACTIONS[action] * speed
        yaw += wheel * (right - left) / axle * dt
        out.append((action, yaw))
        previous = action
    return out


@pytest.mark.parametrize("start_deg", [-40.0, -12.0, 7.0, 30.0, 95.0, 178.0])
def test_a_robot_driving_blind_settles_on_the_grid_and_stays(start_deg: float) -> None:
    run = _drive(math.radians(start_deg), FORWARD, 200)
    late = np.array([yaw for _, yaw in run[60:]])
    assert np.all(np.abs(grid_error(late)) <= HOLD_TOLERANCE + math.radians(1.5))
    assert sum(action == FORWARD for action, _ in run[60:]) > 100


def test_a_spin_begun_before_going_blind_ends_a_quarter_turn_on() -> None:
    run = _drive(math.radians(20.0), SPIN_LEFT, 60)
    actions = [a for a, _ in run]
    first_other = next(i for i, a in enumerate(actions) if a != SPIN_LEFT)
    assert abs(math.degrees(run[first_other - 1][1]) - 90.0) <= math.degrees(HOLD_TOLERANCE)
    # Without the spin it would have steered back to 0 degrees.
    back = _drive(math.radians(20.0), FORWARD, 60)
    assert abs(math.degrees(back[-1][1])) <= 4.5


def _policy(hold_heading: bool) -> HierarchicalPolicy:
    """A navigator whose tables spin right everywhere."""
    q = np.zeros(lower_table_shape())
    q[:, :, SPIN_RIGHT] = 1.0
    level = HigherLevel([[1, 2, 3]])
    return HierarchicalPolicy(q, level, np.zeros(4, dtype=np.int64), hold_heading=hold_heading)


def test_the_navigator_holds_only_in_corridors_and_corners_where_blind() -> None:
    distances = np.stack([BLIND_CM, BLIND_CM, BLIND_CM, BLIND_CM])
    distances[1, 0] = 5.0  # robot 1 sees a wall ahead
    poses = np.zeros((4, 3))
    poses[:, 2] = math.radians(10.0)
    events = np.zeros(4, dtype=np.int64)
    held = _policy(True)
    held.reset(np.arange(4), poses)
    # Robot 3 runs a door sub-task: its table decides, blind or not.
    begin_subtask(held, 3, SubTask.RIGHT)
    action = held.act_on_distances(distances, poses, events)
    assert held.record.state[0] == BLIND_STATE
    assert action.tolist() == [GENTLE_RIGHT, SPIN_RIGHT, GENTLE_RIGHT, SPIN_RIGHT]
    plain = _policy(False)
    plain.reset(np.arange(4), poses)
    assert np.all(plain.act_on_distances(distances, poses, events) == SPIN_RIGHT)


def test_the_dead_reckoned_frame_starts_at_the_episode_start() -> None:
    q = np.zeros(lower_table_shape())
    q[SubTask.CORRIDOR, :, FORWARD] = 1.0
    wall_ahead = encode_state(distance_levels(np.array([5.0, 80, 80, 80, 80, 80])))
    q[SubTask.CORRIDOR, wall_ahead, SPIN_LEFT] = 2.0
    navigator = DeadReckoningNavigator(q, HigherLevel([[1, 2, 3]]), hold_heading=True)
    wall = np.array([5.0, 80, 80, 80, 80, 80])
    codes = [navigator.act(wall, 0) for _ in range(3)]
    assert codes == ["bb"] * 3
    turned = [navigator.act(BLIND_CM, 0) for _ in range(40)]
    spins = turned.index("00")
    assert set(turned[:spins]) == {"bb"} and set(turned[spins:]) <= {"00", "11", "55"}
    assert abs(math.degrees(navigator.pose[0, 2]) - 90.0) <= 4.0
    navigator.reset()
    assert navigator.act(BLIND_CM, 0) == "00"


HOLD_ROUND = dataclasses.replace(E_PUCK_ROUND, hold_heading=True)


def test_training_holds_the_heading_where_blind_at_any_thread_count() -> None:
    one = trained_alike_at_one_and_two_threads(HOLD_ROUND)
    blind = one.tables.visits[SubTask.CORRIDOR, BLIND_STATE]
    rule = [FORWARD, GENTLE_RIGHT, GENTLE_LEFT, SPIN_RIGHT, SPIN_LEFT]
    assert blind[rule].sum() == blind.sum() > 0
    assert blind[GENTLE_RIGHT] + blind[GENTLE_LEFT] > 0
    # With the plain blind rule the same robots only ever drove straight on there.
    forward = trained(dataclasses.replace(HOLD_ROUND, hold_heading=False))
    plain = forward.tables.visits[SubTask.CORRIDOR, BLIND_STATE]
    assert plain.sum() == plain[FORWARD] > 0
    assert not np.array_equal(forward.tables.q, one.tables.q)


HOLD_TINY = dataclasses.replace(TINY, blind_forward=True, hold_heading=True)


def test_a_holding_navigator_records_it_and_every_runner_holds(tmp_path: Path) -> None:
    whole = train(HOLD_TINY, RunFolder(tmp_path / "whole"))
    assert whole is not None and whole.hold_heading
    metadata = json.loads((tmp_path / "whole" / "policy.json").read_text())
    assert metadata["training"]["settings"]["hold_heading"] is True
    assert metadata["training"]["lower"]["hold_heading"] is True
    loaded = load_policy(tmp_path / "whole")
    assert loaded.hold_heading and not load_policy().hold_heading
    # A stopped run resumes only with the same rule.
    assert train(HOLD_TINY, RunFolder(tmp_path / "parts"), stop_after_rounds=1) is None
    other = dataclasses.replace(HOLD_TINY, hold_heading=False)
    with pytest.raises(PolicyFormatError, match="other settings"):
        train(other, RunFolder(tmp_path / "parts", resume=True))
    # The one-robot runner (ROS, TrainedPolicy.act) holds as well.
    loaded.reset()
    assert loaded._driver.policy.hold_heading
    # Saved again, it keeps the rule; a policy.json that says something else than true or
    # false is refused.
    save_policy(loaded, tmp_path / "again")
    assert load_policy(tmp_path / "again").hold_heading
    meta_path = tmp_path / "again" / "policy.json"
    bad = json.loads(meta_path.read_text())
    bad["training"]["lower"]["hold_heading"] = "yes"
    meta_path.write_text(json.dumps(bad))
    with pytest.raises(PolicyFormatError, match="hold_heading"):
        load_policy(tmp_path / "again")


def test_stretches_take_navigators_that_hold_too() -> None:
    import mazesim
    from mazesim.episodes import EpisodeBatch

    nav = EpisodeBatch([mazesim.load_world("seed-maze")], num_envs=2)
    level = HigherLevel([load_policy().checkpoint_ids])
    q = np.zeros(lower_table_shape())
    assert stretches_apply(nav, HierarchicalPolicy(q, level, [0, 0]))
    assert stretches_apply(nav, HierarchicalPolicy(q, level, [0, 0], hold_heading=True))


def test_the_option_reaches_the_help_and_implies_the_blind_rule(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    assert main(["train", "--help"]) == 0
    assert "--hold-heading" in capsys.readouterr().out
    seen = []
    training = importlib.import_module("mazesim.learn.train")
    monkeypatch.setattr(training, "train", lambda settings, *a, **k: seen.append(settings))
    main(["train", "--hold-heading", "--out", str(tmp_path / "h"), "--no-progress"])
    assert seen and seen[0].hold_heading and seen[0].blind_forward
    assert not seen[0].door_distance
    code = main(["train", "--flat", "--hold-heading", "--out", str(tmp_path), "--no-progress"])
    assert code == 2
    assert "hierarchical navigators only" in capsys.readouterr().err
