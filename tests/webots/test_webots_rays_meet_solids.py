"""The rays of the devices a world adds meet what stands on the floor besides the walls (#32,
#33): a DistanceSensor, a Lidar or a RangeFinder meets the world's movable bodies where they
are now and the other robots of a world run, as Webots' rays meet every solid. Before, they met
the walls alone: a plain robot's distance sensor read nothing of an e-puck 6 cm ahead, and a
lidar saw through a box a supervisor had put in front of it.
"""

from __future__ import annotations

import json
import math
import os
import textwrap
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from mazesim._core import ROBOT_REFLECTANCE
from mazesim.webots.lockstep import run_world
from mazesim.webots.rays import WallBoxes
from mazesim.webots.walls_now import OtherRobots
from supervised_world import slot_readings, supervisor_in

pytestmark = pytest.mark.usefixtures("fresh_robot")

#: A generic table: 0 m reads 0, 0.2 m (the ray's reach) reads 1000.
TABLE = "lookupTable [ 0 0 0 0.2 1000 0 ]"
#: A slot sensor looking ahead, level, 0.3 mm up (the R2025a E-puck's groundSensorsSlot).
AHEAD = f'DistanceSensor {{ name "ahead" {TABLE} }}'
#: A box 4 cm wide and 5 cm tall with physics, its near side ``x - 0.02`` ahead of the
#: e-puck (whose slot is 3 cm ahead of its centre).
BOX = """Solid {{
  translation {x} 0 0.025
  children [ Shape {{ geometry DEF B Box {{ size 0.04 0.04 0.05 }} }} ]
  boundingObject USE B
  physics Physics {{ }}
}}
"""


def empty_walls() -> WallBoxes:
    return WallBoxes.of_boxes([])


def test_a_ray_meets_an_upright_cylinder_at_its_side_with_its_reflectance() -> None:
    walls = empty_walls().with_solids(
        np.zeros((0, 6)), np.zeros(0), np.array([[0.5, 0.0, 0.1, 0.38]]), np.array([0.05])
    )
    directions = np.array([[1.0, 0.0], [0.0, 1.0], [2.0, 0.0]])
    distance, wall = walls.cast_walls((0.0, 0.0), directions)
    assert distance[0] == pytest.approx(0.4)
    assert math.isinf(distance[1]) and wall[1] == -1
    assert distance[2] == pytest.approx(0.2), "a direction twice as long: half the parameter"
    assert walls.reflectances(wall)[0] == pytest.approx(0.38)
    # The side faces back along the ray where it is met head-on, out from the axis elsewhere.
    normals = walls.side_normals((0.0, 0.0), directions, distance, wall)
    assert normals[0] == pytest.approx([-1.0, 0.0])
    glancing = np.array([[math.cos(0.15), math.sin(0.15)]])
    d, w = walls.cast_walls((0.0, 0.0), glancing)
    (normal,) = walls.side_normals((0.0, 0.0), glancing, d, w)
    hit = d[0] * glancing[0]
    assert normal == pytest.approx((hit - [0.5, 0.0]) / 0.1)
    assert walls.nearest_distance((0.0, 0.0)) == pytest.approx(0.4)


def test_a_level_ray_passes_over_a_cylinder_lower_than_it_and_a_falling_one_meets_its_top() -> None:
    walls = empty_walls().with_solids(
        np.zeros((0, 6)), np.zeros(0), np.array([[0.5, 0.0, 0.1, 0.38]]), np.array([0.05])
    )
    ahead = np.array([[1.0, 0.0]])
    over, _, _ = walls.cast_sloped((0.0, 0.0), ahead, 0.06, np.array([0.0]))
    assert math.isinf(over[0])
    side, _, on_top = walls.cast_sloped((0.0, 0.0), ahead, 0.04, np.array([0.0]))
    assert side[0] == pytest.approx(0.4) and not on_top[0]
    # Falling 0.02 per metre from 6 cm: 5 cm up after 0.5 m, over the cylinder's middle.
    onto, _, on_top = walls.cast_sloped((0.0, 0.0), ahead, 0.06, np.array([-0.02]))
    assert onto[0] == pytest.approx(0.5) and on_top[0]


def test_boxes_and_cylinders_join_the_walls_after_them_and_keep_the_walls_as_they_were() -> None:
    walls = WallBoxes.of_boxes([(1.0, 0.0, 0.1, 1.0, 0.0, 0.9)])
    joined = walls.with_solids(
        np.array([[0.0, 1.0, 0.2, 0.2, 0.0, 0.5]]),
        np.array([0.1]),
        np.array([[-1.0, 0.0, 0.1, 0.38]]),
        np.array([0.05]),
    )
    directions = np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]])
    distance, wall = joined.cast_walls((0.0, 0.0), directions)
    assert distance == pytest.approx([0.95, 0.9, 0.9])
    assert list(wall) == [0, 1, 2], "the wall, the box, then the cylinder"
    assert joined.reflectances(wall) == pytest.approx([0.9, 0.5, 0.38])
    assert list(joined.top) == [math.inf, 0.1, 0.05]
    assert walls.center.shape == (1, 2) and walls.disc_radius.shape == (0,)
    assert walls.with_solids(np.zeros((0, 6)), [], np.zeros((0, 4)), []) is walls


