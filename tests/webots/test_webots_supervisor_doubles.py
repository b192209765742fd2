"""A supervisor reads poses in double precision, as Webots' supervisor functions return them:
a robot, another robot and a movable body the file or a supervisor put at 0.1 read 0.1, not
0.10000000149011612 (float32's 0.1), while the simulation holds them there; once they move,
the simulation's pose (#32)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from mazesim.webots.lockstep import run_world
from mazesim.webots.solids import as_given
from supervised_world import project_of, supervisor_in

pytestmark = pytest.mark.usefixtures("fresh_robot")

#: An e-puck supervisor at (0.1, 0.2) turned 0.3 rad, a movable box at (0.7, -0.3): numbers
#: float32 rounds (0.1 -> 0.10000000149011612).
WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 2 2 }
DEF BOX Solid {
  translation 0.7 -0.3 0.02
  children [ Shape { geometry DEF BOX_SHAPE Box { size 0.04 0.04 0.04 } } ]
  name "box"
  boundingObject USE BOX_SHAPE
  physics Physics { density -1 mass 0.05 }
}
DEF EPUCK E-puck {
  translation 0.1 0.2 0
  rotation 0 0 1 0.3
  supervisor TRUE
  controller "<extern>"
}
"""


def test_float32_would_round_the_numbers_these_tests_read() -> None:
    for value in (0.1, 0.2, 0.3, 0.7, 0.123456789):
        assert float(np.float32(value)) != value


def test_a_robot_and_a_body_read_the_doubles_the_file_gives_until_they_move(
    tmp_path: Path,
) -> None:
    supervisor = supervisor_in(tmp_path, WORLD)
    robot, box = supervisor.getFromDef("EPUCK"), supervisor.getFromDef("BOX")
    for _ in range(2):  # before the first step and after one at rest
        assert robot.getPosition() == [0.1, 0.2, 0.0]
        assert robot.getField("translation").getSFVec3f() == [0.1, 0.2, 0.0]
        assert robot.getField("rotation").getSFRotation() == [0.0, 0.0, 1.0, 0.3]
        assert robot.getOrientation()[0] == math.cos(0.3)
        assert box.getPosition()[:2] == [0.7, -0.3]
        supervisor.step(32)
    # A supervisor's move reads back as given.
    robot.getField("translation").setSFVec3f([0.123456789, -0.4, 0.0])
    supervisor.step(32)
    assert robot.getPosition()[:2] == [0.123456789, -0.4]
    box.getField("translation").setSFVec3f([-0.5, 0.1, 0.02])
    supervisor.step(32)
    assert box.getPosition()[:2] == [-0.5, 0.1]
    # Driven away, the robot reads the simulation's pose.
    for name in ("left wheel motor", "right wheel motor"):
        supervisor.getDevice(name).setPosition(math.inf)
        supervisor.getDevice(name).setVelocity(3.0)
    supervisor.step(32)
    x, y, _ = robot.getPosition()
    assert x > 0.123456789 + 1e-4 and (x, y) == pytest.approx((0.1246, -0.4), abs=2e-3)


def test_a_pose_reads_as_given_only_within_float32_s_rounding() -> None:
    single = tuple(float(np.float32(v)) for v in (0.1, 0.2, 0.3))
    assert as_given(single, None, (0.1, 0.2, 0.3)) == (0.1, 0.2, 0.3)
    # A yaw a whole turn away is the same yaw.
    assert as_given(single, (0.1, 0.2, 0.3 + math.tau)) == (0.1, 0.2, 0.3 + math.tau)
    moved = (single[0] + 1e-6, single[1], single[2])
    assert as_given(moved, (0.1, 0.2, 0.3)) == moved


#: Two e-pucks: a supervisor at the origin that notes where the other is, and the other,
#: idle at (0.3, -0.2) turned 0.7 rad, until it is moved to x = 0.123456789.
FLEET_WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 2 2 }
DEF WATCHER E-puck { name "watcher" supervisor TRUE controller "watcher" }
DEF OTHER E-puck {
  translation 0.3 -0.2 0
  rotation 0 0 1 0.7
  name "other"
  controller "idle"
}
"""
IDLE = "from controller import Robot\nrobot = Robot()\nwhile robot.step(32) != -1:\n    pass\n"
WATCHER = """import json
import sys
from controller import Supervisor

robot = Supervisor()
other = robot.getFromDef("OTHER")
seen = []
robot.step(32)
seen.append(other.getPosition()[:2] + [other.getField("rotation").getSFRotation()[3]])
other.getField("translation").setSFVec3f([0.123456789, -0.2, 0.0])
robot.step(32)
robot.step(32)
seen.append(other.getPosition()[:2])
with open(sys.argv[1] if len(sys.argv) > 1 else "seen.json", "w") as out:
    json.dump(seen, out)
"""


def test_another_robot_of_a_world_run_reads_the_doubles_it_was_given(tmp_path: Path) -> None:
    world = project_of(tmp_path, "fleet.wbt", FLEET_WORLD, {"idle": IDLE, "watcher": WATCHER})
    watcher, other = run_world(str(world), seconds=0.2, noise=False).robots
    assert watcher.exit_status == 0, watcher.error
    seen = json.loads((tmp_path / "controllers" / "watcher" / "seen.json").read_text())
    assert seen == [[0.3, -0.2, 0.7], [0.123456789, -0.2]]
