"""The study's perturbations reach the robots of its batches and change what they claim."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mazesim import DrivePerturbation, RobotProfile, SensingPerturbation
from mazesim.transfer.axes import Setting
from mazesim.transfer.cells import CellRun, profile_changes, profile_of


def test_a_settings_profile_carries_its_scales() -> None:
    seed = RobotProfile.builtin("seed")
    wider = profile_of(Setting.of({"wheel_radius": 1.05, "axle_length": 0.95}))
    assert wider.wheel_radius == pytest.approx(1.05 * seed.wheel_radius)
    assert wider.axle_length == pytest.approx(0.95 * seed.axle_length)
    assert profile_of(Setting.of({"robot": "alphabot2"})).name == "alphabot2"


def test_settings_on_one_robot_share_its_one_parse_and_perturb_it_as_a_fresh_one() -> None:
    setting = Setting.of({"wheel_radius": 1.05, "ir_angle": 10.0, "noise_scale": 2.0})
    assert profile_changes(setting) == {
        "wheel_radius_scale": 1.05,
        "ir_angle_error": math.radians(10.0),
        "noise_scale": 2.0,
    }
    fresh = RobotProfile.builtin("seed").perturbed(
        DrivePerturbation(wheel_radius_scale=1.05),
        SensingPerturbation(ir_angle_error=math.radians(10.0), noise_scale=2.0),
    )
    assert profile_of(setting).to_toml() == fresh.to_toml()
    assert profile_of(Setting()) is profile_of(Setting.of({"robot": "seed"}))
    assert profile_of(Setting()).to_toml() == RobotProfile.builtin("seed").to_toml()


def _straight_travel(run: CellRun, settings: list[Setting], steps: int) -> np.ndarray:
    """Metres each cell's first robot drives in ``steps`` cruise steps from the same start."""
    nav = run.batch("seed", settings)
    nav.start(np.arange(nav.num_envs), np.zeros(nav.num_envs, dtype=np.int64))
    start = nav.poses[:, :2].astype(np.float64).copy()
    for _ in range(steps):
        nav.step(np.zeros(nav.num_envs, dtype=np.int64))  # 00: forward at cruise speed
    travelled = np.hypot(*(nav.poses[:, :2] - start).T)
    first = np.searchsorted(nav.world_of_env, np.arange(len(settings)))
    return travelled[first]


def test_a_five_percent_wheel_radius_error_changes_straight_travel_by_five_percent(
    run: CellRun,
) -> None:
    cells = [Setting(), Setting.of({"wheel_radius": 1.05}), Setting.of({"wheel_radius": 0.95})]
    plain, longer, shorter = _straight_travel(run, cells, 10)
    assert plain > 0.03
    assert longer / plain == pytest.approx(1.05, rel=0.01)
    assert shorter / plain == pytest.approx(0.95, rel=0.01)


def test_a_weaker_left_motor_turns_the_robot_left(run: CellRun) -> None:
    cells = [Setting(), Setting.of({"motor_mismatch": -0.1})]
    nav = run.batch("seed", cells)
    nav.start(np.arange(nav.num_envs), np.zeros(nav.num_envs, dtype=np.int64))
    yaw = nav.poses[:, 2].astype(np.float64).copy()
    for _ in range(5):
        nav.step(np.zeros(nav.num_envs, dtype=np.int64))
    turned = (nav.poses[:, 2] - yaw + math.pi) % (2 * math.pi) - math.pi
    first = np.searchsorted(nav.world_of_env, np.arange(2))
    assert abs(turned[first[0]]) < 1e-6
    assert turned[first[1]] > 0.01  # a weaker left wheel swings the robot to the left


def test_other_robots_and_perturbed_cells_run_through_the_study(run: CellRun) -> None:
    from mazesim.transfer.cells import run_cells

    settings = [
        Setting.of({"robot": "alphabot2"}),
        Setting.of({"robot": "e-puck"}),
        Setting.of({"noise_scale": 4.0}),
        Setting.of({"robot": "alphabot2", "latency": 1.0}),
    ]
    measures = run_cells(settings, run)
    assert [m.episodes for m in measures] == [2, 2, 2, 2]
    for measure in measures:
        assert 0.0 <= measure.success_rate <= 1.0 and measure.mean_collisions >= 0.0


def test_both_ends_of_every_documented_range_make_a_profile() -> None:
    from mazesim.transfer import AXES
    from mazesim.transfer.randomise import RANDOMISED_AXES

    for axis in AXES:
        if axis.name in RANDOMISED_AXES:
            for level in (axis.low, axis.high):
                assert profile_of(Setting.of({axis.name: level})).name == "seed~perturbed"
