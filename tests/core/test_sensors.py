"""Sensor acceptance through the Python API (Webots' lookup tables, docs/robots.md)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import mazesim
from mazesim import Simulator, World

TABLE = [
    (0.0, 4095.0),
    (0.005, 2133.33),
    (0.01, 1465.73),
    (0.015, 601.46),
    (0.02, 383.84),
    (0.03, 234.93),
    (0.04, 158.03),
    (0.05, 120.0),
    (0.06, 104.09),
    (0.07, 67.19),
]


def lut(x: float) -> float:
    xs, ys = zip(*TABLE)
    return float(np.interp(x, xs, ys))


def wall_before_sensor(index: int, d: float, reflectance: float = 1.0) -> World:
    profile = mazesim.RobotProfile.builtin("e-puck")
    px, py, h = (float(v) for v in profile.distance_sensor_poses()[index])
    cx, cy = px + math.cos(h) * (d + 0.005), py + math.sin(h) * (d + 0.005)
    return World.from_toml(
        'format = "mazesim-world"\nversion = 1\n'
        f"[[walls]]\ncenter = [{cx!r}, {cy!r}]\nsize = [0.01, 0.2]\nyaw = {h!r}\n"
        f"reflectance = {reflectance!r}\n"
    )


@pytest.mark.parametrize("index", [0, 7])
@pytest.mark.parametrize("d", [0.01, 0.02, 0.03, 0.05])
def test_wall_in_front_reads_the_table(index: int, d: float) -> None:
    sim = Simulator(wall_before_sensor(index, d), noise=False)
    reading = sim.distance_sensors()
    assert reading.dtype == np.float32 and reading.shape == (8,)
    assert reading[index] == pytest.approx(lut(d), rel=0.005)


def test_free_space_reads_67_19() -> None:
    sim = Simulator(World.from_toml('format = "mazesim-world"\nversion = 1\n'), noise=False)
    assert np.all(sim.distance_sensors() == np.float32(67.19))


@pytest.mark.parametrize(("d", "f"), [(0.01, 0.5), (0.02, 0.3), (0.03, 0.8)])
def test_reflectance_scales_the_distance(d: float, f: float) -> None:
    sim = Simulator(wall_before_sensor(0, d, f), noise=False)
    assert sim.distance_sensors()[0] == pytest.approx(lut(d / f), rel=0.005)


def test_noise_matches_the_tables_sigma() -> None:
    sim = Simulator(wall_before_sensor(0, 0.03), seed=3, noise=True)
    samples = []
    for _ in range(10_000):
        sim.set_pose(0.0, 0.0, 0.0)
        samples.append(sim.distance_sensors()[0])
    rel_sd = float(np.std(samples, ddof=1)) / lut(0.03)
    assert rel_sd == pytest.approx(0.0241, rel=0.1)


def test_ground_sensors_white_black_and_edge() -> None:
    w = World.from_toml(
        'format = "mazesim-world"\nversion = 1\n[[paint]]\nshape = "rect"\n'
        "center = [0.6, 0.0]\nsize = [1.0, 1.0]\nreflectance = 0.2\n"
    )
    sim = Simulator(w, noise=False)
    assert sim.ground_sensors() == pytest.approx([856.0] * 3, abs=1.0)
    sim.set_pose(0.3, 0.0, 0.0)
    assert sim.ground_sensors() == pytest.approx([300.0] * 3, abs=0.5)
    sim.set_pose(0.07, 0.0, 0.0)
    assert np.all((sim.ground_sensors() > 320) & (sim.ground_sensors() < 840))


def test_sharp_sensors_in_volts_convert_to_cm() -> None:
    w = World.from_toml(
        'format = "mazesim-world"\nversion = 1\n'
        "[[walls]]\ncenter = [0.142, 0.0]\nsize = [0.01, 0.5]\n"
    )
    sim = Simulator(w, robot="seed", noise=False)
    assert sim.robot.distance_sensor_unit == "volts"
    assert sim.robot.distance_sensor_names[0] == "front"
    volts = float(sim.distance_sensors()[0])
    assert volts == pytest.approx(1.25, abs=0.005)
    assert mazesim.sharp_volts_to_cm(volts) == pytest.approx(10.0, abs=0.1)


def test_every_profile_reads_all_its_sensors() -> None:
    for name in mazesim.robot_profile_names():
        sim = Simulator(mazesim.load_world("seed-maze"), robot=name)
        profile = mazesim.RobotProfile.builtin(name)
        assert sim.distance_sensors().shape == (len(profile.distance_sensor_names),)
        assert sim.ground_sensors().shape == (len(profile.ground_sensor_names),)
        assert np.all(np.isfinite(sim.distance_sensors()))


@pytest.mark.parametrize(
    ("name", "distance_max", "distance_range", "ground_max"),
    [
        ("e-puck", 4095.0, 0.07, 1000.0),
        ("seed", 3.03, 0.40, 1000.0),
        ("alphabot2", 3.03, 0.40, 1023.0),
    ],
)
def test_profiles_report_their_sensor_tables_extremes(
    name: str, distance_max: float, distance_range: float, ground_max: float
) -> None:
    # The datasheet / Webots numbers of robots/*.toml, as the gym spaces bound the observations.
    robot = mazesim.RobotProfile.builtin(name)
    assert robot.distance_sensor_max == pytest.approx(distance_max)
    assert robot.distance_sensor_range == pytest.approx(distance_range)
    assert robot.ground_sensor_max == pytest.approx(ground_max)
