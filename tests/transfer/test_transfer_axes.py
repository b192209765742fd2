"""The transfer study's axes and settings, and another robot's readings in seed volts."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mazesim import RobotProfile
from mazesim.errors import InvalidArgumentError, UnknownNameError
from mazesim.learn.discretise import SENSOR_ORDER, distance_levels, volts_to_cm
from mazesim.transfer import AXES, AXIS_NAMES, Setting, parse_axes
from mazesim.transfer.cells import profile_changes
from mazesim.transfer.readings import FAR_CM, SeedReadings


def test_every_axis_documents_its_range_and_its_levels_fit_it() -> None:
    assert len(AXIS_NAMES) == len(set(AXIS_NAMES)) == 12
    for axis in AXES:
        assert axis.levels, axis.name
        assert axis.rest not in axis.levels, axis.name
        for level in axis.levels:
            assert axis.check(level) == level
        assert axis.description and axis.label(axis.levels[0])


def test_the_documented_ranges_are_the_issues() -> None:
    levels = {axis.name: axis.levels for axis in AXES}
    assert min(levels["wheel_radius"]) == 0.95 and max(levels["wheel_radius"]) == 1.05
    assert min(levels["axle_length"]) == 0.95 and max(levels["axle_length"]) == 1.05
    assert min(levels["noise_scale"]) == 0.5 and max(levels["noise_scale"]) == 4.0
    assert levels["latency"] == (1.0, 2.0, 3.0)
    assert levels["link"] == ("ros",)
    assert min(levels["wall_reflectance"]) == 0.2


def test_parse_axes_keeps_the_study_order_and_refuses_unknown_names() -> None:
    assert [a.name for a in parse_axes("link, latency,link")] == ["latency", "link"]
    with pytest.raises(
        UnknownNameError, match="expected transfer axis to be one of .*; found 'warp'"
    ):
        parse_axes("latency,warp")
    with pytest.raises(InvalidArgumentError, match="found none"):
        parse_axes(" , ")


@pytest.mark.parametrize(
    ("values", "message"),
    [
        ({"wheel_radius": 2.0}, r"expected a level in \[0.5, 1.5\] x, found 2"),
        ({"robot": "r2d2"}, "axis 'robot' to be one of seed, e-puck-hardware"),
        ({"latency": math.nan}, "expected a number, found nan"),
        ({"link": 1.0}, "axis 'link' to be one of lockstep, ros"),
    ],
)
def test_a_setting_refuses_levels_off_its_axis(values: dict[str, object], message: str) -> None:
    # A level off a named axis is an unknown name, one off a numbered axis an invalid argument.
    with pytest.raises((InvalidArgumentError, UnknownNameError), match=message):
        Setting.of(values)  # type: ignore[arg-type]


def test_a_setting_asks_the_profile_for_what_its_axes_change() -> None:
    setting = Setting.of(
        {"ir_angle": 10.0, "ir_offset": -5.0, "motor_mismatch": -0.1, "ground_drift": 1.2}
    )
    assert profile_changes(setting) == {
        "ground_gain": 1.2,
        "motor_gains": (0.9, 1.0),
        "ir_angle_error": pytest.approx(math.radians(10.0)),
        "ir_offset_error": -0.005,
    }
    assert profile_changes(Setting.of({"motor_mismatch": 0.05}))["motor_gains"] == (1.0, 0.95)
    # Latency, link and another robot are not changes of a profile.
    assert profile_changes(Setting.of({"latency": 2.0, "link": "ros", "robot": "e-puck"})) == {}
    assert Setting().label() == "baseline"
    assert Setting.of({"link": "ros", "latency": 1.0}).axes == ("latency", "link")


def test_the_e_puck_reads_each_direction_with_its_nearest_sensors() -> None:
    readings = SeedReadings(RobotProfile.builtin("e-puck"))
    names = RobotProfile.builtin("e-puck").distance_sensor_names
    chosen = {
        direction: [names[i] for i in sensors]
        for direction, sensors in zip(SENSOR_ORDER, readings.sensors)
    }
    assert chosen == {
        "front": ["ps0", "ps7"],
        "back": ["ps3", "ps4"],
        "left": ["ps5"],
        "right": ["ps2"],
        "left-front": ["ps6"],
        "right-front": ["ps1"],
    }


def test_e_puck_counts_become_seed_volts_by_distance() -> None:
    readings = SeedReadings(RobotProfile.builtin("e-puck"))
    # ps0 sees a wall at 3 cm (234.93 counts), the rest nothing (the table's last row).
    row = np.full((1, 11), 67.19)
    row[0, 0] = 234.93
    centimetres = volts_to_cm(readings.volts(row))[0]
    # The front takes the nearer of ps0 and ps7; 3 cm is the Sharp table's nearest entry.
    assert centimetres[0] == pytest.approx(3.0, abs=0.05)
    assert np.allclose(centimetres[1:], FAR_CM, atol=0.1)
    assert distance_levels(centimetres[None])[0].tolist() == [0, 3, 3, 3, 3, 3]


def test_the_alphabot2_readings_pass_unchanged_within_range() -> None:
    readings = SeedReadings(RobotProfile.builtin("alphabot2"))
    assert readings.sensors == [[0], [1], [2], [3], [4], [5]]
    volts = np.array([[3.03, 2.33, 1.25, 0.66, 0.42, 0.31, 800.0]])
    mapped = readings.volts(volts)
    assert np.allclose(mapped[0, :5], volts[0, :5], atol=1e-3)
    assert mapped[0, 5] == pytest.approx(0.31)
