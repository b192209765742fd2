"""The supervisor's scene tree below the root: the ``children`` of plain Solid, Transform, Pose
and Group nodes, read from the world file and read-only, and the refusal of calls that would
add nodes to the running world or remove them."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import mazesim
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots import supervisor as supervisor_module
from mazesim.webots.scene import read_scene

#: A world whose obstacles are grouped: a Group holding a Solid (holding a Pose and a Shape)
#: and a Transform holding a Solid.
GROUPED = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 1 1 }
DEF OBSTACLES Group {
  children [
    DEF BOX1 Solid {
      translation 0.3 0.2 0.05
      rotation 0 0 1 1.5708
      children [
        DEF MARK Pose {
          translation 0.1 0 0
          children [ Shape { geometry Box { size 0.01 0.01 0.01 } } ]
        }
        Shape { geometry DEF BOXGEOM Box { size 0.05 0.05 0.1 } }
      ]
      name "box one"
      boundingObject USE BOXGEOM
    }
    Transform { translation -0.3 0 0 children [ Solid { name "inner" } ] }
  ]
}
DEF EPUCK E-puck { translation -0.2 -0.1 0 supervisor TRUE }
"""


pytestmark = pytest.mark.usefixtures("fresh_robot")


def supervisor_of(text: str, tmp_path: Path) -> controller.Supervisor:
    """A supervisor of the robot of the world ``text``, as ``mazesim webots run`` prepares it."""
    path = tmp_path / "grouped.wbt"
    path.write_text(text)
    prepare(mazesim.load_world(str(path)), seconds=5.0, noise=False, scene=read_scene(text))
    controller.Robot.created = None
    return controller.Supervisor()


def test_grouping_nodes_list_their_children_as_the_file_gives_them(tmp_path: Path) -> None:
    supervisor = supervisor_of(GROUPED, tmp_path)
    top = supervisor.getRoot().getField("children")
    assert [top.getMFNode(i).getTypeName() for i in range(top.getCount())] == [
        "WorldInfo",
        "RectangleArena",
        "Group",
        "E-puck",
    ]
    group = top.getMFNode(2)
    inside = group.getField("children")
    assert inside is not None and inside.getTypeName() == "MFNode" and inside.getCount() == 2
    box, transform = inside.getMFNode(0), inside.getMFNode(-1)
    assert (box.getTypeName(), box.getDef()) == ("Solid", "BOX1")
    assert transform.getTypeName() == "Transform"
    assert box.getParentNode() is group and group.getParentNode() is supervisor.getRoot()
    assert box.getField("translation").getSFVec3f() == pytest.approx([0.3, 0.2, 0.05])
    assert box.getField("rotation").getSFRotation() == pytest.approx([0, 0, 1, 1.5708])
    assert box.getField("name").getSFString() == "box one"
    in_box = box.getField("children")
    assert [in_box.getMFNode(i).getTypeName() for i in range(in_box.getCount())] == [
        "Pose",
        "Shape",
    ]
    mark = in_box.getMFNode(0)
    assert mark.getDef() == "MARK" and mark.getParentNode() is box
    # The field is the file's, in the parent's frame; the position is the world's.
    assert mark.getField("translation").getSFVec3f() == pytest.approx([0.1, 0.0, 0.0])
    assert mark.getPosition() == pytest.approx([0.3, 0.3, 0.05], abs=1e-4)
    assert mark.getOrientation()[3] == pytest.approx(math.sin(1.5708), abs=1e-6)
    assert mark.getField("children").getMFNode(0).getTypeName() == "Shape"
    assert in_box.getMFNode(1).getField("translation") is None, "a Shape has no translation"
    inner = transform.getField("children").getMFNode(0)
    assert inner.getField("name").getSFString() == "inner"
    assert inner.getPosition() == pytest.approx([-0.3, 0.0, 0.0])
    assert in_box.getMFNode(2) is None
    # A node inside others is found by its DEF name and by its id.
    assert supervisor.getFromDef("MARK") is mark and supervisor.getFromDef("BOX1") is box
    ids = [n.getId() for n in (group, box, mark, transform, inner, supervisor.getSelf())]
    assert len(set(ids)) == len(ids)
    assert all(supervisor.getFromId(n.getId()) is n for n in (box, mark, inner))


