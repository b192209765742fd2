"""Issue 21: a randomisation spec's robot axis: each env's base profile drawn from a list, the
robots of other profiles trained through the seed robot's volts, as the transfer study drives
them."""

from __future__ import annotations

import dataclasses
import json
from collections import Counter
from pathlib import Path

import numpy as np
import pytest

import mazesim
from lower_oracle import SteppedFleet
from mazesim._core import RobotProfile
from mazesim.batch import RobotBatch
from mazesim.errors import InvalidArgumentError, UnknownNameError
from mazesim.learn.checkpoint import RunFolder
from mazesim.learn.fleet import Fleet, FleetBatch
from mazesim.learn.train import train
from mazesim.transfer.axes import Setting
from mazesim.transfer.randomise import parse_spec, robot_draw, sample_settings
from mazesim.transfer.readings import SeedReadings
from training_settings import TINY

ROBOTS = ("seed", "e-puck", "e-puck2", "e-puck-hardware")
SPEC = parse_spec(f"robot={'|'.join(ROBOTS)},wheel_radius=0.95:1.05,wall_reflectance=0.2:1")


def _robots(settings: list[Setting]) -> list[str]:
    return [str(setting.get("robot")) for setting in settings]


def test_an_inline_robot_list_and_a_toml_one_give_the_same_spec(tmp_path: Path) -> None:
    path = tmp_path / "robots.toml"
    path.write_text(
        "[randomise]\nrobot = ['seed', 'e-puck', 'e-puck2', 'e-puck-hardware']\n"
        "wheel_radius = [0.95, 1.05]\nwall_reflectance = [0.2, 1.0]\n"
    )
    assert parse_spec(path) == SPEC
    assert SPEC.robots == ROBOTS
    assert parse_spec(SPEC.text()) == SPEC
    assert SPEC.text().startswith("robot=seed|e-puck|e-puck2|e-puck-hardware,wheel_radius=")
    # A robot list alone is a spec too.
    assert parse_spec("robot=e-puck").robots == ("e-puck",)


def test_each_env_draws_each_listed_robot_deterministically() -> None:
    settings = sample_settings(SPEC, 400, seed=2, round_index=3)
    counts = Counter(_robots(settings))
    assert set(counts) == set(ROBOTS)
    assert all(60 <= count <= 140 for count in counts.values()), counts
    # The same seed and round give the same draw, another round another, and env i's draw does
    # not depend on how many envs there are.
    assert sample_settings(SPEC, 400, seed=2, round_index=3) == settings
    assert _robots(sample_settings(SPEC, 400, seed=2, round_index=4)) != _robots(settings)
    assert sample_settings(SPEC, 7, seed=2, round_index=3) == settings[:7]
    # The perturbations come on top of every base profile.
    radii = {setting.get("wheel_radius") for setting in settings}
    assert len(radii) == 400


def test_a_name_listed_twice_is_drawn_twice_as_often() -> None:
    spec = parse_spec("robot=seed|seed|e-puck")
    counts = Counter(_robots(sample_settings(spec, 3000, seed=0)))
    assert 1.7 < counts["seed"] / counts["e-puck"] < 2.3, counts


def test_without_a_robot_list_the_draw_is_the_one_it_was() -> None:
    # Adding the robot axis leaves a spec without it drawing what it drew (the shipped
    # randomised navigator's rounds are reproduced from its ranges).
    plain = parse_spec("wheel_radius=0.95:1.05,wall_reflectance=0.2:1")
    with_seed_only = parse_spec("robot=seed,wheel_radius=0.95:1.05,wall_reflectance=0.2:1")
    drawn = sample_settings(plain, 50, seed=5, round_index=1)
    assert sample_settings(with_seed_only, 50, seed=5, round_index=1) == drawn
    assert {setting.get("robot") for setting in drawn} == {"seed"}
    draw = robot_draw(plain, 5)(1, 50)
    assert isinstance(draw, list) and not isinstance(draw, Fleet)


@pytest.mark.parametrize(
    ("spec", "error", "message"),
    [
        ("robot=seed|e-pock", UnknownNameError, "one of seed, e-puck-hardware, e-puck, e-puck2"),
        ("robot=", UnknownNameError, "found ''"),
        ("robot=seed,robot=e-puck", InvalidArgumentError, "'robot' twice"),
    ],
)
def test_a_bad_robot_is_refused_naming_the_valid_ones(
    spec: str, error: type[Exception], message: str
) -> None:
    with pytest.raises(error, match=message):
        parse_spec(spec)


def test_a_bad_robot_in_a_toml_file_names_the_file(tmp_path: Path) -> None:
    path = tmp_path / "bad.toml"
    path.write_text("[randomise]\nrobot = ['seed', 'khepera']\n")
    with pytest.raises(
        UnknownNameError, match=r"expected robot \(in .*\) to be one of seed, "
    ) as caught:
        parse_spec(path)
    assert str(path) in str(caught.value) and "'khepera'" in str(caught.value)
    path.write_text("[randomise]\nrobot = [1, 2]\n")
    with pytest.raises(InvalidArgumentError, match="expected a list of robot profile names"):
        parse_spec(path)


