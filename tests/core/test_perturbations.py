"""Perturbed robot profiles (issue #21): each perturbation changes what it claims, measured in the
simulator, and neutral ones change nothing at all.
"""

from __future__ import annotations

import copy
import math
import pickle
from typing import Any

import numpy as np
import pytest

import mazesim
from batch_buffers import buffers
from mazesim import BatchSimulator, RobotProfile, RunSettings, Simulator, TabularSettings, World

SEED = RobotProfile.builtin("seed")
#: The wall of `facing_wall` is this far ahead of the seed robot's front sensor (metres).
FRONT_GAP = 0.2 - 0.01 - 0.037
HEADER = 'format = "mazesim-world"\nversion = 1\n'


def open_floor() -> World:
    return World.from_toml(HEADER, "open.toml")


def facing_wall() -> World:
    """A long white wall whose face is 0.19 m ahead of the robot's start."""
    text = HEADER + "[start]\nx = 0.0\ny = 0.0\n"
    text += "[[walls]]\ncenter = [0.2, 0.0]\nsize = [0.02, 2.0]\n"
    return World.from_toml(text, "wall.toml")


def wall_below() -> World:
    """A long wall along x whose top face is at y = -0.09."""
    text = HEADER + "[[walls]]\ncenter = [0.5, -0.1]\nsize = [3.0, 0.02]\n"
    return World.from_toml(text, "floor-wall.toml")


def drive(sim: Simulator, left: float, right: float, steps: int) -> None:
    for _ in range(steps):
        sim.step(left, right)


# --- wheels and motors ------------------------------------------------------------------------


def test_a_5_percent_wheel_radius_error_changes_straight_travel_by_5_percent() -> None:
    travelled = []
    for profile in (SEED, SEED.perturbed(drive=mazesim.DrivePerturbation(wheel_radius_scale=1.05))):
        sim = Simulator(open_floor(), robot=profile, noise=False)
        drive(sim, 4.0, 4.0, 100)
        x, y, _ = sim.pose
        assert abs(y) < 1e-9
        travelled.append(x)
        assert sim.encoders[0] == pytest.approx(4.0 * 100 * 0.032, abs=2 * SEED.encoder_resolution)
    assert travelled[1] / travelled[0] == pytest.approx(1.05, rel=1e-5)


def spun(profile: RobotProfile, steps: int = 40) -> float:
    sim = Simulator(open_floor(), robot=profile, noise=False)
    drive(sim, -1.0, 1.0, steps)
    return sim.pose[2]


def test_an_axle_error_changes_the_turn_rate_by_the_inverse_ratio() -> None:
    base, wider = (
        spun(SEED),
        spun(SEED.perturbed(drive=mazesim.DrivePerturbation(axle_length_scale=1.05))),
    )
    assert base == pytest.approx(2 * 0.0205 * 1.0 * 40 * 0.032 / 0.052, rel=1e-5)
    assert wider / base == pytest.approx(1 / 1.05, rel=1e-5)


def test_a_weaker_right_motor_curves_a_straight_command_right_by_the_predicted_radius() -> None:
    profile = SEED.perturbed(drive=mazesim.DrivePerturbation(motor_gains=(1.0, 0.95)))
    sim = Simulator(open_floor(), robot=profile, noise=False)
    drive(sim, 4.0, 4.0, 100)
    x, y, yaw = sim.pose
    assert yaw < 0 and y < 0, "it turns right"
    # On a circle of radius R = axle / 2 * (gl + gr) / (gl - gr) through the start: the chord
    # from the start subtends the angle turned.
    predicted = SEED.axle_length / 2 * 1.95 / 0.05
    assert -yaw == pytest.approx(0.0205 * 4.0 * 0.05 / SEED.axle_length * 3.2, rel=1e-5)
    assert math.hypot(x, y) / (2 * math.sin(-yaw / 2)) == pytest.approx(predicted, rel=1e-4)
    # The encoders count the wheels' true rotation; the commanded speeds are as given.
    left, right = sim.encoders
    assert right / left == pytest.approx(0.95, abs=2e-4)
    assert sim.wheel_speeds == (4.0, 4.0)


