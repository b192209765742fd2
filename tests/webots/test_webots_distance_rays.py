"""A DistanceSensor of several rays, and a sonar, read as Webots reads them (#32).

Webots' ``WbDistanceSensor`` (src/webots/nodes/WbDistanceSensor.cpp) lays up to 10 rays out by a
fixed table of circles in a cone of half-angle ``aperture / 2`` (2 rays: one up, one down, in
the sensor's x-z plane), weighs each by ``exp(-(theta / (aperture * gaussianWidth))^2)``, and
makes one distance of them by the sensor's type: the weighted mean (generic), that mean over the
weighted mean reflection factor (infra-red), the nearest ray heard back within pi/8 of a
surface's normal (sonar). mazesim cast one ray per sensor before; a project whose MyBot has two
eyes of ``numberOfRays 2, aperture 1`` 6.3 cm up (Webots' emitter_receiver sample) read nothing
where Webots reads the floor under the lower ray.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from mazesim.webots.distance_rays import (
    GENERIC,
    INFRA_RED,
    LASER,
    MOST_RAYS,
    SONAR,
    DistanceRays,
    RayHits,
    sensor_distance,
    sensor_type,
)
from mazesim.webots.own_sensors import own_sensors
from mazesim.webots.scene import read_scene
from supervised_world import slot_readings, supervisor_in

#: A generic table: 0 m reads 0, 0.15 m (the rays' reach) reads 1000.
TABLE = "lookupTable [ 0 0 0 0.15 1000 0 ]"


def test_two_rays_point_up_and_down_by_half_the_aperture_and_weigh_alike() -> None:
    rays = DistanceRays.of(2, 1.0)
    up, down = rays.directions
    assert up == pytest.approx([math.cos(0.5), 0.0, math.sin(0.5)])
    assert down == pytest.approx([math.cos(0.5), 0.0, -math.sin(0.5)])
    assert rays.weights == pytest.approx([0.5, 0.5])


@pytest.mark.parametrize("count", [3, 4, 5, 6, 7, 8, 9, 10, 11, 20, 37])
def test_every_layout_holds_its_rays_in_the_cone_weighted_to_one(count: int) -> None:
    rays = DistanceRays.of(count, 0.8, gaussian_width=0.5)
    assert len(rays) == count
    assert np.linalg.norm(rays.directions, axis=1) == pytest.approx(np.ones(count))
    off_axis = np.arccos(np.clip(rays.directions[:, 0], -1.0, 1.0))
    assert off_axis.max() == pytest.approx(0.4)
    assert rays.weights.sum() == pytest.approx(1.0)
    # A ray nearer the axis weighs more; rays equally far off it weigh alike.
    order = np.argsort(off_axis)
    assert np.all(np.diff(rays.weights[order]) <= 1e-12)
    # The layouts are balanced about the axis (left-right, and up-down for most).
    assert abs(rays.directions[:, 1].sum()) < 1e-9


def test_the_weights_follow_webots_gaussian_of_the_angle_off_the_axis() -> None:
    # 4 rays: the axis and a circle of three at half the aperture; gaussianWidth 1: exp(-(0.5)^2)
    rays = DistanceRays.of(4, 0.6)
    circle = math.exp(-0.25)
    assert rays.weights == pytest.approx(np.array([1.0, circle, circle, circle]) / (1 + 3 * circle))


@pytest.mark.parametrize(
    ("count", "aperture", "kind", "expected"),
    [(0, 1.0, GENERIC, 1), (-3, 1.0, GENERIC, 1), (5, 0.0, GENERIC, 1), (5, 1.0, LASER, 1),
     (5, -1.0, GENERIC, 5), (10**9, 1.0, GENERIC, MOST_RAYS), (5, math.nan, GENERIC, 1)],
)  # fmt: skip
def test_the_fields_are_corrected_as_webots_corrects_them(
    count: int, aperture: float, kind: int, expected: int
) -> None:
    assert len(DistanceRays.of(count, aperture, kind=kind)) == expected


def test_a_gaussian_too_narrow_for_every_ray_weighs_the_nearest_rays_alike() -> None:
    # exp(-(0.5 / 1e-300)^2) is 0 for both rays of a pair: the weights stay finite.
    assert DistanceRays.of(2, 1.0, gaussian_width=1e-300).weights == pytest.approx([0.5, 0.5])
    assert DistanceRays.of(4, 1.0, gaussian_width=1e-300).weights == pytest.approx([1, 0, 0, 0])


def test_a_negative_aperture_lays_the_rays_as_its_opposite_does() -> None:
    assert DistanceRays.of(5, -1.0).directions == pytest.approx(DistanceRays.of(5, 1.0).directions)


def _hits(distances: list[float], factors: list[float], incidences: list[float]) -> RayHits:
    return RayHits(np.array(distances), np.array(factors), np.array(incidences))


def test_each_type_makes_one_distance_of_its_rays_as_webots_does() -> None:
    rays = DistanceRays.of(2, 1.0)  # weights 0.5 and 0.5
    hits = _hits([0.04, math.inf], [0.2, math.nan], [1.0, 0.0])
    # Generic: a ray that meets nothing counts the reach.
    assert sensor_distance(GENERIC, rays, hits, 0.1) == pytest.approx(0.07)
    # Infra-red: the mean over the mean factor, 0.07 / (0.5 * 0.2 + 0.5 * 1).
    assert sensor_distance(INFRA_RED, rays, hits, 0.1) == pytest.approx(0.07 / 0.6)
    assert sensor_distance(INFRA_RED, rays, hits, 0.1, 0.5) == pytest.approx(
        0.07 + (0.07 / 0.6 - 0.07) * 0.5
    )
    # Sonar: the nearest ray heard back; a surface met 30 degrees off its normal is not.
    assert sensor_distance(SONAR, rays, hits, 0.1) == pytest.approx(0.04)
    oblique = _hits([0.04, 0.06], [1.0, 1.0], [math.cos(0.52), math.cos(0.2)])
    assert sensor_distance(SONAR, rays, oblique, 0.1) == pytest.approx(0.06)
    unheard = _hits([0.04, 0.06], [1.0, 1.0], [math.cos(0.52), math.cos(0.52)])
    assert sensor_distance(SONAR, rays, unheard, 0.1) == 0.1
    # A hit beyond the reach is no hit.
    assert sensor_distance(GENERIC, rays, _hits([0.2, 0.3], [1, 1], [1, 1]), 0.1) == 0.1


@pytest.mark.parametrize(
    ("text", "expected"),
    [("generic", GENERIC), ("Generic", GENERIC), ("infra-red", INFRA_RED),
     ("INFRARED", INFRA_RED), ("laser", LASER), ("sonar", SONAR), ("ultrasonic", SONAR)],
)  # fmt: skip
def test_a_type_is_read_as_webots_reads_it_anything_unknown_a_sonar(
    text: str, expected: int
) -> None:
    assert sensor_type(text) == expected


def _eye(name: str, rays: int, *, rotation: str = "0 0 1 0", kind: str = "generic") -> str:
    """A sensor 5 cm above the floor (0.0497 m above the slot), facing ahead."""
    return (
        f'DistanceSensor {{ translation 0 0 0.0497 rotation {rotation} name "{name}" '
        f'type "{kind}" {TABLE} numberOfRays {rays} aperture 1 }}\n'
    )


#: A white wall whose face is 4 cm ahead of the sensors (x = 0.07), 0.3 m tall.
WALL = (
    "Solid { translation 0.12 0 0.15 children [ DEF W Shape {\n"
    "  appearance PBRAppearance { baseColor 1 1 1 roughness 0 metalness 0 }\n"
    "  geometry Box { size 0.1 0.6 0.3 } } ] boundingObject USE W }\n"
)


@pytest.mark.usefixtures("fresh_robot")
def test_the_lower_of_two_rays_reads_the_floor_where_one_ray_reads_nothing(
    tmp_path: Path,
) -> None:
    sensors = _eye("two", 2) + _eye("one", 1) + _eye("rolled", 2, rotation="1 0 0 1.5708")
    two, one, rolled = slot_readings(tmp_path, sensors, ["two", "one", "rolled"])
    # The lower ray meets the floor 0.05 / sin(0.5) away, the upper one nothing (its 0.15 m).
    floor = 0.05 / math.sin(0.5)
    assert two == pytest.approx((0.5 * floor + 0.5 * 0.15) / 0.15 * 1000, abs=0.5)
    assert one == pytest.approx(1000.0)
    # Rolled a quarter turn about its axis, the two rays spread left and right, level.
    assert rolled == pytest.approx(1000.0)


@pytest.mark.usefixtures("fresh_robot")
def test_both_rays_meet_a_wall_nearer_than_the_floor(tmp_path: Path) -> None:
    (two,) = slot_readings(tmp_path, _eye("two", 2), ["two"], scenery=WALL)
    assert two == pytest.approx(0.04 / math.cos(0.5) / 0.15 * 1000, abs=0.5)


def _slanted_wall(turn_deg: float) -> str:
    """A wall whose face, 4 cm ahead of the sensors on their axis, is turned ``turn_deg``
    degrees from facing them."""
    turn = math.radians(turn_deg)
    # The face's centre at (0.07, 0); the box's centre half its thickness behind the face.
    x, y = 0.07 + 0.05 * math.cos(turn), 0.05 * math.sin(turn)
    return (
        f"Solid {{ translation {x!r} {y!r} 0.15 rotation 0 0 1 {turn!r} children [ DEF W Shape {{\n"
        "  appearance PBRAppearance { baseColor 1 1 1 roughness 0 metalness 0 }\n"
        "  geometry Box { size 0.1 0.6 0.3 } } ] boundingObject USE W }\n"
    )


@pytest.mark.usefixtures("fresh_robot")
@pytest.mark.parametrize(("turn", "heard"), [(15.0, True), (30.0, False)])
def test_a_sonar_does_not_hear_a_wall_met_more_than_22_5_degrees_off_its_normal(
    tmp_path: Path, turn: float, heard: bool
) -> None:
    level = 'translation 0 0 0.0197 name "{}" type "{}" ' + TABLE
    sensors = "".join(
        f"DistanceSensor {{ {level.format(name, kind)} }}\n" for name, kind in
        (("sonar", "sonar"), ("generic", "generic"))
    )  # fmt: skip
    sonar, generic = slot_readings(
        tmp_path, sensors, ["sonar", "generic"], scenery=_slanted_wall(turn)
    )
    assert generic == pytest.approx(0.04 / 0.15 * 1000, abs=0.5)
    assert sonar == (pytest.approx(generic) if heard else 1000.0)


def test_an_e_puck_s_rays_of_several_per_sensor_are_said_to_be_cast_once() -> None:
    text = (
        "#VRML_SIM R2025a utf8\nWorldInfo { }\n"
        'E-puck { controller "x" distance_sensor_numberOfRays 3 }\n'
    )
    (warning,) = own_sensors("e-puck", read_scene(text)).warnings
    assert warning.startswith("DistanceSensor 'ps0', 'ps1'")
    assert "casts 3 rays in Webots (numberOfRays 3" in warning
    assert "mazesim casts one" in warning
    plain = '#VRML_SIM R2025a utf8\nWorldInfo { }\nE-puck { controller "x" }\n'
    assert own_sensors("e-puck", read_scene(plain)).warnings == []


def _box(face_x: float, height: float) -> str:
    """A white box 0.1 m deep and 0.6 m wide whose face is at x = ``face_x`` (in front of the
    sensors), ``height`` tall, standing on the floor."""
    return (
        f"Solid {{ translation {face_x + 0.05!r} 0 {height / 2!r} children [ DEF B Shape {{\n"
        "  appearance PBRAppearance { baseColor 1 1 1 roughness 0 metalness 0 }\n"
        f"  geometry Box {{ size 0.1 0.6 {height!r} }} }} ] boundingObject USE B }}\n"
    )


@pytest.mark.usefixtures("fresh_robot")
def test_the_upper_ray_passes_over_a_wall_lower_than_it_where_it_crosses_it(
    tmp_path: Path,
) -> None:
    # The face 4 cm ahead: the upper ray crosses it 0.05 + 0.04 tan(0.5) = 7.2 cm up, over a
    # 6 cm wall (and meets nothing within its reach), the lower one 2.8 cm up, on its side.
    (low,) = slot_readings(tmp_path, _eye("two", 2), ["two"], scenery=_box(0.07, 0.06))
    side = 0.04 / math.cos(0.5)
    assert low == pytest.approx((0.5 * side + 0.5 * 0.15) / 0.15 * 1000, abs=0.5)


@pytest.mark.usefixtures("fresh_robot")
@pytest.mark.parametrize(("height", "expected"), [(0.05, 1000.0), (0.3, 0.04 / 0.15 * 1000)])
def test_a_level_ray_above_a_low_box_passes_over_it(
    tmp_path: Path, height: float, expected: float
) -> None:
    # A level sensor 10 cm up: a 5 cm box 4 cm ahead is under its ray, a 30 cm one in its way.
    sensor = f'DistanceSensor {{ translation 0 0 0.0997 name "high" {TABLE} }}'
    (read,) = slot_readings(tmp_path, sensor, ["high"], scenery=_box(0.07, height))
    assert read == pytest.approx(expected, abs=0.5)


@pytest.mark.usefixtures("fresh_robot")
def test_a_falling_ray_meets_a_wall_s_top_and_a_sonar_does_not_hear_it(tmp_path: Path) -> None:
    # 10 cm up, tilted 0.5 rad down: over the face 2 cm ahead (8.9 cm up there) of an 8 cm
    # box, onto its top (0.02 m down) 0.02 / tan(0.5) = 3.66 cm across the floor; a sonar
    # meets the top 61 degrees off its normal and hears nothing.
    sensors = "".join(
        f'DistanceSensor {{ translation 0 0 0.0997 rotation 0 1 0 0.5 name "{kind}" '
        f'type "{kind}" {TABLE} }}\n'
        for kind in ("generic", "sonar")
    )
    generic, sonar = slot_readings(
        tmp_path, sensors, ["generic", "sonar"], scenery=_box(0.05, 0.08)
    )
    assert generic == pytest.approx(0.02 / math.sin(0.5) / 0.15 * 1000, abs=0.5)
    assert sonar == 1000.0


@pytest.mark.usefixtures("fresh_robot")
@pytest.mark.parametrize(("height", "seen"), [(0.05, False), (0.3, True)])
def test_a_lidar_and_a_range_finder_pass_over_a_box_lower_than_them(
    tmp_path: Path, height: float, seen: bool
) -> None:
    # A one-layer lidar and a range finder 11 cm up, level, in the slot (3 cm ahead): a box
    # whose face is 4 cm ahead of them is in their way when it is 30 cm tall, under them at 5.
    devices = (
        'Lidar { translation 0 0 0.1097 name "lidar" horizontalResolution 3 fieldOfView 0.1 '
        "numberOfLayers 1 maxRange 1 }\n"
        'RangeFinder { translation 0 0 0.1097 name "depth" width 3 height 1 fieldOfView 0.1 '
        "maxRange 1 }\n"
    )
    robot = supervisor_in(
        tmp_path,
        "#VRML_SIM R2025a utf8\nWorldInfo { basicTimeStep 16 }\nRectangleArena { floorSize 2 2 }\n"
        + _box(0.07, height)
        + f'E-puck {{ supervisor TRUE controller "<extern>" groundSensorsSlot [ {devices} ] }}\n',
    )
    lidar, depth = robot.getDevice("lidar"), robot.getDevice("depth")
    lidar.enable(16)
    depth.enable(16)
    robot.step(16)
    middle = lidar.getRangeImage()[1]
    ahead = depth.getRangeImage()[1]
    if seen:
        assert middle == pytest.approx(0.04, abs=1e-3) and ahead == pytest.approx(0.04, abs=1e-3)
    else:
        # Over the box, the arena's 10 cm wall (0.97 m ahead) is under the rays too.
        assert middle == math.inf and ahead == math.inf
