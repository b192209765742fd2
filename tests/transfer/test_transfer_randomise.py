"""Domain randomisation's spec (inline or TOML) and its per-env sampling."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from mazesim.errors import InvalidArgumentError, MazesimIOError, UnknownNameError
from mazesim.transfer.randomise import (
    RANDOMISED_AXES,
    RandomisationSpec,
    parse_spec,
    sample_settings,
)


def test_an_inline_spec_and_a_toml_file_give_the_same_ranges(tmp_path: Path) -> None:
    inline = parse_spec("noise_scale=0.5:4, wheel_radius=0.95:1.05")
    path = tmp_path / "ranges.toml"
    path.write_text("[randomise]\nwheel_radius = [0.95, 1.05]\nnoise_scale = [0.5, 4]\n")
    assert parse_spec(path) == inline
    # In the study's axis order, whatever order they were written in.
    assert inline.ranges == (("wheel_radius", (0.95, 1.05)), ("noise_scale", (0.5, 4.0)))


@pytest.mark.parametrize(
    ("spec", "error", "message"),
    [
        ("wheel_radius=0.95", InvalidArgumentError, "axis=low:high, found 'wheel_radius"),
        ("wheel_radius=a:b", InvalidArgumentError, "expected a TOML file or axis=low:high"),
        ("wheel_radius=1.05:0.95", InvalidArgumentError, "expected low <= high, found 1.05 > 0.95"),
        ("wheel_radius=0.1:1.05", InvalidArgumentError, r"expected a level in \[0.5, 1.5\] x"),
        (
            "latency=0:3",
            UnknownNameError,
            "a property of the robot profile to be one of .*'latency'",
        ),
        ("warp=0:1", UnknownNameError, "expected transfer axis to be one of .*; found 'warp'"),
        (",", InvalidArgumentError, "expected at least one axis range, found none"),
        ("slip=0:0.2,noise_scale=1:2,slip=0:0.5", InvalidArgumentError, "'slip' twice"),
    ],
)
def test_a_bad_inline_spec_says_what_it_expected(
    spec: str, error: type[Exception], message: str
) -> None:
    with pytest.raises(error, match=message):
        parse_spec(spec)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("[randomise]\nslip = [0.0]\n", r"slip: expected a range of two numbers \[low, high\]"),
        ("[other]\nslip = [0.0, 0.5]\n", r"expected one table \[randomise\]"),
        ("[randomise\n", "not a valid TOML file"),
        ('[randomise]\nslip = ["a", "b"]\n', "expected a range of two numbers"),
        ("[randomise]\nslip = [0, 1" + "0" * 400 + "]\n", r"slip: expected a range of two finite"),
    ],
)
def test_a_bad_toml_spec_names_the_file(tmp_path: Path, text: str, message: str) -> None:
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(InvalidArgumentError, match=message) as caught:
        parse_spec(path)
    assert str(path) in str(caught.value)


def test_a_missing_toml_file_is_an_io_error(tmp_path: Path) -> None:
    with pytest.raises(MazesimIOError, match="cannot read the randomisation file"):
        parse_spec(tmp_path / "none.toml")


def test_a_spec_file_that_is_not_text_is_refused(tmp_path: Path) -> None:
    path = tmp_path / "spec.toml"
    path.write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00")
    with pytest.raises(
        InvalidArgumentError, match="expected the randomisation file .* in UTF-8 text"
    ):
        parse_spec(path)


def test_sampling_is_uniform_in_each_range_and_repeatable() -> None:
    spec = RandomisationSpec.of({"wheel_radius": (0.95, 1.05), "slip": [0.0, 0.5]})
    settings = sample_settings(spec, 2000, seed=3, round_index=1)
    radius = np.array([s.get("wheel_radius") for s in settings])
    slip = np.array([s.get("slip") for s in settings])
    assert 0.95 <= radius.min() < 0.952 and 1.048 < radius.max() <= 1.05
    assert abs(radius.mean() - 1.0) < 0.005 and abs(slip.mean() - 0.25) < 0.02
    # Untouched axes stay at rest; the same seed and round give the same draws, others do not.
    assert {s.get("noise_scale") for s in settings} == {1.0}
    assert sample_settings(spec, 2000, seed=3, round_index=1) == settings
    assert sample_settings(spec, 2000, seed=3, round_index=2) != settings
    assert sample_settings(spec, 5, seed=3, round_index=1) == settings[:5]


def test_every_profile_axis_can_be_randomised() -> None:
    assert set(RANDOMISED_AXES) == {
        "wheel_radius", "axle_length", "motor_mismatch", "noise_scale", "ir_angle",
        "ir_offset", "wall_reflectance", "ground_drift", "slip",
    }  # fmt: skip
    with pytest.raises(InvalidArgumentError, match="at least one env"):
        sample_settings(parse_spec("slip=0:0.5"), 0, seed=0)


def test_an_axis_of_several_ranges_draws_each_range_as_often(tmp_path: Path) -> None:
    dark = parse_spec("wall_reflectance=0.2:0.4|0.2:1,slip=0:0.5")
    path = tmp_path / "dark.toml"
    path.write_text("[randomise]\nwall_reflectance = [[0.2, 0.4], [0.2, 1.0]]\nslip = [0, 0.5]\n")
    assert parse_spec(path) == dark
    assert parse_spec(dark.text()) == dark
    assert dark.text() == "wall_reflectance=0.2:0.4|0.2:1.0,slip=0.0:0.5"
    levels = np.array(
        [s.get("wall_reflectance") for s in sample_settings(dark, 4000, seed=1, round_index=0)]
    )
    assert levels.min() >= 0.2 and levels.max() <= 1.0 and levels.max() > 0.9
    # Half from [0.2, 0.4], half from [0.2, 1] (a quarter of which is below 0.4): 5/8 below.
    assert 0.6 < float(np.mean(levels < 0.4)) < 0.65
    # The other axes draw as they would without the second range.
    plain = parse_spec("wall_reflectance=0.2:1,slip=0:0.5")
    slips = [s.get("slip") for s in sample_settings(plain, 50, seed=1)]
    assert [s.get("slip") for s in sample_settings(dark, 50, seed=1)] == slips


def test_a_bad_range_among_several_is_named() -> None:
    with pytest.raises(InvalidArgumentError, match=r"expected a level in \[0.05, 1\]"):
        parse_spec("wall_reflectance=0.2:0.4|0.01:1")
    with pytest.raises(InvalidArgumentError, match="expected a TOML file or axis=low:high"):
        parse_spec("wall_reflectance=0.2:0.4|0.5")