def test_slip_on_contact_shortens_travel_along_a_wall_and_not_the_encoders() -> None:
    start = (0.0, -0.09 + SEED.body_radius + 1e-4, -0.17)
    ends = []
    for slip in (0.0, 0.3):
        sim = Simulator(
            wall_below(),
            robot=SEED.perturbed(drive=mazesim.DrivePerturbation(slip_on_contact=slip)),
            noise=False,
        )
        sim.set_pose(*start)
        drive(sim, 4.0, 4.0, 60)
        assert sim.colliding
        ends.append((sim.pose[0] - start[0], sim.encoders))
    (free, free_encoders), (slipping, slipping_encoders) = ends
    assert free > 0.1
    assert slipping / free == pytest.approx(0.7, rel=1e-3)
    assert slipping_encoders == free_encoders


def test_slip_on_contact_does_nothing_away_from_walls() -> None:
    poses = []
    for slip in (0.0, 0.5):
        sim = Simulator(
            open_floor(),
            robot=SEED.perturbed(drive=mazesim.DrivePerturbation(slip_on_contact=slip)),
            noise=False,
        )
        drive(sim, 3.0, 4.0, 50)
        poses.append(sim.pose)
    assert poses[0] == poses[1]


# --- sensors ----------------------------------------------------------------------------------


def front_reading(profile: RobotProfile, noise: bool = False, seed: int = 0) -> float:
    sim = Simulator(facing_wall(), robot=profile, noise=noise, seed=seed)
    return float(sim.distance_sensors()[0])


def test_noise_scale_zero_reads_as_noise_off() -> None:
    quiet = SEED.perturbed(sensing=mazesim.SensingPerturbation(noise_scale=0.0))
    a = Simulator(World.builtin("seed-maze"), robot=quiet, seed=5)
    b = Simulator(World.builtin("seed-maze"), robot=SEED, seed=5, noise=False)
    for k in range(60):
        a.step(4.0, 3.0 + k % 3)
        b.step(4.0, 3.0 + k % 3)
        np.testing.assert_array_equal(a.distance_sensors(), b.distance_sensors())
        np.testing.assert_array_equal(a.ground_sensors(), b.ground_sensors())
        assert a.pose == b.pose


def test_noise_scale_two_doubles_the_spread_of_readings_at_a_fixed_distance() -> None:
    spread = []
    for scale in (1.0, 2.0):
        sim = Simulator(
            facing_wall(),
            robot=SEED.perturbed(sensing=mazesim.SensingPerturbation(noise_scale=scale)),
        )
        readings = []
        for seed in range(3000):
            sim.reset(seed=seed)
            readings.append(sim.distance_sensors()[0])
        spread.append(np.std(readings))
        # The mean stays the noise-free reading.
        assert np.mean(readings) == pytest.approx(front_reading(SEED), rel=2e-3)
    # Relative error of the ratio about 2 %: the bound is 5 of those, and the seeds are fixed.
    assert spread[1] / spread[0] == pytest.approx(2.0, rel=0.1)


def test_an_ir_offset_error_moves_each_sensor_along_its_heading() -> None:
    moved = SEED.perturbed(sensing=mazesim.SensingPerturbation(ir_offset_error=0.01))
    before, after = SEED.distance_sensor_poses(), moved.distance_sensor_poses()
    np.testing.assert_allclose(after[:, 2], before[:, 2])
    shift = after[:, :2] - before[:, :2]
    headings = np.stack([np.cos(before[:, 2]), np.sin(before[:, 2])], axis=1)
    np.testing.assert_allclose(shift, 0.01 * headings, atol=1e-15)
    # The front sensor reads the wall 1 cm nearer.
    seen = SEED.distance_from_reading(0, front_reading(moved))
    assert seen == pytest.approx(FRONT_GAP - 0.01, abs=1e-5)
    assert SEED.distance_from_reading(0, front_reading(SEED)) == pytest.approx(FRONT_GAP, abs=1e-5)


