"""The text a supervisor's ``worldSave`` writes: a node's fields set where its type is (#33)."""

from __future__ import annotations

from mazesim.webots.world_save import with_fields

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
