"""The e-puck's proximity sensors against Webots' E-puck PROTO, and what its rear pair can read
of a box behind it (the `dominikzurek/reactive-behaviors` row of docs/webots-compat.md).

The PROTO mounts ps0..ps7 as ``E-puckDistanceSensor`` nodes at a translation and an axis-angle
rotation each (facts quoted below, Webots R2025a ``E-puck.proto``); the sensor's ray is its x
axis. Each ``E-puckDistanceSensor`` holds one ray (``numberOfRays 1``, aperture 0.1) of type
infra-red with the lookup table mazesim's ``e-puck`` profile carries. It also turns its
DistanceSensor 0.16 rad about the sensor's own z axis, which tilts the ray 9 degrees upward
(an imported E-puck's rays tilt so; the ``e-puck`` profile's, checked here, are level, and read a
wall at a given horizontal distance as if 1.3 % nearer). Here that cancels: the controller stops
by its front sensors' readings, so with the tilt it stops 0.7 mm nearer and the best rear pair
reads 80.06 instead of 80.00, still below the controller's 82.2.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import mazesim
from mazesim import Simulator, World

#: ps0..ps7 in Webots' E-puck PROTO: translation x, y (m) and rotation axis, angle (rad).
PROTO_MOUNTS = (
    (0.03, -0.01, (-0.977797, 0.14818, 0.148178), -1.593259),
    (0.022, -0.025, (0.858029, -0.363171, -0.363172), 1.723331),
    (0.0, -0.031, (-0.577352, 0.577348, 0.577352), -2.094405),
    (-0.03, -0.015, (0.176824, -0.695961, -0.695968), 2.79157),
    (-0.03, 0.015, (0.17854, 0.695742, 0.695749), 2.788236),
    (0.0, 0.031, (0.577354, 0.577344, 0.577352), 2.094396),
    (0.022, 0.025, (0.858533, 0.362572, 0.362579), 1.722748),
    (0.03, 0.01, (-0.978028, -0.147411, -0.147416), -1.593022),
)
#: The reactive-behaviors controller turns until both rear sensors read above this.
REAR_ALIGN_THRESHOLD = 82.2
#: ... after stopping where both front sensors read at least this.
FRONT_STOP_THRESHOLD = 100.0


def _ray_direction(axis: tuple[float, float, float], angle: float) -> np.ndarray:
    """The x axis turned by an axis-angle rotation (Rodrigues' formula)."""
    k = np.asarray(axis) / np.linalg.norm(axis)
    x = np.array([1.0, 0.0, 0.0])
    return (
        x * math.cos(angle)
        + np.cross(k, x) * math.sin(angle)
        + k * np.dot(k, x) * (1.0 - math.cos(angle))
    )


@pytest.mark.parametrize("index", range(8))
def test_proximity_sensors_sit_and_point_as_the_protos(index: int) -> None:
    x, y, axis, angle = PROTO_MOUNTS[index]
    ray = _ray_direction(axis, angle)
    assert abs(ray[2]) < 1e-3  # the mount itself keeps the ray level
    pose = mazesim.RobotProfile.builtin("e-puck").distance_sensor_poses()[index]
    assert pose[:2] == pytest.approx([x, y], abs=1e-9)
    assert pose[2] == pytest.approx(math.atan2(ray[1], ray[0]), abs=1e-3)


def _box_ahead() -> World:
    """The world's first box: 0.5 m wide, its face 0.76 m ahead of the start."""
    return World.from_toml(
        'format = "mazesim-world"\nversion = 1\n'
        "[[walls]]\ncenter = [1.01, 0.0]\nsize = [0.5, 0.5]\n"
    )


def _front_stop(sim: Simulator) -> float:
    """The x (heading +x) at which both front sensors first read the stop threshold."""
    near, far = 0.60, 0.74
    for _ in range(40):
        mid = 0.5 * (near + far)
        sim.set_pose(mid, 0.0, 0.0)
        ps = sim.distance_sensors()
        if min(ps[0], ps[7]) >= FRONT_STOP_THRESHOLD:
            far = mid
        else:
            near = mid
    return far


def test_the_rear_pair_never_both_reach_the_threshold_without_noise() -> None:
    sim = Simulator(_box_ahead(), noise=False)
    x = _front_stop(sim)
    assert x == pytest.approx(0.6716, abs=2e-4)
    best = (0.0, 0.0)
    for tenth in range(1500, 2101):
        yaw = math.radians(tenth / 10)
        sim.set_pose(x, 0.0, yaw)
        ps = sim.distance_sensors()
        best = max(best, (float(min(ps[3], ps[4])), tenth / 10))
    # The best heading is the half turn, and even there the pair reads 80, not 82.2.
    assert best[1] == pytest.approx(180.0, abs=1.0)
    assert best[0] == pytest.approx(80.0, abs=0.3)
    assert best[0] < REAR_ALIGN_THRESHOLD


def test_forty_seven_fast_steps_turn_the_e_puck_past_the_half_turn() -> None:
    sim = Simulator(_box_ahead(), noise=False, control_step_ms=32.0)  # basicTimeStep 32
    sim.set_pose(0.6716, 0.0, 0.0)
    for _ in range(47):
        sim.step(-3.14, 3.14)
    _, _, yaw = sim.pose
    turned = math.degrees(yaw) % 360.0
    assert turned == pytest.approx(190.4, abs=0.5)
    ps = sim.distance_sensors()
    # Past the half turn ps3 looks beside the box (free space) and ps4 nearly straight at it.
    assert ps[3] == pytest.approx(67.19, abs=0.01)
    assert ps[4] > FRONT_STOP_THRESHOLD


def test_the_proto_s_tilted_rays_leave_the_rear_pair_below_the_threshold_too() -> None:
    tilted = mazesim.RobotProfile.builtin("e-puck").with_infrared_elevation(0.16)
    sim = Simulator(_box_ahead(), robot=tilted, noise=False)
    x = _front_stop(sim)
    assert x == pytest.approx(0.6724, abs=2e-4)
    best = 0.0
    for tenth in range(1700, 1901):
        sim.set_pose(x, 0.0, math.radians(tenth / 10))
        ps = sim.distance_sensors()
        best = max(best, float(min(ps[3], ps[4])))
    assert best == pytest.approx(80.06, abs=0.05)
    assert best < REAR_ALIGN_THRESHOLD