def test_an_ir_angle_error_turns_each_sensor_outward() -> None:
    turned = SEED.perturbed(sensing=mazesim.SensingPerturbation(ir_angle_error=0.2))
    before, after = SEED.distance_sensor_poses(), turned.distance_sensor_poses()
    # front, back (on the axis: counter-clockwise), left, right, left-front, right-front.
    np.testing.assert_allclose(after[:, 2] - before[:, 2], [0.2, 0.2, 0.2, -0.2, 0.2, -0.2])
    np.testing.assert_array_equal(after[:, :2], before[:, :2])
    # The front ray meets the square wall obliquely: it reads the longer slant distance.
    seen = SEED.distance_from_reading(0, front_reading(turned))
    assert seen == pytest.approx(FRONT_GAP / math.cos(0.2), abs=1e-5)


def test_a_darker_wall_reads_as_a_white_wall_farther_away() -> None:
    # Webots' model: a wall of reflection factor r at distance d reads as white at d / r.
    for reflectance in (0.8, 0.5):
        profile = SEED.perturbed(sensing=mazesim.SensingPerturbation(wall_reflectance=reflectance))
        assert profile.wall_reflectance == reflectance
        seen = SEED.distance_from_reading(0, front_reading(profile))
        assert seen == pytest.approx(FRONT_GAP / reflectance, abs=1e-5)
    assert front_reading(
        SEED.perturbed(sensing=mazesim.SensingPerturbation(wall_reflectance=0.5))
    ) < front_reading(SEED)


def test_ground_gain_scales_the_ground_readings() -> None:
    world = World.builtin("seed-maze")
    base = Simulator(world, robot=SEED, noise=False)
    drifted = Simulator(
        world,
        robot=SEED.perturbed(sensing=mazesim.SensingPerturbation(ground_gain=0.8)),
        noise=False,
    )
    for k in range(80):
        base.step(5.0, 5.0 - k % 2)
        drifted.step(5.0, 5.0 - k % 2)
        np.testing.assert_allclose(drifted.ground_sensors(), 0.8 * base.ground_sensors(), rtol=1e-6)
        np.testing.assert_array_equal(drifted.distance_sensors(), base.distance_sensors())


# --- neutral perturbations, profiles as values -----------------------------------------------


def random_drive(robot: Any, steps: int = 150) -> tuple[list[Any], list[Any]]:
    sim = Simulator(World.builtin("seed-maze"), robot=robot, seed=9)
    rng = np.random.default_rng(1)
    readings, poses = [], []
    for _ in range(steps):
        sim.step(*rng.uniform(-2.0, 6.28, 2))
        readings.append(np.concatenate([sim.distance_sensors(), sim.ground_sensors()]))
        poses.append(sim.pose)
    return readings, poses


def test_neutral_perturbations_run_bit_identically() -> None:
    neutral = SEED.perturbed()
    assert neutral.name == "seed~perturbed"
    base_readings, base_poses = random_drive("seed")
    readings, poses = random_drive(neutral)
    assert poses == base_poses
    np.testing.assert_array_equal(np.array(readings), np.array(base_readings))


def test_profile_fields_read_from_toml_and_written_back() -> None:
    text = SEED.to_toml().replace("motor_gains = [1.0, 1.0]", "motor_gains = [1.0, 0.9]")
    profile = RobotProfile.from_toml(text, "mine.toml")
    assert profile.motor_gains == (1.0, 0.9)
    assert (profile.noise_scale, profile.wall_reflectance, profile.ground_gain) == (1.0, 1.0, 1.0)
    assert profile.slip_on_contact == 0.0
    again = RobotProfile.from_toml(profile.to_toml())
    assert again.to_toml() == profile.to_toml()
    bad = text.replace("wall_reflectance = 1.0", "wall_reflectance = 1.5")
    with pytest.raises(mazesim.WorldFormatError, match=r"wall_reflectance") as info:
        RobotProfile.from_toml(bad, "mine.toml")
    assert info.value.source == "mine.toml"