def test_a_slot_sensor_reads_a_movable_box_ahead_of_it(tmp_path: Path) -> None:
    (clear,) = slot_readings(tmp_path, AHEAD, ["ahead"])
    (tmp_path / "b").mkdir()
    (boxed,) = slot_readings(tmp_path / "b", AHEAD, ["ahead"], scenery=BOX.format(x=0.15))
    assert clear == pytest.approx(1000.0), "nothing within 0.2 m ahead"
    # The box's near side 0.13 m from the robot's centre, 0.10 m from the slot's sensor.
    assert boxed == pytest.approx(1000.0 * 0.10 / 0.2, abs=1.0)


def test_a_lidar_sees_a_movable_box_ahead_of_it(tmp_path: Path) -> None:
    lidar = (
        'Lidar { name "lidar" horizontalResolution 9 numberOfLayers 1 fieldOfView 0.8 maxRange 1 }'
    )
    text_points = []
    for scenery, where in (("", tmp_path), (BOX.format(x=0.25), tmp_path / "b")):
        where.mkdir(exist_ok=True)
        robot = supervisor_in(
            where,
            "#VRML_SIM R2025a utf8\nWorldInfo { basicTimeStep 16 }\n"
            "RectangleArena { floorSize 2 2 }\n"
            f"{scenery}"
            f'E-puck {{ supervisor TRUE controller "<extern>" turretSlot [ {lidar} ] }}\n',
        )
        device = robot.getDevice("lidar")
        device.enable(16)
        robot.step(16)
        text_points.append(device.getRangeImage())
    clear, boxed = text_points
    middle = 4  # the ray straight ahead (the fourth of nine from the left, 0-based 4)
    assert clear[middle] > 0.9, "the arena's wall 1 m away, at the lidar's range"
    assert boxed[middle] == pytest.approx(0.23, abs=0.02), "the box's near side 0.23 m ahead"


WATCHER_CONTROLLER = textwrap.dedent(
    """
    import json, os
    from controller import Robot

    robot = Robot()
    sensor = robot.getDevice("eye")
    sensor.enable(32)
    robot.step(64)
    with open(os.environ["EYE_LOG"], "w") as out:
        json.dump(sensor.getValue(), out)
    """
)
#: A plain robot with a level infra-red distance sensor 3.5 cm up at its centre, looking
#: along +x.
WATCHER = f"""Robot {{
  name "watcher"
  controller "eye"
  children [ DistanceSensor {{ translation 0 0 0.035 name "eye" type "infra-red" {TABLE} }} ]
}}
"""


@pytest.mark.parametrize("ahead", [0.08, 0.1])
def test_in_a_world_run_a_plain_robots_sensor_reads_an_e_puck_ahead_of_it(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, ahead: float
) -> None:
    log = tmp_path / "eye.json"
    monkeypatch.setenv("EYE_LOG", str(log))
    (tmp_path / "worlds").mkdir()
    (tmp_path / "controllers" / "eye").mkdir(parents=True)
    (tmp_path / "controllers" / "eye" / "eye.py").write_text(WATCHER_CONTROLLER)
    world = tmp_path / "worlds" / "w.wbt"
    e_puck = f'E-puck {{ translation {ahead} 0 0 controller "<none>" }}\n'
    world.write_text(
        "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\n"
        "RectangleArena { floorSize 2 2 }\n" + e_puck + WATCHER
    )
    run = run_world(str(world), seconds=0.2, noise=False)
    assert [r.exit_status for r in run.robots if r.controller] == [0]
    # Infra-red: the distance over the shell's reflection factor (red sensitivity 1).
    distance = (ahead - 0.037) / ROBOT_REFLECTANCE
    expected = 1000.0 * min(distance, 0.2) / 0.2
    assert json.loads(log.read_text()) == pytest.approx(expected, rel=0.02)
    assert os.path.exists(log)


def looking_robot(tmp_path: Path, node: str, device: str, scenery: str = "") -> Any:
    """The device ``eye`` of the only robot of a world, a plain Robot of fields ``node``
    holding ``device`` among its children, beside ``scenery``, after one step with the device
    enabled."""
    text = (
        "#VRML_SIM R2025a utf8\nWorldInfo { basicTimeStep 16 }\n"
        "RectangleArena { floorSize 2 2 }\n"
        f"{scenery}"
        f'Robot {{ {node} controller "<extern>" supervisor TRUE children [ {device} ] }}\n'
    )
    robot = supervisor_in(tmp_path, text, robot="Robot {")
    found = robot.getDevice("eye")
    found.enable(16)
    robot.step(16)
    return found


