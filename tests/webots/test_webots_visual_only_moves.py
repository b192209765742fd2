"""A visual-only Solid (no ``boundingObject``: nothing collides with it, but the infra-red
sensors and the camera see it) that a supervisor moves is seen where it was moved, as a wall
with a ``boundingObject`` is: a pedestrian or a target that a supervisor walks across the
world (#32)."""

from __future__ import annotations

import inspect
from pathlib import Path

from mazesim.webots.lockstep import run_world
from supervised_world import colour_share, project_of, supervisor_in

#: A red visual-only box 0.1 m tall far from an e-puck "watcher" facing +x; a second robot.
WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 2 2 }
DEF PED Solid {
  translation 0.6 0.6 0.05
  children [
    Shape { appearance PBRAppearance { baseColor 1 0 0 } geometry Box { size 0.1 0.3 0.1 } }
  ]
  name "pedestrian"
}
E-puck { translation 0 0 0 name "watcher" controller "WATCHER" supervisor TRUE }
E-puck { translation -0.6 -0.6 0 name "mover" controller "MOVER" supervisor TRUE }
"""

#: Moves the pedestrian 0.1 m ahead of the watcher, its near face 5 cm from its centre.
AHEAD = 'robot.getFromDef("PED").getField("translation").setSFVec3f([0.1, 0, 0.05])'

#: Records, at each step, ps0 and the share of the watcher's image in the box's red (with the
#: tests' own :func:`colour_share`, written into the controller).
WATCHER = f"""from typing import Any

from controller import Supervisor

{inspect.getsource(colour_share)}

robot = Supervisor()
camera, ps0 = robot.getDevice("camera"), robot.getDevice("ps0")
for device in (camera, ps0):
    device.enable(32)
with open(OUT, "w") as out:
    for _ in range(12):
        robot.step(32)
        out.write(f"{{ps0.getValue()}} {{colour_share(camera, (204, 0, 0))}}\\n")
"""

MOVER = f"""from controller import Supervisor

robot = Supervisor()
for _ in range(4):
    robot.step(32)
{AHEAD}
for _ in range(10):
    robot.step(32)
"""


def _readings(path: Path) -> list[tuple[float, float]]:
    values = path.read_text().split()
    return [(float(a), float(b)) for a, b in zip(values[::2], values[1::2])]


def test_a_world_run_sees_a_visual_only_solid_where_another_robots_supervisor_moved_it(
    tmp_path: Path,
) -> None:
    out = tmp_path / "readings.txt"
    text = WORLD.replace("WATCHER", "watcher").replace("MOVER", "mover")
    watcher = WATCHER.replace("OUT", repr(str(out)))
    world = project_of(tmp_path, "ped.wbt", text, {"watcher": watcher, "mover": MOVER})
    run = run_world(str(world), seconds=1.0, seed=1)
    assert [robot.exit_status for robot in run.robots] == [0, 0], run.robots
    readings = _readings(out)
    assert len(readings) == 12
    # Far away: ps0 reads its noise floor (about 70) and no red is seen; 0.1 m ahead, ps0
    # reads its face 2 cm away and the box fills the middle of the image.
    assert all(ps0 < 120 and red == 0.0 for ps0, red in readings[:4]), readings
    assert all(ps0 > 250 and red > 0.2 for ps0, red in readings[6:]), readings


def test_a_controller_run_sees_a_visual_only_solid_where_its_supervisor_moved_it(
    tmp_path: Path,
) -> None:
    # The watcher alone, driven from here: it moves the pedestrian itself.
    alone = WORLD.replace('controller "WATCHER"', 'controller "<extern>"')
    robot = supervisor_in(tmp_path, alone.split("E-puck { translation -0.6")[0])
    ps0, camera = robot.getDevice("ps0"), robot.getDevice("camera")
    ps0.enable(32)
    camera.enable(32)
    red = (round(255 * 0.8), 0, 0)
    robot.step(32)
    assert ps0.getValue() < 120 and colour_share(camera, red) == 0.0
    exec(AHEAD, {"robot": robot})
    for _ in range(2):
        robot.step(32)
    assert ps0.getValue() > 250 and colour_share(camera, red) > 0.2


def test_a_camera_recognises_a_visual_only_solid_where_a_supervisor_moved_it(
    tmp_path: Path,
) -> None:
    text = (
        "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\n"
        'E-puck {\n  controller "<extern>"\n  supervisor TRUE\n  turretSlot [\n'
        '    Camera { translation 0.0395 0 -0.0206 name "rec" width 52 height 39 '
        "fieldOfView 0.84 recognition Recognition { } }\n  ]\n}\n"
        'DEF PED Solid { translation 0.6 0.6 0.05 name "ped" model "pedestrian" '
        "recognitionColors [ 1 0 0 ] children [ Shape { geometry Box { size 0.05 0.05 0.1 } } ] }\n"
    )
    robot = supervisor_in(tmp_path, text)
    camera = robot.getDevice("rec")
    camera.enable(32)
    camera.recognitionEnable(32)
    robot.step(32)
    assert camera.getRecognitionObjects() == []  # out of the field of view
    robot.getFromDef("PED").getField("translation").setSFVec3f([0.3, 0, 0.05])
    robot.step(32)
    robot.step(32)
    seen = camera.getRecognitionObjects()
    assert [o.getModel() for o in seen] == ["pedestrian"]
    # Where it was put: 0.3 m ahead of the robot's centre, about 0.27 m ahead of its camera.
    assert abs(seen[0].getPosition()[0] - 0.27) < 0.01 and abs(seen[0].getPosition()[1]) < 0.01