def test_a_perturbed_profile_and_its_simulator_pickle() -> None:
    profile = SEED.perturbed(
        drive=mazesim.DrivePerturbation(wheel_radius_scale=0.97),
        sensing=mazesim.SensingPerturbation(ir_angle_error=0.05, ground_gain=1.1),
    )
    copy = pickle.loads(pickle.dumps(profile))
    assert copy.to_toml() == profile.to_toml()
    assert pickle.loads(pickle.dumps(SEED)).to_toml() == SEED.to_toml()
    sim = Simulator(World.builtin("seed-maze"), robot=profile, seed=3)
    drive(sim, 5.0, 4.0, 20)
    restored = pickle.loads(pickle.dumps(sim))
    assert restored.robot.name == "seed~perturbed"
    drive(sim, 4.0, 5.0, 20)
    drive(restored, 4.0, 5.0, 20)
    assert restored.pose == sim.pose
    np.testing.assert_array_equal(restored.distance_sensors(), sim.distance_sensors())


def test_a_snapshot_of_a_perturbed_profile_does_not_restore_into_the_original() -> None:
    world = World.builtin("seed-maze")
    perturbed = Simulator(world, robot=SEED.perturbed())
    with pytest.raises(mazesim.SnapshotError, match=r"seed~perturbed"):
        Simulator(world, robot="seed").restore(perturbed.snapshot())


# --- batches of several profiles --------------------------------------------------------------

PROFILES = [
    SEED,
    SEED.perturbed(
        drive=mazesim.DrivePerturbation(wheel_radius_scale=1.05, motor_gains=(0.97, 1.0))
    ),
    SEED.perturbed(
        drive=mazesim.DrivePerturbation(slip_on_contact=0.2),
        sensing=mazesim.SensingPerturbation(noise_scale=3.0, wall_reflectance=0.4),
    ),
    SEED.perturbed(
        sensing=mazesim.SensingPerturbation(
            ir_angle_error=-0.1, ir_offset_error=0.003, ground_gain=0.9
        )
    ),
]


#: Wheel speeds of up to five envs over 40 steps.
ACTIONS = np.random.default_rng(4).uniform(-1.0, 6.28, (40, 5, 2)).astype(np.float32)


def stepped(
    robots: list[RobotProfile], seeds: list[int], threads: int, rows: list[int]
) -> tuple[np.ndarray, np.ndarray]:
    """Observations of every step and the final poses of a batch of ``robots``, env ``j``
    driven by the wheel speeds ``ACTIONS[:, rows[j]]``."""
    world = World.builtin("seed-maze")
    batch = BatchSimulator(world, num_envs=len(robots), robot=robots, seeds=seeds, threads=threads)
    out = buffers(batch)
    batch.reset(*out)
    observations = []
    for k in range(len(ACTIONS)):
        batch.step(np.ascontiguousarray(ACTIONS[k, rows]), *out)
        observations.append(out[0].copy())
    return np.array(observations), out[1].copy()


@pytest.mark.parametrize("threads", [1, 2])
def test_per_env_profiles_in_one_batch_equal_each_profile_alone(threads: int) -> None:
    robots = [PROFILES[k] for k in (1, 0, 3, 2, 1)]
    seeds = [10, 11, 12, 13, 14]
    together, poses = stepped(robots, seeds, threads, [0, 1, 2, 3, 4])
    for i, (robot, seed) in enumerate(zip(robots, seeds)):
        alone, alone_poses = stepped([robot], [seed], 1, [i])
        np.testing.assert_array_equal(together[:, i], alone[:, 0])
        np.testing.assert_array_equal(poses[i], alone_poses[0])
    # The profiles differ, so rows of different profiles on the same wheel speeds do.
    other, _ = stepped([PROFILES[0]] * 5, seeds, threads, [0, 1, 2, 3, 4])
    assert not np.array_equal(together[:, 0], other[:, 0])


