"""The E-puck's ground sensors module sits and faces where Webots' PROTOs put it, before R2022a
and since (#32).

Webots' E-puck.proto before R2022a (V8.5 to R2021b, Y-up) mounts its ``groundSensorsSlot`` in a
Transform 3 cm forward (``translation 0 0.0003 -0.03``, the robot facing -z) turned ``0 0 1
-1.57``; its E-puckGroundSensors.proto (R2019b) turns itself back by its default ``rotation 0
0 1 1.5708`` and holds gs0, gs1, gs2 at x = -0.01, 0, 0.01 (x to the robot's right: gs0 on
the left), 3 mm up, each turned ``0 0 1 -1.57`` so that its x axis points at the floor. Since
R2022a (Z-up) the slot is ``translation 0.03 0 0.0003``, unturned, and the module's default
rotation is ``0 0 1 0``. In both, gs0 is 1 cm left of the middle, gs2 1 cm right, 3 cm ahead of
the centre, looking down: a dark strip under the robot's front left darkens gs0 alone. A sensor
the slot holds tilted less far down meets the floor ahead of it, or a wall nearer than that.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from supervised_world import slot_readings, supervisor_in

pytestmark = pytest.mark.usefixtures("fresh_robot")

#: A black strip 2 cm x 3.5 cm on the floor under the robot's front left (ENU: x 0.02 to
#: 0.04, y 0.005 to 0.04), in each version's frame: Webots' converter maps NUE (x, y, z) to
#: ENU (-z, -x, y).
STRIPS = {
    "R2023b": "translation 0.03 0.0225 0.0005",
    "R2021a": "translation -0.0225 0.0005 -0.03",
}
SIZES = {"R2023b": "0.02 0.035 0.001", "R2021a": "0.035 0.001 0.02"}


def world(version: str) -> str:
    return (
        f"#VRML_SIM {version} utf8\n"
        "WorldInfo { basicTimeStep 32 }\n"
        "RectangleArena { floorSize 1 1 }\n"
        f"Transform {{ {STRIPS[version]} children [ Shape {{\n"
        "  appearance PBRAppearance { baseColor 0 0 0 roughness 1 metalness 0 }\n"
        f"  geometry Box {{ size {SIZES[version]} }} }} ] }}\n"
        'E-puck { supervisor TRUE controller "<extern>"\n'
        "  groundSensorsSlot [ E-puckGroundSensors { } ] }\n"
    )


@pytest.mark.parametrize("version", ["R2021a", "R2023b"])
def test_a_strip_under_the_front_left_darkens_gs0_alone(tmp_path: Path, version: str) -> None:
    robot = supervisor_in(tmp_path, world(version))
    sensors = [robot.getDevice(f"gs{i}") for i in range(3)]
    for sensor in sensors:
        sensor.enable(32)
    robot.step(32)
    left, middle, right = (sensor.getValue() for sensor in sensors)
    assert left < 0.7 * middle, (left, middle, right)
    assert right == pytest.approx(middle, rel=0.1), (left, middle, right)


def test_an_infra_red_sensor_in_the_slot_reads_the_floor_from_its_0_3_mm(tmp_path: Path) -> None:
    # Since R2022a the slot holds its nodes 0.3 mm above the floor: an infra-red sensor turned
    # to look straight down on white paint (reflection factor 1) reads 0.0003 m through the
    # default table (0.1 m: 1000), 3.0; one tilted 0.131 rad back from straight down, 0.3 mm
    # / sin(1.7017), 3.026 (Webots casts from the sensor's own height).
    sensors = (
        'DistanceSensor { rotation 0 1 0 1.5708 name "down" type "infra-red" }\n'
        'DistanceSensor { rotation 0 1 0 1.7017 name "tilted" type "infra-red" }'
    )
    down, tilted = slot_readings(tmp_path, sensors, ["down", "tilted"])
    assert down == pytest.approx(3.0, abs=0.01)
    assert tilted == pytest.approx(3.0 / math.sin(1.7017), abs=0.01)


#: What lies ahead of a sensor 1 cm up, tilted 15 degrees down at the slot's 3 cm ahead: its ray
#: meets the floor 0.01 / sin(0.2618) = 3.86 cm away, 3.73 cm ahead of it (x = 0.0673).
AHEAD = {
    "white floor": ("", 386.4),
    # A black patch where the ray meets the floor: reflection factor 0.2, so 0.193 m, beyond
    # the default table's 0.1 m (1000).
    "black patch": (
        "Transform { translation 0.0673 0 0.0005 children [ Shape {\n"
        "  appearance PBRAppearance { baseColor 0 0 0 roughness 1 metalness 0 }\n"
        "  geometry Box { size 0.03 0.04 0.001 } } ] }\n",
        1000.0,
    ),
    # A white wall 2 cm ahead of the sensor, nearer than the floor: 0.02 / cos(0.2618).
    "wall": (
        "Solid { translation 0.055 0 0.025 children [ DEF B Shape {\n"
        "  appearance PBRAppearance { baseColor 1 1 1 roughness 0 metalness 0 }\n"
        "  geometry Box { size 0.01 0.2 0.05 } } ] boundingObject USE B }\n",
        207.06,
    ),
}


@pytest.mark.parametrize("case", sorted(AHEAD))
def test_a_sensor_tilted_a_little_down_reads_the_floor_ahead_or_a_nearer_wall(
    tmp_path: Path, case: str
) -> None:
    # A hand-made line sensor tilted 15 degrees down (less than the 45 at which a sensor reads
    # only the floor) meets the floor a few centimetres ahead, as Webots' 3D ray does: on white
    # it reads 386, on a black line 1000; a wall nearer than that point is what it meets.
    scenery, expected = AHEAD[case]
    sensor = (
        'DistanceSensor { translation 0 0 0.0097 rotation 0 1 0 0.2618 name "ir" type "infra-red" }'
    )
    (read,) = slot_readings(tmp_path, sensor, ["ir"], scenery=scenery)
    assert read == pytest.approx(expected, abs=0.5)


@pytest.mark.parametrize(("sensitivity", "expected"), [("", 15.0), ("redColorSensitivity 0", 3.0)])
def test_red_colour_sensitivity_sets_how_much_the_floor_s_colour_counts(
    tmp_path: Path, sensitivity: str, expected: float
) -> None:
    # Straight down 0.3 mm over black (factor 0.2): 0.0015 m through the default table (0.1 m:
    # 1000), 15; Webots' redColorSensitivity 0 reads the distance alone, 3.
    sensor = (
        f'DistanceSensor {{ rotation 0 1 0 1.5708 name "down" type "infra-red" {sensitivity} }}'
    )
    (read,) = slot_readings(tmp_path, sensor, ["down"], floor="0 0 0")
    assert read == pytest.approx(expected, abs=0.01)