@pytest.mark.parametrize(
    ("node", "floor"),
    [
        ("translation 0 0 0.1 rotation 0 1 0 1.5708", 0.1),
        ("translation 0 0 0.15 rotation 0 1 0 1.5708", 0.15),
        ("translation 0 0 0.05 rotation 0 1 0 0.7854", 0.05 * math.sqrt(2.0)),
    ],
)
def test_a_sensor_of_a_robot_mazesim_does_not_move_sits_where_its_node_puts_it(
    tmp_path: Path, node: str, floor: float
) -> None:
    # A Robot without physics stays where its node stands in Webots: turned a quarter turn
    # about y, its x axis (the sensor's) points down at the floor from its height; turned an
    # eighth, it meets the floor sqrt(2) times its height away.
    eye = looking_robot(tmp_path, node, f'DistanceSensor {{ name "eye" {TABLE} }}')
    assert eye.getValue() == pytest.approx(1000.0 * floor / 0.2, abs=1.0)


def test_a_lidar_of_a_raised_robot_passes_over_a_box_lower_than_it(tmp_path: Path) -> None:
    lidar = 'Lidar { name "eye" horizontalResolution 9 numberOfLayers 1 fieldOfView 0.8 }'
    readings = []
    for height in (0.02, 0.08):
        where = tmp_path / str(height)
        where.mkdir()
        eye = looking_robot(where, f"translation 0 0 {height}", lidar, BOX.format(x=0.25))
        readings.append(eye.getRangeImage()[4])
    low, high = readings
    assert low == pytest.approx(0.23, abs=0.02), "the 5 cm box's near side, 2 cm up"
    assert high > 0.9, "8 cm up, over the box to the arena's wall"


def test_in_a_world_run_a_sensor_above_an_e_pucks_body_reads_the_mast_it_carries(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # The e-puck's body stops at 4.75 cm; an infra-red sensor 8 cm up passes over it, but
    # meets a mast 2 cm wide on its turret, as the camera draws it; a generic one passes
    # through the mast, a visual shape (as it passes through a sensed-only wall).
    readings = []
    for mast, kind in (("", "infra-red"), (MAST, "infra-red"), (MAST, "generic")):
        where = tmp_path / str(len(readings))
        (where / "worlds").mkdir(parents=True)
        (where / "controllers" / "eye").mkdir(parents=True)
        (where / "controllers" / "eye" / "eye.py").write_text(WATCHER_CONTROLLER)
        log = where / "eye.json"
        monkeypatch.setenv("EYE_LOG", str(log))
        world = where / "worlds" / "w.wbt"
        e_puck = f'E-puck {{ translation 0.1 0 0 controller "<none>" turretSlot [ {mast} ] }}\n'
        world.write_text(
            "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\n"
            "RectangleArena { floorSize 2 2 }\n"
            + e_puck
            + WATCHER.replace("infra-red", kind).replace("0 0 0.035", "0 0 0.08")
        )
        run_world(str(world), seconds=0.2, noise=False)
        readings.append(json.loads(log.read_text()))
    bare, masted, through = readings
    assert bare == pytest.approx(1000.0), "over the body, nothing within 0.2 m"
    assert through == pytest.approx(1000.0), "a generic sensor: no visual shapes"
    # The turret slot stands 9.5 mm behind the e-puck's centre: the mast's near side is
    # 0.1 - 0.0095 - 0.01 m ahead.
    assert masted == pytest.approx(1000.0 * 0.0805 / 0.2, rel=0.02), "the mast's near side"


#: A mast 2 cm wide and 15 cm tall at the centre of an e-puck's turret.
MAST = "Solid { translation 0 0 0.075 children [ Shape { geometry Box { size 0.02 0.02 0.15 } } ] }"


@pytest.mark.parametrize(
    ("node", "expected"),
    [
        ("translation 0.2 0.1 0.3", [0.25, 0.1, 0.3]),
        ("translation 0.2 0.1 0.3 rotation 0 1 0 1.5708", [0.2, 0.1, 0.25]),
    ],
)
def test_a_gps_of_a_robot_mazesim_does_not_move_reads_where_its_node_puts_it(
    tmp_path: Path, node: str, expected: list[float]
) -> None:
    # 5 cm along the robot's x axis: ahead of a level robot, below one turned to look down.
    gps = looking_robot(tmp_path, node, 'GPS { name "eye" translation 0.05 0 0 }')
    assert gps.getValues() == pytest.approx(expected, abs=1e-4)


def test_the_devices_of_a_robot_share_one_question_a_step_for_the_other_robots() -> None:
    # Over a controller's pipe each question is a round trip: a robot's touch sensors, camera
    # and added sensors ask for the other robots' places once a step between them.
    asked = []

    class Shared:
        def other_robots(self) -> list[tuple[float, float, float]]:
            asked.append(1)
            return [(0.1, 0.2, 0.037)]

    class Simulation:
        simulator = Shared()
        fleet = None
        steps = 0

    simulation = Simulation()
    robots = OtherRobots.of(simulation)  # type: ignore[arg-type]
    assert OtherRobots.of(simulation) is robots  # type: ignore[arg-type]
    assert robots.now() == robots.now() == [(0.1, 0.2, 0.037)]
    assert len(asked) == 1
    simulation.steps = 1
    robots.now()
    assert len(asked) == 2
