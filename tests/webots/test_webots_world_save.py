"""The text a supervisor's ``worldSave`` writes: a node's fields set where its type is, its
numbers as a person writes them and only the fields set (#33)."""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

import pytest

from mazesim.webots.lockstep import run_world
from mazesim.webots.world_save import with_fields
from supervised_world import project_of

WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
DEF ONE E-puck {
  translation 0 0
    0
  name "a { b"  # a string and a comment { that hold braces
  turretSlot [ Solid { translation 1 2 3 } ]
}
E-puck { name "two" }
"""


def test_a_node_s_fields_are_replaced_number_by_number_keeping_every_line() -> None:
    saved = with_fields(WORLD, 3, {"translation": [0.25, -1.5, 0.0], "rotation": [0, 0, 1, 2]})
    lines = saved.split("\n")
    assert len(lines) == len(WORLD.split("\n"))
    assert lines[2] == "DEF ONE E-puck { rotation 0 0 1 2"
    assert lines[3:5] == ["  translation 0.25 -1.5", "    0"]
    # The Solid inside a field of the node keeps its own translation.
    assert lines[6] == "  turretSlot [ Solid { translation 1 2 3 } ]"


def test_a_node_on_one_line_and_a_line_without_a_node() -> None:
    saved = with_fields(WORLD, 9, {"translation": [1.0, 2.0, 0.5]})
    assert saved.split("\n")[8] == 'E-puck { translation 1 2 0.5 name "two" }'
    assert with_fields(WORLD, 0, {"translation": [1.0, 2.0, 0.5]}) == WORLD
    assert with_fields(WORLD, 99, {"translation": [1.0, 2.0, 0.5]}) == WORLD


#: A supervisor, an e-puck and another e-puck that write neither translation nor rotation
#: (the second writes its translation), and a wall that writes no rotation.
UNPOSED = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
Robot { name "boss" controller "saver" supervisor TRUE }
DEF ROVER E-puck { name "rover" controller "<none>" }
DEF STILL E-puck { translation 0.5 0.5 0 name "still" controller "<none>" }
Solid {
  translation 0.3 0 0.05
  children [ Shape { geometry DEF WALL Box { size 0.02 0.3 0.1 } } ]
  boundingObject USE WALL
}
"""

#: Saves the world, turns the rover a half turn at (0.3, 0.2), saves it again and notes the
#: angle its rotation field reads back.
SAVER = """import json
import math
import os

from controller import Supervisor

boss = Supervisor()
step = int(boss.getBasicTimeStep())
boss.step(step)
assert boss.worldSave("first.wbt")
rover = boss.getFromDef("ROVER")
rover.getField("translation").setSFVec3f([0.3, 0.2, 0.0])
rover.getField("rotation").setSFRotation([0.0, 0.0, 1.0, math.pi])
boss.step(step)
angle = rover.getField("rotation").getSFRotation()[3]
assert boss.worldSave("second.wbt")
os.mkdir("folder.wbt")
with open("angle.json", "w") as out:
    json.dump([angle, boss.worldSave("folder.wbt")], out)
"""


def test_a_saved_world_writes_numbers_as_a_person_would_and_only_fields_set(
    tmp_path: Path,
) -> None:
    world = project_of(tmp_path, "unposed.wbt", UNPOSED, {"saver": SAVER})
    folder = tmp_path / "controllers" / "saver"
    # A save is an atomic write: the temporary a killed save left is removed by the next.
    # (Its writer's pid is past Linux's largest, 2**22: no process runs by it.)
    orphan = folder / f".first.wbt.{2**22 + 1}-0123abcd.tmp"
    orphan.write_text("half")
    robots = run_world(str(world), seconds=0.2, noise=False).robots
    assert [r.exit_status for r in robots] == [0, 0, 0], [r.error for r in robots]
    assert not orphan.exists()
    # Nothing moved yet: the saved world reads as the file, no default field added.
    assert (folder / "first.wbt").read_text() == UNPOSED
    # The rover's fields as set, in the shortest text of their single-precision values, and
    # the half turn as pi, not -pi.
    angle, into_a_folder = json.loads((folder / "angle.json").read_text())
    assert angle == pytest.approx(math.pi)
    assert into_a_folder is False
    assert not [name for name in os.listdir(folder) if name.endswith(".tmp")]
    lines = (folder / "second.wbt").read_text().split("\n")
    assert lines[3] == (
        'DEF ROVER E-puck { translation 0.3 0.2 0 rotation 0 0 1 3.1415927 name "rover" '
        'controller "<none>" }'
    )
    assert lines[4:] == UNPOSED.split("\n")[4:]