def test_the_draw_is_a_fleet_led_by_each_profile_unperturbed() -> None:
    draw = robot_draw(SPEC, seed=4)
    fleet = draw(0, 40)
    assert isinstance(fleet, Fleet)
    again = draw(0, 40)
    assert isinstance(again, Fleet)
    assert [p.to_toml() for p in again.profiles] == [p.to_toml() for p in fleet.profiles]
    assert np.array_equal(fleet.group, again.group)
    for index, name in enumerate(ROBOTS):
        members = np.flatnonzero(fleet.group == index)
        assert members.size, name
        base = RobotProfile.builtin(name)
        assert fleet.profiles[int(members[0])].to_toml() == base.to_toml()
        assert all(fleet.profiles[int(env)].name.startswith(name) for env in members)
        # The seed robot's sensors pass as they are, the others' through the study's mapping.
        assert (fleet.readings[index] is None) == (name == "seed")
    # The higher level trains on the seed robot, perturbed as the same draw, robot 0 nominal.
    assert isinstance(fleet.higher, list)
    assert all(p.name.startswith("seed") for p in fleet.higher)
    assert fleet.higher[0].to_toml() == RobotProfile.builtin("seed").to_toml()
    leaders = {int(np.flatnonzero(fleet.group == index)[0]) for index in range(len(ROBOTS))}
    for env in set(range(1, 40)) - leaders:
        base = RobotProfile.builtin(ROBOTS[int(fleet.group[env])])
        scale = fleet.profiles[env].wheel_radius / base.wheel_radius
        seed_radius = RobotProfile.builtin("seed").wheel_radius
        assert fleet.higher[env].wheel_radius == pytest.approx(scale * seed_radius)


def test_a_stepped_fleet_shows_each_robot_as_its_own_batch_in_seed_volts() -> None:
    # The reference the core's fleet rounds are checked against (tests/lower_oracle.py).
    world = mazesim.load_world("seed-maze")
    profiles = [RobotProfile.builtin(name) for name in ("seed", "e-puck", "e-puck", "seed")]
    mapping = SeedReadings(RobotProfile.builtin("e-puck"))
    fleet = Fleet(profiles, np.array([0, 1, 1, 0]), [None, mapping], "seed")
    mixed = SteppedFleet(FleetBatch([world], fleet, control_step_ms=64.0, threads=1))
    alone = {
        name: RobotBatch([world], np.zeros(2, dtype=np.int64), robot=name, threads=1)
        for name in ("seed", "e-puck")
    }
    # Each robot at the start, turned its own way.
    starts = np.tile(np.array(world.start, dtype=np.float64), (4, 1))
    starts[:, 2] += np.array([0.0, 0.5, 1.0, 2.0])
    seeds = np.array([1, 2, 3, 4], dtype=np.uint64)
    mixed.place(np.arange(4), starts, seeds)
    alone["seed"].place(np.arange(2), starts[[0, 3]], seeds[[0, 3]])
    alone["e-puck"].place(np.arange(2), starts[[1, 2]], seeds[[1, 2]])
    actions = np.array([0, 3, 5, 1])
    for _ in range(20):
        mixed.step(actions)
        alone["seed"].step(actions[[0, 3]])
        alone["e-puck"].step(actions[[1, 2]])
    assert mixed.observations.shape == (4, 6)
    assert np.array_equal(mixed.poses[[0, 3]], alone["seed"].poses)
    assert np.array_equal(mixed.poses[[1, 2]], alone["e-puck"].poses)
    assert np.array_equal(mixed.observations[[0, 3]], alone["seed"].observations[:, :6])
    epuck = alone["e-puck"]
    volts = mapping.volts(epuck.observations[:, : epuck.distance_width])
    assert np.array_equal(mixed.observations[[1, 2]], volts.astype(np.float32))
    # The e-puck drives at fractions of its own motor limit, not the seed robot's.
    assert not np.array_equal(mixed.poses[1], mixed.poses[0])


def test_a_fleet_refuses_groups_it_has_no_readings_for() -> None:
    profiles = [RobotProfile.builtin("seed")] * 3
    with pytest.raises(InvalidArgumentError, match="expected groups from 0 to 0, found 0 to 1"):
        Fleet(profiles, np.array([0, 1, 0]), [None], "seed")
    with pytest.raises(InvalidArgumentError, match="expected one group per env for 3"):
        Fleet(profiles, np.array([0, 0]), [None], "seed")


def test_training_on_several_robots_is_deterministic_and_records_the_spec(
    tmp_path: Path,
) -> None:
    settings = dataclasses.replace(TINY, randomise=SPEC.text())
    one = train(settings, RunFolder(tmp_path / "one"), threads=1, robot=robot_draw(SPEC, TINY.seed))
    two = train(settings, RunFolder(tmp_path / "two"), threads=2, robot=robot_draw(SPEC, TINY.seed))
    assert one is not None and two is not None
    assert one.lower_q is not None and two.lower_q is not None
    assert np.array_equal(one.lower_q, two.lower_q)
    assert one.training["history"] == two.training["history"]
    saved = json.loads((tmp_path / "one" / "policy.json").read_text())
    assert parse_spec(saved["training"]["settings"]["randomise"]) == SPEC
    # The other profiles reach the tables: the seed robot alone, with the same ranges, learns
    # other ones.
    seed_only = parse_spec("wheel_radius=0.95:1.05,wall_reflectance=0.2:1")
    plain = train(
        dataclasses.replace(TINY, randomise=seed_only.text()),
        RunFolder(tmp_path / "plain"),
        robot=robot_draw(seed_only, TINY.seed),
    )
    assert plain is not None and plain.lower_q is not None
    assert not np.array_equal(one.lower_q, plain.lower_q)