def ran(robots: list[Any], threads: int, controller: str = "random") -> dict[str, Any]:
    world = World.builtin("seed-maze")
    n = len(robots)
    batch = BatchSimulator(world, num_envs=n, robot=robots, seeds=20, threads=threads)
    out = buffers(batch)
    batch.reset(*out)
    trace = {"poses": np.zeros((30, n, 3), np.float32)}
    rule: Any = controller
    if controller == "tabular":
        rule = TabularSettings(np.random.default_rng(2).uniform(0.0, 1.0, (4096, 12)))
    seeds = np.arange(n, dtype=np.uint64) + 7
    counters = batch.run(30, rule, *out, settings=RunSettings(seeds=seeds, trace=trace))
    return {"poses": trace["poses"], "obs": out[0].copy(), "counters": counters}


EPUCK = RobotProfile.builtin("e-puck")


@pytest.mark.parametrize(
    ("controller", "base"),
    [("braitenberg", EPUCK), ("avoid-collision", EPUCK), ("random", EPUCK), ("tabular", SEED)],
)
def test_every_controller_runs_mixed_profiles_as_each_alone(
    controller: str, base: RobotProfile
) -> None:
    robots = [
        base,
        base.perturbed(
            drive=mazesim.DrivePerturbation(wheel_radius_scale=0.95),
            sensing=mazesim.SensingPerturbation(noise_scale=2.0),
        ),
        base.perturbed(
            drive=mazesim.DrivePerturbation(motor_gains=(1.0, 0.9)),
            sensing=mazesim.SensingPerturbation(wall_reflectance=0.5),
        ),
    ]
    mixed = ran(robots, threads=2, controller=controller)
    for i, robot in enumerate(robots):
        alone = ran([robot] * len(robots), threads=1, controller=controller)
        np.testing.assert_array_equal(mixed["poses"][:, i], alone["poses"][:, i])
    assert not np.array_equal(mixed["poses"][:, 0], mixed["poses"][:, 1])


def test_run_of_mixed_profiles_equals_each_profile_run_in_its_slot() -> None:
    mixed = ran(PROFILES, threads=2)
    for i, profile in enumerate(PROFILES):
        alone = ran([profile] * len(PROFILES), threads=1)
        np.testing.assert_array_equal(mixed["poses"][:, i], alone["poses"][:, i])
        np.testing.assert_array_equal(mixed["obs"][i], alone["obs"][i])
    # A profile of faster wheels drives farther on the same random wheel speeds.
    fast = ran(
        [PROFILES[0].perturbed(drive=mazesim.DrivePerturbation(wheel_radius_scale=2.0))] * 4,
        threads=1,
    )
    slow = ran([PROFILES[0]] * 4, threads=1)
    assert not np.array_equal(fast["poses"], slow["poses"])


def test_run_steps_match_single_steps_for_a_perturbed_profile() -> None:
    profile = PROFILES[2]
    world = World.builtin("seed-maze")
    batch = BatchSimulator(world, num_envs=2, robot=profile, seeds=[3, 4])
    out = buffers(batch)
    batch.reset(*out)
    trace = {"wheel_speeds": np.zeros((25, 2, 2), np.float32)}
    settings = RunSettings(seeds=np.array([1, 2], np.uint64), trace=trace)
    batch.run(25, "random", *out, settings=settings)
    stepper = BatchSimulator(world, num_envs=2, robot=profile, seeds=[3, 4])
    again = buffers(stepper)
    stepper.reset(*again)
    for k in range(25):
        stepper.step(np.ascontiguousarray(trace["wheel_speeds"][k]), *again)
    np.testing.assert_array_equal(again[0], out[0])
    np.testing.assert_array_equal(again[1], out[1])


