"""A supervisor reads a field a project PROTO's instance leaves out at the PROTO's default, as
Webots' ``wb_supervisor_node_get_field`` finds every field a PROTO declares: a RoboCup Rescue
(Erebus) supervisor reads each victim's ``type`` whether the world writes it or not, and it
found None for a victim left at its default ``harmed`` (an AttributeError stopped its run)."""

from __future__ import annotations

from pathlib import Path

import pytest

from mazesim.webots import expansions
from supervised_world import supervisor_in

#: A project PROTO of the Erebus kind: fields of each single-value type, a node and a list.
VICTIM = """#VRML_SIM R2023b utf8
PROTO Victim [
  field SFVec3f    translation 0 0 0
  field SFRotation rotation    0 0 1 0
  field SFString   name        "Victim"
  field SFString   type        "harmed"
  field SFInt32    scoreWorth  10
  field SFFloat    size        0.05
  field SFBool     found       FALSE
  field SFColor    tint        1 0.5 0
  field SFNode     marker      NULL
  field MFString   tags        ["a" "b"]
]
{
  Solid {
    translation IS translation
    rotation IS rotation
    name IS name
    children [ Shape { geometry Box { size 0.05 0.05 0.05 } } ]
  }
}
"""

WORLD = """#VRML_SIM R2023b utf8
EXTERNPROTO "Victim.proto"
WorldInfo { basicTimeStep 32 }
DEF HUMANS Group { children [
  Victim { translation 0.3 0 0 }
  Victim { translation -0.3 0 0 name "Victim1" type "stable" scoreWorth 5 found TRUE }
] }
DEF EPUCK E-puck { supervisor TRUE controller "<extern>" }
"""


def test_a_field_an_instance_leaves_out_is_read_at_its_proto_default(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (tmp_path / "Victim.proto").write_text(VICTIM)
    robot = supervisor_in(tmp_path, WORLD)
    humans = robot.getFromDef("HUMANS").getField("children")
    left_out, written = humans.getMFNode(0), humans.getMFNode(1)
    assert left_out.getField("type").getSFString() == "harmed"
    assert left_out.getField("scoreWorth").getSFInt32() == 10
    assert left_out.getField("size").getSFFloat() == pytest.approx(0.05)
    assert left_out.getField("found").getSFBool() is False
    assert left_out.getField("tint").getSFColor() == pytest.approx([1.0, 0.5, 0.0])
    assert left_out.getField("name").getSFString() == "Victim"
    assert left_out.getField("marker").getSFNode() is None
    # What the world writes wins, and the instance's pose is the file's.
    assert written.getField("type").getSFString() == "stable"
    assert written.getField("scoreWorth").getSFInt32() == 5
    assert written.getField("found").getSFBool() is True
    assert left_out.getField("translation").getSFVec3f() == pytest.approx([0.3, 0.0, 0.0])
    # A default is the instance's own: set on one, the other keeps its default.
    left_out.getField("type").setSFString("dead")
    assert left_out.getField("type").getSFString() == "dead"
    assert written.getField("type").getSFString() == "stable"
    capsys.readouterr()
    # A field the PROTO does not declare is still none, with Webots' message.
    assert left_out.getField("colour") is None
    assert "field 'colour' does not exist" in capsys.readouterr().err


def test_the_defaults_are_those_of_the_world_imported_last(tmp_path: Path) -> None:
    (tmp_path / "Victim.proto").write_text(VICTIM)
    supervisor_in(tmp_path, WORLD)
    assert expansions.interface_of("Victim") is not None
    # Another world, without the PROTO, leaves no default of the first behind.
    supervisor_in(
        tmp_path, WORLD.split("DEF HUMANS")[0].replace('EXTERNPROTO "Victim.proto"\n', "")
    )
    assert expansions.interface_of("Victim") is None
