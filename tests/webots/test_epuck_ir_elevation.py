"""The E-puck PROTO's tilted proximity sensors: each ``E-puckDistanceSensor`` turns its
DistanceSensor 0.16 rad about the mount's z axis, which the mounts lay horizontal, so every
ray rises 9.17 degrees (Webots 8.6 to R2025a). An imported ``E-puck`` node reads walls along its
tilted rays; mazesim's own worlds and profiles keep level ones (docs/webots.md)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import mazesim
from mazesim import RobotProfile, Simulator, World
from mazesim.webots import prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.scene import EPUCK_IR_ELEVATION, read_scene

#: ps0's mount in Webots' E-puck PROTO (R2025a): axis-angle rotation; the ray is the x axis
#: turned by it after the E-puckDistanceSensor's own 0.16 rad about z.
PS0_MOUNT = ((-0.977797, 0.14818, 0.148178), -1.593259)


def _rotation(axis: tuple[float, float, float], angle: float) -> np.ndarray:
    k = np.asarray(axis) / np.linalg.norm(axis)
    cross = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * cross + (1 - math.cos(angle)) * cross @ cross


def test_the_proto_tilts_the_ray_by_its_0_16_rad_without_turning_it() -> None:
    ray = _rotation(*PS0_MOUNT) @ _rotation((0.0, 0.0, 1.0), 0.16) @ np.array([1.0, 0, 0])
    assert math.asin(ray[2]) == pytest.approx(EPUCK_IR_ELEVATION, abs=1e-4)
    heading = RobotProfile.builtin("e-puck").distance_sensor_poses()[0][2]
    assert math.atan2(ray[1], ray[0]) == pytest.approx(heading, abs=1e-3)


def _box_ahead() -> World:
    """A wall whose face is 0.06 m ahead of the robot's centre (0.03 m from ps0 and ps7)."""
    return World.from_toml(
        'format = "mazesim-world"\nversion = 1\n[[walls]]\ncenter = [0.56, 0.0]\nsize = [1, 1]\n'
    )


def test_a_tilted_profile_reads_a_wall_farther_and_pickles_whole() -> None:
    level = RobotProfile.builtin("e-puck")
    tilted = level.with_infrared_elevation(0.16)
    assert tilted.distance_sensor_elevations() == [0.16] * 8
    assert level.distance_sensor_elevations() == [0.0] * 8
    assert tilted.name == level.name and tilted != level
    flat = Simulator(_box_ahead(), robot=level, noise=False).distance_sensors()
    up = Simulator(_box_ahead(), robot=tilted, noise=False).distance_sensors()
    assert np.all(up[[0, 7]] < flat[[0, 7]])
    # ps7 looks at the wall 0.2992 rad off its normal: 0.03 / cos(0.2992) across the floor,
    # that over cos(0.16) along the ray, read through the table between 0.03 and 0.04 m.
    slant = 0.03 / math.cos(0.2992) / math.cos(0.16)
    expected = 234.93 + (slant - 0.03) / 0.01 * (158.03 - 234.93)
    assert float(up[7]) == pytest.approx(expected, rel=2e-3)
    assert RobotProfile.from_toml(tilted.to_toml()) == tilted
    with pytest.raises(mazesim.InvalidArgumentError, match="infra-red elevation"):
        level.with_infrared_elevation(1.2)


@pytest.mark.parametrize(
    ("text", "elevation"),
    [
        ("#VRML_SIM R2023b utf8\nE-puck { }\n", EPUCK_IR_ELEVATION),
        ('#VRML_SIM R2023b utf8\nE-puck { version "2" }\n', EPUCK_IR_ELEVATION),
        ("#VRML_SIM V8.6 utf8\nE-puck { }\n", EPUCK_IR_ELEVATION),
        ('#VRML_SIM R2023b utf8\nRobot { name "e-puck" }\n', 0.0),
        ("#VRML_SIM R2023b utf8\nEPuck { }\n", 0.0),
    ],
)
def test_only_an_e_puck_proto_node_has_tilted_rays(text: str, elevation: float) -> None:
    assert read_scene(text).infrared_elevation == elevation


def test_an_imported_e_puck_senses_along_tilted_rays_and_a_mazesim_world_along_level_ones() -> None:
    readings = []
    for scene in (None, read_scene("#VRML_SIM R2023b utf8\nE-puck { }\n")):
        prepare(_box_ahead(), seconds=1.0, noise=False, scene=scene)
        simulator = simulations.current().simulator
        readings.append(simulator.distance_sensors())
        assert simulator.robot.distance_sensor_elevations()[0] == (
            0.0 if scene is None else EPUCK_IR_ELEVATION
        )
        simulations.release()
    level, tilted = readings
    assert np.array_equal(level, Simulator(_box_ahead(), noise=False).distance_sensors())
    assert np.all(tilted[[0, 7]] < level[[0, 7]])
