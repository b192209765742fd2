"""A node a supervisor imports at the top of the scene whose name a sibling Solid has is
renamed as Webots renames it, ``NAME(N)`` with the first free index: three E-pucks imported
without a ``name`` beside the world's ``e-puck`` are ``e-puck(1)`` to ``e-puck(3)``, and their
controllers tell themselves apart by ``getName()`` (#33)."""

from __future__ import annotations

from pathlib import Path

import pytest

from mazesim.webots.lockstep import run_world
from mazesim.webots.name_clash import unique_names
from supervised_world import project_of

pytestmark = pytest.mark.usefixtures("fresh_robot")


def test_names_taken_get_the_first_free_index_and_others_stay() -> None:
    text = 'E-puck { } E-puck { name "e-puck" } Solid { } Robot { name "x(2)" } WoodenBox { }'
    renamed = unique_names(text, ["e-puck", "e-puck(2)", "solid", "x(2)", "other"])
    assert renamed == (
        'E-puck { name "e-puck(1)" } E-puck { name "e-puck(3)" } Solid { name "solid(1)" } '
        'Robot { name "x(1)" } WoodenBox { }'
    )
    assert unique_names('E-puck { name "a" }', ["b"]) == 'E-puck { name "a" }'
    assert unique_names("E-puck {", ["e-puck"]) == "E-puck {", "not nodes: the import says so"
    # A name's escapes are kept as written, not escaped again.
    assert unique_names('Solid { name "a\\"b" }', ['a\\"b']) == 'Solid { name "a\\"b(1)" }'
    assert unique_names("DEF X Solid{}", ["solid"]) == 'DEF X Solid{ name "solid(1)"}'


WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
E-puck { translation -0.3 0 0 controller "namer" }
Robot { name "spawner" controller "spawner" supervisor TRUE }
"""
SPAWNER = """from controller import Supervisor

boss = Supervisor()
children = boss.getRoot().getField("children")
for x in (0.0, 0.15, 0.3):
    children.importMFNodeFromString(-1, f'E-puck {{ translation {x} 0.3 0 controller "namer" }}')
while boss.step(32) != -1:
    pass
"""
NAMER = """from controller import Robot

robot = Robot()
print(f"named {robot.getName()}")
while robot.step(32) != -1:
    pass
"""


def test_imported_e_pucks_are_renamed_apart_and_know_their_names(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    world = project_of(tmp_path, "spawn.wbt", WORLD, {"spawner": SPAWNER, "namer": NAMER})
    run = run_world(str(world), seconds=0.2, noise=False)
    names = sorted(x for x in capfd.readouterr().out.splitlines() if x.startswith("named "))
    assert names == ["named e-puck", "named e-puck(1)", "named e-puck(2)", "named e-puck(3)"]
    assert [r.name for r in run.robots] == [
        "e-puck",
        "spawner",
        "e-puck(1)",
        "e-puck(2)",
        "e-puck(3)",
    ]
