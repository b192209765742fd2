"""Issue 6: the lower level's state (Table 4.1, the 4^6 encoding), actions and mirror symmetry."""

from __future__ import annotations

import numpy as np
import pytest

import mazesim
from mazesim.actions import ACTION_CODES, WHEEL_SPEED_FRACTIONS, wheel_speeds
from mazesim.errors import InvalidArgumentError
from mazesim.learn.discretise import (
    LEVEL_EDGES_CM,
    NUM_STATES,
    SENSOR_ORDER,
    SHARP_TABLE,
    decode_state,
    distance_levels,
    distances_and_levels,
    encode_state,
    observation_states,
    volts_to_cm,
)
from mazesim.learn.subtasks import SubTask
from navigator_oracle import (
    MIRRORED_ACTION,
    MIRRORED_SUBTASK,
    begin_subtask,
    heading_phases,
    mirrored_states,
)


def test_table_4_1_levels_at_the_boundaries() -> None:
    distances = [0.0, 6.99, 7.0, 12.99, 13.0, 19.99, 20.0, 40.0]
    assert distance_levels(distances).tolist() == [0, 0, 1, 1, 2, 2, 3, 3]


def test_sensor_order_is_the_reports() -> None:
    assert SENSOR_ORDER == ("front", "back", "left", "right", "left-front", "right-front")
    robot = mazesim.RobotProfile.builtin("seed")
    assert tuple(robot.distance_sensor_names) == SENSOR_ORDER


def test_state_encoding_round_trips_every_state() -> None:
    states = np.arange(NUM_STATES)
    levels = decode_state(states)
    assert levels.shape == (NUM_STATES, 6)
    assert np.array_equal(encode_state(levels), states)
    # The front sensor is the least significant base-4 digit.
    assert encode_state([1, 0, 0, 0, 0, 0]) == 1
    assert encode_state([0, 0, 0, 0, 0, 1]) == 4**5
    assert encode_state([3, 3, 1, 1, 2, 2]) == 3 + 3 * 4 + 16 + 64 + 2 * 256 + 2 * 1024


def test_encoding_refuses_bad_levels_and_states() -> None:
    with pytest.raises(InvalidArgumentError, match="levels as whole numbers from 0 to 3"):
        encode_state([0, 1, 2, 3, 4, 0])
    with pytest.raises(InvalidArgumentError, match="6 levels"):
        encode_state([0, 1, 2])
    with pytest.raises(InvalidArgumentError, match="states as whole numbers from 0 to 4095"):
        decode_state(4096)


@pytest.mark.parametrize(
    ("levels", "found"),
    [([1.7, 0, 0, 0, 0, 0], "1.7"), ([0, 0, np.nan, 0, 0, 0], "nan"), ([[0] * 5 + [-0.5]], "-0.5")],
)
def test_encoding_refuses_levels_that_are_not_whole(levels: list, found: str) -> None:
    # numpy's int64 cast would cut 1.7 to level 1 and state 4.9 to state 4 without a word.
    with pytest.raises(InvalidArgumentError, match=f"whole numbers from 0 to 3, found {found}"):
        encode_state(levels)
    assert encode_state([2.0, 0, 0, 0, 0, True]) == 2 + 4**5


def test_decoding_refuses_states_that_are_not_whole() -> None:
    with pytest.raises(InvalidArgumentError, match="found 4.9"):
        decode_state(4.9)
    with pytest.raises(InvalidArgumentError, match="found inf"):
        decode_state([1, np.inf])
    assert decode_state(np.float32(5.0)).tolist() == [1, 1, 0, 0, 0, 0]


def test_volts_to_cm_equals_the_core_inversion_bit_for_bit() -> None:
    volts = np.concatenate([np.linspace(0.0, 4.0, 4001), [3.03, 2.78, 1.76, 0.98, 0.66, 0.31]])
    core = np.array([mazesim.sharp_volts_to_cm(float(v)) for v in volts])
    assert np.array_equal(volts_to_cm(volts), core)


def test_distances_and_levels_are_the_core_steps_state_in_cm_and_levels() -> None:
    """One call gives the distances ``volts_to_cm`` gives and the levels Table 4.1 puts them at,
    each of the readings' shape, and the levels are those of the state the core's tabular
    controller acts on."""
    volts = np.random.default_rng(5).uniform(0.0, 3.5, (400, 6)).astype(np.float32)
    distances, levels = distances_and_levels(volts)
    assert distances.shape == levels.shape == (400, 6)
    assert np.array_equal(distances, volts_to_cm(volts))
    assert np.array_equal(levels, np.searchsorted(LEVEL_EDGES_CM, distances, side="right"))
    assert np.array_equal(encode_state(levels), observation_states(volts))
    assert set(np.unique(levels).tolist()) == {0, 1, 2, 3}


@pytest.mark.parametrize("reading", [np.nan, np.inf, -np.inf, -0.5])
def test_the_vector_discretisers_refuse_what_the_scalar_one_refuses(
    reading: float,
) -> None:
    """A reading no Sharp ranger gives (not a number, infinite, below 0 V) is refused by
    ``sharp_volts_to_cm`` and by every vector discretiser alike, not read as level 3 (NaN)."""
    with pytest.raises(InvalidArgumentError, match="0 V or more"):
        mazesim.sharp_volts_to_cm(reading)
    rows = np.full((3, 6), 1.0)
    rows[1, 2] = reading
    for discretise in (volts_to_cm, distances_and_levels, observation_states):
        with pytest.raises(InvalidArgumentError, match="readings of 0 V or more, finite") as caught:
            discretise(rows)
        assert f"found {reading} V" in str(caught.value)


