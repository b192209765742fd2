"""Every setter of a Webots ``Field`` (and ``Node.setVelocity``) checks its value's shape and
kind by one check (``mazesim.webots.field.field_value``, #35): more numbers than the field holds,
another kind of value, or a number that is not finite is refused with a ``MazesimError`` naming
the call, where it was dropped or put into the world (``setSFVec3f`` of 4 values silently lost
the fourth)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import pytest

from mazesim.errors import InvalidArgumentError, WrongTypeError
from supervised_world import supervisor_in, supervisor_of

#: (node, field, setter, value, error, what the message says)
REFUSED = [
    (
        "EPUCK",
        "translation",
        "setSFVec3f",
        [0.1, 0.0, 0.0, 9.0],
        InvalidArgumentError,
        "Field.setSFVec3f(): expected a list of 3 numbers, found 4",
    ),
    (
        "GATE",
        "translation",
        "setSFVec3f",
        [math.nan, 0.0, 0.0],
        InvalidArgumentError,
        "Field.setSFVec3f(): expected finite numbers",
    ),
    ("EPUCK", "translation", "setSFVec3f", [1e300, 0.0, 0.0], InvalidArgumentError, "found 1e+300"),
    ("EPUCK", "translation", "setSFVec3f", "abc", WrongTypeError, "Field.setSFVec3f"),
    ("EPUCK", "translation", "setSFVec3f", ["a", "b", "c"], WrongTypeError, "Field.setSFVec3f"),
    (
        "EPUCK",
        "rotation",
        "setSFRotation",
        [0, 0, 1, 0.5, 7],
        InvalidArgumentError,
        "Field.setSFRotation(): expected a list of 4 numbers, found 5",
    ),
    ("EPUCK", "rotation", "setSFRotation", [0, 0, 1, math.inf], InvalidArgumentError, "found inf"),
    ("EPUCK", "customData", "setSFString", b"abc", WrongTypeError, "Field.setSFString"),
    ("EPUCK", "customData", "setSFString", 12, WrongTypeError, "Field.setSFString"),
]


@pytest.mark.parametrize(("node", "name", "setter", "value", "error", "says"), REFUSED)
def test_a_field_value_of_another_shape_or_kind_is_refused(
    tmp_path: Path, node: str, name: str, setter: str, value: Any, error: type, says: str
) -> None:
    supervisor = supervisor_of(tmp_path)
    supervisor.step(32)
    field = supervisor.getFromDef(node).getField(name)
    before = field.value
    with pytest.raises(error) as refused:
        getattr(field, setter)(value)
    assert says in str(refused.value)
    assert field.value == before, "a refused value changed nothing"


def test_the_value_property_checks_as_the_setters_do(tmp_path: Path) -> None:
    supervisor = supervisor_of(tmp_path)
    field = supervisor.getFromDef("EPUCK").getField("translation")
    with pytest.raises(InvalidArgumentError, match="expected a list of 3 numbers, found 4"):
        field.value = [0.1, 0.0, 0.0, 1.0]


def test_fewer_numbers_are_padded_with_zeros_as_webots_pads_them(tmp_path: Path) -> None:
    supervisor = supervisor_of(tmp_path)
    field = supervisor.getFromDef("GATE").getField("translation")
    field.setSFVec3f([0.2])
    assert field.getSFVec3f() == [0.2, 0.0, 0.0]
    field.setSFVec3f((0.1, 0.05, 0.05))
    assert field.getSFVec3f() == [0.1, 0.05, 0.05]


def test_a_velocity_of_seven_numbers_is_refused(tmp_path: Path) -> None:
    supervisor = supervisor_of(tmp_path)
    with pytest.raises(InvalidArgumentError, match=r"Node.setVelocity\(\): expected a list of 6"):
        supervisor.getFromDef("BOX").setVelocity([0.0] * 7)


def test_an_appearance_field_the_file_leaves_out_is_read_and_set_at_its_default(
    tmp_path: Path,
) -> None:
    # A supervisor fades a point it ate: the PBRAppearance writes its colour, not its
    # transparency, which Webots gives at its default 0 (a float, written or not).
    supervisor = supervisor_in(
        tmp_path,
        "#VRML_SIM R2023b utf8\n"
        "DEF POINTS Group { children [ Solid { translation 0.2 0 0 children [ Shape {\n"
        "  appearance PBRAppearance { baseColor 1 0.5 0 metalness 0 }\n"
        "  geometry Sphere { radius 0.01 } } ] } ] }\n"
        "DEF EPUCK E-puck { supervisor TRUE }\n",
    )
    point = supervisor.getFromDef("POINTS").getField("children").getMFNode(0)
    shape = point.getField("children").getMFNode(0)
    appearance = shape.getField("appearance").getSFNode()
    transparency = appearance.getField("transparency")
    assert transparency is not None and transparency.getSFFloat() == 0.0
    assert appearance.getField("metalness").getTypeName() == "SFFloat", "written as 0"
    transparency.setSFFloat(0.8)
    supervisor.step(32)
    assert transparency.getSFFloat() == pytest.approx(0.8)


def test_base_nodes_fields_are_found_at_their_defaults_and_of_their_own_types(
    tmp_path: Path,
) -> None:
    # An inverted-pendulum supervisor reads the position of a HingeJointParameters in an
    # E-puck's turretSlot (another robot's): no field there "existed" (a node in a slot had
    # none); a field the
    # file leaves out (axis, physics, locked) did not either; `position 1` was an SFInt32, so
    # setSFFloat(0.5) read back 0.
    supervisor = supervisor_in(
        tmp_path,
        "#VRML_SIM R2023b utf8\n"
        "DEF EPUCK E-puck { supervisor TRUE }\n"
        "E-puck { translation 0.3 0 0 turretSlot [ HingeJoint {\n"
        "  jointParameters DEF SLOTTED HingeJointParameters { position -0.05 }\n"
        "  endPoint DEF PEND Solid { translation 0 0 0.08 } } ] }\n"
        "Solid { translation -0.3 0 0 children [ HingeJoint {\n"
        "  jointParameters DEF TOP HingeJointParameters { position 1 } } ] }\n",
    )
    slotted = supervisor.getFromDef("SLOTTED").getField("position")
    assert slotted is not None and slotted.getSFFloat() == pytest.approx(-0.05)
    top = supervisor.getFromDef("TOP")
    position = top.getField("position")
    assert position.getTypeName() == "SFFloat"
    position.setSFFloat(0.5)
    assert position.getSFFloat() == pytest.approx(0.5)
    assert top.getField("axis").getSFVec3f() == [1.0, 0.0, 0.0]  # HingeJointParameters' default
    pend = supervisor.getFromDef("PEND")
    assert pend.getField("translation").getSFVec3f() == pytest.approx([0.0, 0.0, 0.08])
    assert pend.getField("physics").getSFNode() is None  # an SFNode left out: empty
    assert pend.getField("locked").getSFBool() is False
    assert pend.getField("name").getSFString() == "solid"


def test_a_field_of_three_numbers_other_than_translation_is_set_and_read_back(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # A T-maze supervisor puts its cue light far away (SpotLight.location.setSFVec3f): Webots
    # sets the field; mazesim said the SFVec3f field was of the wrong type and kept it.
    supervisor = supervisor_in(
        tmp_path,
        "#VRML_SIM R2023b utf8\n"
        "DEF CUE SpotLight { location 0.3 0.1 0.2 direction 0 0 -1 }\n"
        "DEF EPUCK E-puck { supervisor TRUE }\n",
    )
    location = supervisor.getFromDef("CUE").getField("location")
    assert location.getTypeName() == "SFVec3f"
    location.setSFVec3f([20.0, 0.0, 20.0])
    supervisor.step(32)
    assert location.getSFVec3f() == pytest.approx([20.0, 0.0, 20.0])
    assert location.value == pytest.approx([20.0, 0.0, 20.0])
    assert "called with a field of type" not in capsys.readouterr().err