def test_one_profile_given_any_way_costs_the_same_memory() -> None:
    world = World.builtin("seed-maze")
    n = 64
    by_name = BatchSimulator(world, num_envs=n, robot="seed").bytes_per_env()
    by_profile = BatchSimulator(world, num_envs=n, robot=SEED).bytes_per_env()
    by_list = BatchSimulator(world, num_envs=n, robot=[SEED] * n).bytes_per_env()
    assert by_name == by_profile == by_list
    two = BatchSimulator(world, num_envs=n, robot=[SEED, PROFILES[1]] * (n // 2)).bytes_per_env()
    assert by_name < two < by_name + 256


def test_set_world_and_resets_keep_each_envs_profile() -> None:
    world, arena = World.builtin("seed-maze"), World.builtin("arena")
    batch = BatchSimulator(world, num_envs=2, robot=[SEED, PROFILES[1]], seeds=[1, 2])
    batch.set_world(1, arena, 5)
    out = buffers(batch)
    batch.reset(*out)
    alone = BatchSimulator(arena, num_envs=1, robot=PROFILES[1], seeds=[5])
    single = buffers(alone)
    alone.reset(*single)
    for _ in range(20):
        batch.step(np.full((2, 2), 5.0, np.float32), *out)
        alone.step(np.full((1, 2), 5.0, np.float32), *single)
    np.testing.assert_array_equal(out[1][1], single[1][0])
    np.testing.assert_array_equal(out[0][1], single[0][0])


# --- bad arguments ----------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("arguments", "named"),
    [
        ({"wheel_radius_scale": 0.0}, "wheel_radius_scale"),
        ({"wheel_radius_scale": float("nan")}, "wheel_radius_scale"),
        ({"axle_length_scale": -1.05}, "axle_length_scale"),
        ({"axle_length_scale": 1e300}, "axle_length_scale"),
        ({"motor_gains": (1.0, 0.0)}, "motor_gains"),
        ({"motor_gains": (1.0,)}, "motor_gains"),
        ({"motor_gains": "ab"}, "motor_gains"),
        ({"noise_scale": -0.1}, "noise_scale"),
        ({"noise_scale": float("inf")}, "noise_scale"),
        ({"ir_angle_error": 4.0}, "ir_angle_error"),
        ({"ir_offset_error": 0.05}, "ir_offset_error"),
        ({"wall_reflectance": 0.0}, "wall_reflectance"),
        ({"wall_reflectance": 1.01}, "wall_reflectance"),
        ({"ground_gain": 0.0}, "ground_gain"),
        ({"slip_on_contact": 1.0}, "slip_on_contact"),
        ({"slip_on_contact": -0.1}, "slip_on_contact"),
        ({"slip_on_contact": 10**400}, "slip_on_contact"),
    ],
)
def test_bad_perturbations_are_refused_naming_the_argument(
    arguments: dict[str, Any], named: str
) -> None:
    drive = {k: v for k, v in arguments.items() if k in DRIVE}
    sensing = {k: v for k, v in arguments.items() if k not in DRIVE}
    with pytest.raises(mazesim.InvalidArgumentError, match=rf"expected {named}.*found"):
        # The offset's bound is the robot's body radius: checked by perturbed.
        SEED.perturbed(mazesim.DrivePerturbation(**drive), mazesim.SensingPerturbation(**sensing))


#: The parameters of DrivePerturbation (the others are SensingPerturbation's).
DRIVE = ("wheel_radius_scale", "axle_length_scale", "motor_gains", "slip_on_contact")


def test_perturbed_takes_perturbations_only() -> None:
    with pytest.raises(mazesim.InvalidArgumentError, match="expected drive to be a Drive"):
        SEED.perturbed(1.05)  # type: ignore[arg-type]
    with pytest.raises(mazesim.InvalidArgumentError, match="expected sensing to be a Sensing"):
        SEED.perturbed(sensing=mazesim.DrivePerturbation())  # type: ignore[arg-type]
    with pytest.raises(mazesim.InvalidArgumentError, match="not_a_keyword"):
        SEED.perturbed(not_a_keyword=1.0)  # type: ignore[call-arg]


def test_former_keywords_warn_and_perturb_as_the_perturbations_do() -> None:
    changes = {
        "wheel_radius_scale": 0.97,
        "axle_length_scale": 1.02,
        "motor_gains": (1.0, 0.95),
        "slip_on_contact": 0.1,
        "noise_scale": 2.0,
        "ir_angle_error": 0.05,
        "ir_offset_error": 0.002,
        "wall_reflectance": 0.6,
        "ground_gain": 1.1,
    }
    drive = mazesim.DrivePerturbation(**{k: v for k, v in changes.items() if k in DRIVE})
    sensing = mazesim.SensingPerturbation(**{k: v for k, v in changes.items() if k not in DRIVE})
    with pytest.warns(DeprecationWarning, match="perturbed's keyword .* is deprecated"):
        former = SEED.perturbed(**changes)  # type: ignore[call-arg]
    assert former == SEED.perturbed(drive, sensing)
    assert former.to_toml() == SEED.perturbed(drive=drive, sensing=sensing).to_toml()
    with pytest.raises(mazesim.InvalidArgumentError, match="either drive and sensing or"):
        SEED.perturbed(drive, noise_scale=2.0)  # type: ignore[call-arg]
    with (
        pytest.warns(DeprecationWarning),
        pytest.raises(mazesim.InvalidArgumentError, match="ir_offset_error"),
    ):
        SEED.perturbed(ir_offset_error=0.05)  # type: ignore[call-arg]


def test_the_perturbations_show_and_keep_their_values() -> None:
    drive = mazesim.DrivePerturbation(wheel_radius_scale=1.05, motor_gains=[1.0, 0.9])
    assert repr(drive) == (
        "DrivePerturbation(wheel_radius_scale=1.05, axle_length_scale=1.0, "
        "motor_gains=(1.0, 0.9), slip_on_contact=0.0)"
    )
    assert drive.motor_gains == (1.0, 0.9) and drive.wheel_radius_scale == 1.05
    sensing = mazesim.SensingPerturbation(noise_scale=0.0, ground_gain=0.8)
    assert repr(sensing) == (
        "SensingPerturbation(noise_scale=0.0, ir_angle_error=0.0, ir_offset_error=0.0, "
        "wall_reflectance=1.0, ground_gain=0.8)"
    )
    assert drive == mazesim.DrivePerturbation(1.05, motor_gains=(1.0, 0.9))
    assert drive != mazesim.DrivePerturbation() and sensing != mazesim.SensingPerturbation()
    assert hash(sensing) == hash(mazesim.SensingPerturbation(0.0, ground_gain=0.8))
    for value in (drive, sensing):
        for again in (pickle.loads(pickle.dumps(value)), copy.deepcopy(value)):
            assert again == value and repr(again) == repr(value)
    with pytest.raises(AttributeError):
        drive.slip_on_contact = 0.5  # type: ignore[misc]


def test_a_batch_of_profiles_of_other_sensors_or_count_is_refused() -> None:
    world = World.builtin("seed-maze")
    with pytest.raises(mazesim.InvalidArgumentError, match=r"environment 1 with 8 and 3"):
        BatchSimulator(world, num_envs=2, robot=[SEED, "e-puck"])
    with pytest.raises(mazesim.InvalidArgumentError, match=r"sequence of 3 .* found 2 of them"):
        BatchSimulator(world, num_envs=3, robot=[SEED, SEED])
    with pytest.raises(mazesim.InvalidArgumentError, match=r"expected robot\[1\] to be"):
        BatchSimulator(world, num_envs=2, robot=[SEED, 3])
    with pytest.raises(mazesim.UnknownNameError):
        BatchSimulator(world, num_envs=2, robot=[SEED, "khepera"])
    with pytest.raises(mazesim.InvalidArgumentError, match=r"expected robot to be .*found a"):
        Simulator(world, robot=[SEED])
