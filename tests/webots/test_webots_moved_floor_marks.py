"""A floor mark that a supervisor moves (a thin black Solid lying on the floor, as a T-maze's
cue a genetic algorithm's supervisor places between trials) is read where it was moved: the
ground sensors and the camera see it there and no longer where it was, in a controller's run
and in a world run (#32)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from mazesim.webots.lockstep import run_world
from supervised_world import project_of, supervisor_in

#: A black sheet 2 mm thick and 30 cm square far from the e-puck "watcher" at (0, 0) facing +x,
#: with a bounding object (it is stood on) or without (visual only).
MARK = (
    "DEF MARK Solid {{ translation 0.6 0.6 0.001 children [ DEF SHEET Shape {{ appearance "
    "PBRAppearance {{ baseColor 0 0 0 roughness 1 }} geometry Box {{ size 0.3 0.3 0.002 }} }} "
    '] name "mark" {bounding} }}\n'
)


def _world(bounded: bool, mover: bool = False) -> str:
    return (
        "#VRML_SIM R2025a utf8\nWorldInfo { basicTimeStep 32 }\nRectangleArena { floorSize 3 3 }\n"
        + MARK.format(bounding="boundingObject USE SHEET" if bounded else "")
        + 'E-puck { translation 0 0 0 name "watcher" controller "WATCHER" supervisor TRUE '
        + "groundSensorsSlot [ E-puckGroundSensors { } ] }\n"
        + (
            'E-puck { translation -0.8 -0.8 0 name "mover" controller "mover" supervisor TRUE }\n'
            if mover
            else ""
        )
    )


def _bottom_middle(camera: Any) -> int:
    """The grey of the bottom row's middle pixel (the floor some 11 cm ahead)."""
    image: Any = camera.getImage()
    i = 4 * ((camera.getHeight() - 1) * camera.getWidth() + camera.getWidth() // 2)
    return sum(image[i : i + 3]) // 3


def _move(robot: Any, x: float, y: float) -> None:
    robot.getFromDef("MARK").getField("translation").setSFVec3f([x, y, 0.001])
    robot.step(32)
    robot.step(32)


@pytest.mark.parametrize("bounded", [False, True])
def test_a_moved_floor_mark_is_seen_and_read_where_it_was_put(
    tmp_path: Path, bounded: bool
) -> None:
    text = _world(bounded).replace('"WATCHER"', '"<extern>"')
    robot = supervisor_in(tmp_path, text)
    sensors = [robot.getDevice(f"gs{i}") for i in range(3)]
    camera = robot.getDevice("camera")
    for device in (*sensors, camera):
        device.enable(32)
    robot.step(32)
    bare = [s.getValue() for s in sensors]
    assert _bottom_middle(camera) > 200  # the white floor ahead
    _move(robot, 0.2, 0.0)  # ahead of the robot: the camera sees it, the sensors do not
    assert _bottom_middle(camera) < 60
    assert [s.getValue() for s in sensors] == pytest.approx(bare, rel=0.05)
    _move(robot, 0.0, 0.0)  # under the robot
    under = [s.getValue() for s in sensors]
    assert all(u < 0.6 * b for u, b in zip(under, bare)), (bare, under)
    _move(robot, -0.6, 0.6)  # away again
    assert [s.getValue() for s in sensors] == pytest.approx(bare, rel=0.05)
    assert _bottom_middle(camera) > 200


WATCHER = """from controller import Supervisor

robot = Supervisor()
sensors = [robot.getDevice(f"gs{i}") for i in range(3)]
for sensor in sensors:
    sensor.enable(32)
with open(OUT, "w") as out:
    for _ in range(10):
        robot.step(32)
        out.write(f"{min(s.getValue() for s in sensors)}\\n")
"""

MOVER = """from controller import Supervisor

robot = Supervisor()
for _ in range(4):
    robot.step(32)
robot.getFromDef("MARK").getField("translation").setSFVec3f([0, 0, 0.001])
for _ in range(8):
    robot.step(32)
"""


def test_a_world_run_reads_a_floor_mark_where_another_robots_supervisor_moved_it(
    tmp_path: Path,
) -> None:
    out = tmp_path / "ground.txt"
    text = _world(True, mover=True).replace('"WATCHER"', '"watcher"')
    watcher = WATCHER.replace("OUT", repr(str(out)))
    world = project_of(tmp_path, "marks.wbt", text, {"watcher": watcher, "mover": MOVER})
    run = run_world(str(world), seconds=0.5, seed=1)
    assert [robot.exit_status for robot in run.robots] == [0, 0], run.robots
    readings = [float(v) for v in out.read_text().split()]
    assert len(readings) == 10
    assert min(readings[:4]) > 1.6 * max(readings[6:]), readings