@pytest.mark.parametrize("distance", [np.nan, -1.0])
def test_distance_levels_refuses_a_distance_below_0_cm_or_not_a_number(
    distance: float,
) -> None:
    with pytest.raises(InvalidArgumentError, match="distances of 0 cm or more"):
        distance_levels([25.0, distance])
    assert distance_levels([np.inf]).tolist() == [3]  # nothing seen in range: the far level


@pytest.mark.parametrize(
    "values", [np.array([1.0 + 2.0j]), np.array([None]), np.array(["1.0"]), [[1.0], [1.0, 2.0]]]
)
def test_numbers_that_are_not_real_are_no_readings(values: object) -> None:
    """numpy would drop an imaginary part, or read None as NaN, without a word."""
    for discretise in (volts_to_cm, distance_levels):
        with pytest.raises(InvalidArgumentError, match="expected"):
            discretise(values)


def test_observation_states_of_a_batch() -> None:
    world = mazesim.load_world("seed-maze")
    batch = mazesim.BatchSimulator(world, num_envs=2, robot="seed", seeds=[1, 2])
    observations = np.zeros((2, batch.observation_width), np.float32)
    poses = np.zeros((2, 3), np.float32)
    batch.reset(observations, poses, np.zeros(2, bool), np.zeros(2, np.int32))
    states = observation_states(observations)
    # At the start, facing east along the bottom corridor: open ahead, walls close on three sides.
    levels = decode_state(states)
    assert levels[:, 0].tolist() == [3, 3]
    assert levels[:, 3].tolist() == [1, 1]


def test_action_codes_and_wheel_speeds() -> None:
    assert ACTION_CODES == (
        "00", "11", "22", "33", "44", "55", "66", "77", "88", "aa", "bb", "99"
    )  # fmt: skip
    assert wheel_speeds("00", 6.28) == (3.14, 3.14)
    left, right = wheel_speeds("aa", 6.28)
    assert left > 0 > right and left == -right
    left, right = wheel_speeds("99", 6.28)
    assert left < 0 and right < 0
    for strength in range(1, 5):
        right_turn = wheel_speeds(f"{strength}" * 2, 1.0)
        left_turn = wheel_speeds(f"{strength + 4}" * 2, 1.0)
        assert right_turn[0] > right_turn[1] and left_turn == right_turn[::-1]
    assert WHEEL_SPEED_FRACTIONS.shape == (12, 2)


def test_mirror_images() -> None:
    codes = {ACTION_CODES[a]: ACTION_CODES[MIRRORED_ACTION[a]] for a in range(12)}
    assert codes["11"] == "55" and codes["88"] == "44" and codes["aa"] == "bb"
    assert codes["00"] == "00" and codes["99"] == "99"
    assert MIRRORED_SUBTASK[SubTask.RIGHT] == SubTask.LEFT
    state = encode_state([0, 1, 2, 3, 1, 2])
    assert decode_state(mirrored_states(state, SubTask.CORRIDOR)).tolist() == [0, 1, 3, 2, 2, 1]
    states = np.arange(3 * NUM_STATES)
    for subtask in SubTask:
        kinds = np.full(states.size, int(subtask))
        assert np.array_equal(mirrored_states(mirrored_states(states, kinds), kinds), states)
    # Going forward: right of straight (phase 0) mirrors to left of it (phase 2).
    assert mirrored_states(5, SubTask.FORWARD) // NUM_STATES == 2


def test_heading_phases() -> None:
    degrees = np.radians([0.0, -29.0, -31.0, -59.0, -61.0, 20.0])
    assert heading_phases(np.full(6, SubTask.RIGHT), degrees).tolist() == [0, 0, 1, 1, 2, 0]
    assert heading_phases(np.full(6, SubTask.LEFT), -degrees).tolist() == [0, 0, 1, 1, 2, 0]
    forward = np.radians([-6.0, -4.0, 0.0, 4.0, 6.0])
    assert heading_phases(np.full(5, SubTask.FORWARD), forward).tolist() == [0, 1, 1, 1, 2]
    assert heading_phases(np.full(5, SubTask.CORRIDOR), forward).tolist() == [0] * 5


def test_corridors_and_corners_never_reverses() -> None:
    from mazesim.learn.higher import HigherLevel
    from mazesim.learn.lower import lower_table_shape
    from mazesim.learn.policy import HierarchicalPolicy
    from mazesim.learn.subtasks import SUBTASK_ACTIONS

    backward = ACTION_CODES.index("99")
    assert not SUBTASK_ACTIONS[SubTask.CORRIDOR, backward]
    assert SUBTASK_ACTIONS[1:].all() and SUBTASK_ACTIONS[SubTask.CORRIDOR].sum() == 11
    # A table whose best action is backward everywhere: Corridors and Corners takes the best of
    # the others, a door sub-task takes it.
    lower = np.zeros(lower_table_shape())
    lower[:, :, backward] = 1.0
    lower[:, :, 3] = 0.5
    policy = HierarchicalPolicy(lower, HigherLevel([[1, 2]]), np.zeros(2, dtype=np.int64))
    poses = np.zeros((2, 3))
    policy.reset([0, 1], poses)
    begin_subtask(policy, 1, SubTask.RIGHT)
    actions = policy.act_on_distances(np.full((2, 6), 30.0), poses, np.zeros(2, dtype=np.int64))
    assert actions.tolist() == [3, backward]


def test_the_sharp_table_is_the_seed_profiles() -> None:
    rows = mazesim.RobotProfile.builtin("seed").distance_sensor_table(0)[:, :2].tolist()
    assert [list(row) for row in SHARP_TABLE] == rows
    assert SHARP_TABLE[0] == (0.03, 3.03) and SHARP_TABLE[-1] == (0.40, 0.31)
    assert all(type(value) is float for row in SHARP_TABLE for value in row)