def test_a_dotted_def_path_finds_a_node_inside_another(tmp_path: Path) -> None:
    # Webots' reference manual, wb_supervisor_node_get_from_def: dots are "a scoping operator
    # in the DEF parameter" ("ROBOT.JOINT.SOLID").
    supervisor = supervisor_of(GROUPED, tmp_path)
    mark = supervisor.getFromDef("OBSTACLES.BOX1.MARK")
    assert mark is not None and mark.getTypeName() == "Pose" and mark.getDef() == "MARK"
    assert mark == supervisor.getFromDef("MARK")
    assert supervisor.getFromDef("OBSTACLES.MARK") == mark, "any depth inside"
    assert supervisor.getFromDef("BOX1.OBSTACLES") is None, "the scope is inside the first"
    for missing in ("OBSTACLES.NOPE", "NOPE.BOX1", "OBSTACLES..BOX1", "OBSTACLES."):
        assert supervisor.getFromDef(missing) is None, missing


def test_world_info_and_the_e_puck_have_the_fields_webots_declares(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # Webots' reference manual, WorldInfo (basicTimeStep an SFFloat, whole or not), and
    # E-puck.proto's declared fields at their defaults where the file leaves them out.
    supervisor = supervisor_of(GROUPED, tmp_path)
    top = supervisor.getRoot().getField("children")
    info = top.getMFNode(0)
    assert info.getTypeName() == "WorldInfo"
    step = info.getField("basicTimeStep")
    assert step.getTypeName() == "SFFloat" and step.getSFFloat() == 32.0
    assert info.getField("FPS").getSFFloat() == 60.0
    assert info.getField("gravity").getTypeName() == "SFFloat"
    assert info.getField("randomSeed").getTypeName() == "SFInt32"
    assert info.getField("coordinateSystem").getSFString() == "ENU"
    puck = supervisor.getFromDef("EPUCK")
    assert puck.getField("camera_rotation").getSFRotation() == [0.0, 0.0, 1.0, 0.0]
    assert puck.getField("camera_noise").getTypeName() == "SFFloat"
    assert puck.getField("camera_antiAliasing").getSFBool() is False
    # C's wb_supervisor_node_get_field_by_index asks for the name, then takes that field.
    from mazesim.webots.native_calls import NativeCalls

    calls = NativeCalls(supervisor, [])
    (handle,) = calls.call("wb_supervisor_node_get_from_def", [b"EPUCK"])
    (name,) = calls.call("wb_supervisor_node_get_field_by_index", [handle, 0])
    assert name == puck.getFieldByIndex(0).getName().encode()
    # A loop over a node's fields by index reads each field once.
    for node in (info, puck):
        count = node.getNumberOfFields()
        names = [node.getFieldByIndex(i).getName() for i in range(count)]
        assert len(set(names)) == count > 10, names
        for name in names:
            assert node.getField(name) is not None, name
        capsys.readouterr()
        assert node.getFieldByIndex(count) is None
        assert "out of range" in capsys.readouterr().err


def test_a_node_inside_another_records_what_is_set(tmp_path: Path) -> None:
    supervisor = supervisor_of(GROUPED, tmp_path)
    box = supervisor.getFromDef("BOX1")
    assert box.getPosition() == pytest.approx([0.3, 0.2, 0.05])
    box.getField("translation").setSFVec3f([0.0, 0.1, 0.05])
    box.getField("rotation").setSFRotation([0.0, 0.0, 1.0, 0.5])
    assert box.getField("translation").getSFVec3f() == pytest.approx([0.0, 0.1, 0.05])
    assert box.getField("rotation").getSFRotation() == pytest.approx([0.0, 0.0, 1.0, 0.5])
    # The robot still moves, and a top-level node's field is still recorded.
    supervisor.getSelf().getField("translation").setSFVec3f([0.1, 0.0, 0.0])
    assert simulations.current().simulator.pose[0] == pytest.approx(0.1, abs=1e-6)
    group = supervisor.getFromDef("OBSTACLES")
    assert group.getField("translation") is None, "a Group is not placed"


def test_a_deep_nesting_is_read_without_recursion(tmp_path: Path) -> None:
    depth = 3000
    nested = "Group { children [ " * depth + "DEF DEEP Solid { }" + " ] }" * depth
    scene = read_scene("#VRML_SIM R2023b utf8\n" + nested)
    node = scene.nodes[0]
    for _ in range(depth - 1):
        (node,) = node.children
    assert node.children[0].def_name == "DEEP"


#: A world whose ``children`` fields hold USE nodes: the Group lists a Solid, a Transform that
#: USEs that Solid, and a USE of a Solid at the file's top.
WITH_USE = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
DEF POST Solid { translation 0.2 0.1 0 name "post" }
DEF ROW Group {
  children [
    DEF PILLAR Solid { translation 0.3 0 0 rotation 0 0 1 1.5708 name "pillar" }
    Transform { translation 0 0.5 0 children [ USE PILLAR ] }
    USE POST
  ]
}
DEF EPUCK E-puck { translation -0.2 -0.1 0 supervisor TRUE }
"""


def test_a_use_in_a_children_field_is_the_node_of_its_def(tmp_path: Path) -> None:
    supervisor = supervisor_of(WITH_USE, tmp_path)
    row = supervisor.getFromDef("ROW").getField("children")
    assert row.getCount() == 3, "the Solid, the Transform and the USE of POST"
    post, pillar = supervisor.getFromDef("POST"), supervisor.getFromDef("PILLAR")
    assert row.getMFNode(2) is post and row.getMFNode(-1) is post
    transform = row.getMFNode(1).getField("children")
    assert transform.getCount() == 1 and transform.getMFNode(0) is pillar
    # The same node: its DEF name, fields, parent and place in the world are its DEF's.
    assert transform.getMFNode(0).getDef() == "PILLAR"
    assert pillar.getParentNode() is supervisor.getFromDef("ROW")
    assert pillar.getPosition() == pytest.approx([0.3, 0.0, 0.0])
    assert post.getParentNode() is supervisor.getRoot()
    assert post.getField("name").getSFString() == "post"
    ids = [n.getId() for n in (post, pillar, row.getMFNode(1), supervisor.getFromDef("ROW"))]
    assert len(set(ids)) == len(ids) and supervisor.getFromId(pillar.getId()) is pillar


def test_a_use_stands_for_the_last_def_of_its_name_before_it() -> None:
    text = (
        "#VRML_SIM R2023b utf8\n"
        'DEF A Solid { name "first" }\n'
        'Group { children [ USE A DEF A Solid { name "second" } USE A USE B ] }\n'
    )
    (first, group) = read_scene(text).nodes
    assert [child.name for child in group.children] == ["first", "second", "second"]
    assert group.children[0] is first, "the USE is the DEF's own node, not a copy"


def test_strings_holding_brackets_or_numbers_are_read_as_strings() -> None:
    text = (
        "#VRML_SIM R2023b utf8\n"
        'Solid { name "rock 1" customData "[(0.1, 0.2)] {x}" translation 1 2 3 }\n'
        'DEF EPUCK E-puck { customData "{\\"state\\": [1, 2]}" controllerArgs [ "a" "[b]" ] }\n'
    )
    scene = read_scene(text)
    rock, robot = scene.nodes
    assert rock.strings == {"customData": "[(0.1, 0.2)] {x}"} and rock.numbers == {}
    assert rock.name == "rock 1" and rock.translation == (1.0, 2.0, 3.0)
    assert scene.robot_custom_data == '{\\"state\\": [1, 2]}' and robot.robot
    assert scene.controller_args == ["a", "[b]"]


def test_adding_or_removing_nodes_where_mazesim_cannot_prints_an_error_and_changes_nothing(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    supervisor = supervisor_of(GROUPED, tmp_path)
    root = supervisor.getRoot().getField("children")
    box = supervisor.getFromDef("BOX1")
    no_file = "refused by mazesim: the run's world is no Webots world file; nothing changed"
    refused = {
        "importMFNodeFromString() " + no_file: lambda: root.importMFNodeFromString(-1, "Solid {}"),
        "Field.importSFNodeFromString() on field 'children' of node Solid (DEF BOX1) is not "
        "supported": lambda: box.getField("children").importSFNodeFromString("Solid {}"),
        "importMFNode(): cannot read 'box.wbo'": lambda: root.importMFNode(-1, "box.wbo"),
        "wb_supervisor_field_remove_mf() " + no_file: lambda: root.removeMF(2),
        "Field.removeSF() on field 'children' of the scene tree's root": lambda: root.removeSF(),
        "wb_supervisor_node_remove() refused by mazesim: a node inside another node stays": (
            box.remove
        ),
        "importMFNodeFromString() " + no_file: lambda: box.getField(
            "children"
        ).importMFNodeFromString(-1, "Solid {}"),
    }
    capsys.readouterr()
    for call, refused_call in refused.items():
        assert refused_call() is None
        message = capsys.readouterr().err
        assert message.startswith(f"Error: {call}"), message
    assert root.getCount() == 4 and supervisor.getFromDef("BOX1") is box


def test_the_start_up_check_names_the_calls_that_change_the_scene(tmp_path: Path) -> None:
    from mazesim.webots.requirements import prepare_controller, scene_changes

    spawner = tmp_path / "spawner" / "spawner.py"
    spawner.parent.mkdir()
    spawner.write_text(
        "from controller import Supervisor\n"
        "supervisor = Supervisor()\n"
        "children = supervisor.getRoot().getField('children')\n"
        "children.importMFNodeFromString(-1, 'DEF TRASH Solid {}')\n"
        "kept = [1, 2]\n"
        "kept.remove(1)\n"
        "supervisor.getFromDef('TRASH').remove()\n"
    )
    prepared = prepare_controller(str(spawner))
    (statement,) = [m for m in prepared.missing if m.startswith("adding nodes")]
    assert "(importMFNodeFromString, remove)" in statement
    assert "print an error and change nothing" in statement and prepared.runnable
    cleaner = tmp_path / "cleaner" / "cleaner.c"
    cleaner.parent.mkdir()
    cleaner.write_text("void clean(WbNodeRef n) { wb_supervisor_node_remove(n); }\n")
    assert scene_changes(str(cleaner), "c") == ["wb_supervisor_node_remove"]
    plain = tmp_path / "plain" / "plain.py"
    plain.parent.mkdir()
    plain.write_text("items = [1]\nitems.remove(1)\n")
    assert scene_changes(str(plain), "python") == []


def test_a_compiled_controllers_remove_is_refused_as_a_python_ones(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from mazesim.webots.native_calls import NativeCalls

    calls = NativeCalls(supervisor_of(GROUPED, tmp_path), [])
    (box,) = calls.call("wb_supervisor_node_get_from_def", [b"BOX1"])
    capsys.readouterr()
    calls.call("wb_supervisor_node_remove", [box])
    assert "a node inside another node stays" in capsys.readouterr().err
    (root,) = calls.call("wb_supervisor_node_get_root", [])
    children, _ = calls.call("wb_supervisor_node_get_field", [root, b"children"])
    calls.call("wb_supervisor_field_import_mf_node_from_string", [children, -1, b"Solid {}"])
    assert "importMFNodeFromString" in capsys.readouterr().err
    assert calls.call("wb_supervisor_field_get_count", [children]) == [4]


#: An arena that writes none of its fields, and an e-puck that names no controller.
UNWRITTEN = """#VRML_SIM R2025a utf8
WorldInfo { basicTimeStep 32 }
DEF ARENA RectangleArena { }
DEF SMALL RectangleArena { translation 3 0 0 floorSize 0.5 0.25 name "small" }
DEF EPUCK E-puck { translation -0.2 -0.1 0 supervisor TRUE controller "x" }
DEF OTHER E-puck { translation 0.2 0 0 }
DEF PLAIN WoodenBox { translation 0.4 0.4 0.05 size 0.1 0.1 0.1 }
DEF LIGHT WoodenBox { translation -0.4 0.4 0.05 size 0.05 0.1 0.1 mass 0.06 }
"""


def test_a_protos_fields_the_file_leaves_out_read_as_the_proto_declares(tmp_path: Path) -> None:
    supervisor = supervisor_of(UNWRITTEN, tmp_path)
    arena = supervisor.getFromDef("ARENA")
    assert arena is not None
    assert arena.getField("floorSize").getSFVec2f() == [1.0, 1.0]
    assert arena.getField("wallHeight").getSFFloat() == pytest.approx(0.1)
    assert arena.getField("name").getSFString() == "rectangle arena"
    small = supervisor.getFromDef("SMALL")
    assert small.getField("floorSize").getSFVec2f() == [0.5, 0.25], "the file's value wins"
    assert small.getField("floorTileSize").getSFVec2f() == [0.5, 0.5]
    assert small.getField("name").getSFString() == "small"
    other = supervisor.getFromDef("OTHER")
    assert other.getField("controller").getSFString() == "e-puck_avoid_obstacles"
    assert other.getField("camera_width").getSFInt32() == 52
    assert other.getField("supervisor").getSFBool() is False
    assert other.getField("no such field") is None
    # A WoodenBox's mass, which a supervisor reads to pick the lightest box: 0 (a box without
    # physics) where the file leaves it out, an SFFloat either way.
    plain, light = supervisor.getFromDef("PLAIN"), supervisor.getFromDef("LIGHT")
    assert plain.getField("mass").getType() == controller.Field.SF_FLOAT
    assert plain.getField("mass").getSFFloat() == 0.0
    assert light.getField("mass").getSFFloat() == pytest.approx(0.06)
    assert plain.getField("size").getSFVec3f() == pytest.approx([0.1, 0.1, 0.1])
    assert plain.getField("locked").getSFBool() is False
    assert plain.getField("name").getSFString() == "wooden box"


#: Walls whose sizes a supervisor reads through their Shapes' geometry, and a painted marker.
WALLS = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
DEF WALL_X Solid {
  translation 0.5 0 0.05
  children [ DEF SIDE Shape { geometry Box { size 0.3 0.01 0.1 } } ]
  boundingObject USE SIDE
}
DEF MARK Pose {
  children [
    Shape {
      appearance Appearance { material Material { diffuseColor 0 0 1 } }
      geometry Cylinder { height 0.1 radius 0.05 }
    }
  ]
}
DEF EPUCK E-puck { supervisor TRUE }
"""


def test_a_supervisor_reads_a_shapes_geometry_and_appearance_through_their_fields(
    tmp_path: Path,
) -> None:
    """``getSFNode`` of a field holding one node (a Shape's ``geometry`` and ``appearance``, an
    Appearance's ``material``, a Solid's ``boundingObject``) gives that node and its fields, as
    a supervisor mapping a maze's walls from the scene tree reads them."""
    supervisor = supervisor_of(WALLS, tmp_path)
    wall = supervisor.getFromDef("WALL_X")
    shape = wall.getField("children").getMFNode(0)
    geometry = shape.getField("geometry").getSFNode()
    assert (geometry.getTypeName(), geometry.getParentNode()) == ("Box", shape)
    assert geometry.getField("size").getSFVec3f() == pytest.approx([0.3, 0.01, 0.1])
    assert shape.getField("geometry").getTypeName() == "SFNode"
    assert wall.getField("boundingObject").getSFNode() is shape, "a USE is its DEF's node"
    marker = supervisor.getFromDef("MARK").getField("children").getMFNode(0)
    material = marker.getField("appearance").getSFNode().getField("material").getSFNode()
    assert material.getField("diffuseColor").getSFColor() == [0.0, 0.0, 1.0]
    material.getField("diffuseColor").setSFColor([1, 0, 0])
    assert material.getField("diffuseColor").getSFColor() == [1.0, 0.0, 0.0], "recorded"
    assert marker.getField("geometry").getSFNode().getField("radius").getSFFloat() == 0.05
    # Webots' Python getters read a field by its own type: the node of an SFNode field; the C
    # API's typed function refuses it.
    geometry_field = marker.getField("geometry")
    assert geometry_field.getSFVec3f() is geometry_field.getSFNode()
    assert wall.getField("name").getSFString() == "solid", "a Solid's default name"
    assert wall.getField("nothing") is None and geometry_field.c_sf_vec3f() is None
    ids = {shape.getId(), geometry.getId(), material.getId()}
    assert len(ids) == 3 and 0 not in ids
    assert supervisor.getFromId(geometry.getId()) is geometry
    grouped = supervisor_of(GROUPED, tmp_path)
    box = grouped.getFromDef("BOXGEOM")  # a DEF in a Shape's geometry field
    assert box.getTypeName() == "Box" and box.getField("size").getSFVec3f()[2] == 0.1
    assert grouped.getFromDef("BOX1").getField("boundingObject").getSFNode() is box


def test_another_robot_whose_node_leaves_its_rotation_out_has_a_live_rotation_field() -> None:
    """A robot of the world of a project's own e-puck PROTO (not known here as a Solid) whose
    node writes no ``rotation``: a supervisor still finds its rotation field, as in Webots (a
    NULL field crashed a C supervisor that read it)."""
    puck = supervisor_module.Node(
        "epuck_rangeColA", "e-puck1", 7, translation=(0.1, 0.2, 0.0), name="e-puck1"
    )
    assert puck.getBaseTypeName() == "epuck_rangeColA"
    puck._fleet_index = 1  # another robot of the world, as a world run links it
    rotation = puck.getField("rotation")
    assert rotation is not None and rotation.getTypeName() == "SFRotation"
    assert puck.getField("translation").getTypeName() == "SFVec3f"
    assert puck.getNumberOfFields() == 3  # name, translation, rotation
    wall = supervisor_module.Node("Wall", "W", 8, translation=(0.0, 0.0, 0.0))
    assert wall.getField("rotation") is None, "a node that is no robot keeps the file's fields"


def test_a_robot_set_into_a_wall_is_pushed_out_of_it_as_webots_physics_does(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Webots puts a node wherever its translation is set and its physics pushes a body out of
    a wall it overlaps; the supervisor's move never fails for a pose a few mm into a wall."""
    supervisor = supervisor_of(GROUPED, tmp_path)
    robot = supervisor.getSelf()
    # The arena's east wall (0.01 m thick) starts at x = 0.5: 0.46 puts the e-puck's
    # 0.037 m body 3 mm into it.
    robot.getField("translation").setSFVec3f([0.466, 0.0, 0.0])
    x, y, _ = robot.getPosition()
    assert 0.462 <= x <= 0.465 and abs(y) < 0.002, "the nearest pose clear of the wall"
    assert simulations.current().simulator.wall_clearance >= -0.001, "as a simulator allows"
    # On the centre of BOX1 (5 cm square) the nearest clear pose is 6.2 cm away: refused, with
    # Webots' kind of error (its field setters never raise); the robot stays where it was.
    capsys.readouterr()
    robot.getField("translation").setSFVec3f([0.3, 0.2, 0.0])
    assert "cannot be moved there" in capsys.readouterr().err
    assert robot.getPosition()[:2] == pytest.approx([x, y], abs=1e-9)
    # So is a pose beyond mazesim's limits (1 km), which Webots takes.
    robot.getField("translation").setSFVec3f([1500.0, 0.0, 0.0])
    error = capsys.readouterr().err
    assert "cannot be moved there" in error and "[-1000, 1000], found 1500.0" in error
    assert robot.getPosition()[:2] == pytest.approx([x, y], abs=1e-9)
    assert robot.getField("translation").getSFVec3f()[:2] == pytest.approx([x, y], abs=1e-9)


#: An e-puck saved expanded (a plain Robot, as R2025a saves one), a supervisor whose Emitter
#: holds the Shape that shows its range; a second one beside it.
EXPANDED = """#VRML_SIM R2025a utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { }
DEF epuck Robot {
  translation 0.1 0 0
  children [
    DEF EPUCK_RECEIVER Receiver { channel 1 }
    DEF EPUCK_EMITTER Emitter {
      children [
        Pose {
          children [
            Shape {
              appearance PBRAppearance { transparency 0.9 }
              geometry Sphere { radius 0.25 }
            }
          ]
        }
      ]
      range 0.25
      channel 1
    }
  ]
  name "epuck"
  model "GCtronic e-puck"
  controller "aggregation"
  supervisor TRUE
}
DEF other Robot {
  translation -0.2 0 0
  children [ DEF EPUCK_EMITTER Emitter { channel 1 } ]
  name "other"
  model "GCtronic e-puck"
  controller "aggregation"
}
"""


def test_a_plain_robots_children_and_its_devices_children_are_fields(tmp_path: Path) -> None:
    supervisor = supervisor_of(EXPANDED, tmp_path)
    own = supervisor.getFromDef("epuck")
    children = own.getField("children")
    assert children.getCount() == 2
    emitter = children.getMFNode(1)
    assert (emitter.getTypeName(), emitter.getDef()) == ("Emitter", "EPUCK_EMITTER")
    assert emitter.getField("range").getSFFloat() == pytest.approx(0.25)
    pose = emitter.getField("children").getMFNode(0)
    shape = pose.getField("children").getMFNode(0)
    appearance = shape.getField("appearance").getSFNode()
    transparency = appearance.getField("transparency")
    assert transparency.getSFFloat() == pytest.approx(0.9)
    transparency.setSFFloat(1.0)  # hides the range sphere, as a swarm's controller does
    assert transparency.getSFFloat() == 1.0
    # Another robot's children are there too; an E-puck PROTO's are not a field of it.
    other = supervisor.getFromDef("other").getField("children")
    assert other.getMFNode(0).getTypeName() == "Emitter"
