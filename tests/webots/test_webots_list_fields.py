"""A supervisor reads and edits a node's list fields of values (``MFString``, ``MFVec3f``...)
as Webots' ``wb_supervisor_field_get_mf_*`` and its setters do. Public supervisors read a
floor's texture ``url`` with ``getMFString(0)`` and write it back, edit a DistanceSensor's
``lookupTable`` row by row with ``setMFVec3f``, or read a project PROTO's list field; each
found no such field (``getField`` gave None and the next call an AttributeError)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from mazesim.errors import InvalidArgumentError
from mazesim.webots.field import Field
from mazesim.webots.importer import import_wbt
from mazesim.webots.scene import read_scene
from native_controllers import NEEDS_COMPILERS, run_twins, write_source
from supervised_world import supervisor_in

#: A project PROTO with list fields of two kinds, one left out by the instance.
MARKER = """#VRML_SIM R2023b utf8
PROTO Marker [
  field SFVec3f    translation 0 0 0
  field MFString   tags        ["a" "b"]
  field MFFloat    weights     [0.5 1.5]
  field MFInt32    codes       [3 4]
]
{
  Solid { translation IS translation }
}
"""

WORLD = """#VRML_SIM R2023b utf8
EXTERNPROTO "Marker.proto"
DEF INFO WorldInfo { basicTimeStep 32 info [ "first line" "second line" ] }
DEF FLOOR Solid {
  translation 0 0 -0.01
  children [ Shape { appearance Appearance { texture DEF TEX ImageTexture {
    url [ "textures/floor.png" ] } } geometry Plane { } } ]
}
DEF SENSOR DistanceSensor { lookupTable [ 0 1000 0, 0.07 0 0.01 ] }
DEF MARK Marker { translation 0.2 0 0 codes [7] }
DEF EPUCK E-puck { supervisor TRUE controller "<extern>" }
"""


@pytest.fixture
def robot(tmp_path: Path) -> Any:
    (tmp_path / "Marker.proto").write_text(MARKER)
    return supervisor_in(tmp_path, WORLD)


def test_a_texture_url_reads_and_is_written_back(robot: Any) -> None:
    url = robot.getFromDef("TEX").getField("url")
    assert url.getType() == Field.MF_STRING
    assert url.getTypeName() == "MFString"
    assert url.getCount() == 1
    assert url.getMFString(0) == "textures/floor.png"
    assert url.getMFString(-1) == "textures/floor.png"
    url.setMFString(0, "textures/other.png")
    assert robot.getFromDef("TEX").getField("url").getMFString(0) == "textures/other.png"


def test_a_lookup_table_reads_row_by_row_and_rows_are_set_inserted_and_removed(
    robot: Any,
) -> None:
    table = robot.getFromDef("SENSOR").getField("lookupTable")
    assert table.getType() == Field.MF_VEC3F
    assert table.getCount() == 2
    assert table.getMFVec3f(1) == pytest.approx([0.07, 0.0, 0.01])
    table.setMFVec3f(1, [0.1, 0.0, 0.02])
    table.insertMFVec3f(-1, [0.2, 0.0, 0.0])
    table.insertMFVec3f(0, [-0.1, 1000.0, 0.0])
    assert table.getCount() == 4
    assert [table.getMFVec3f(i)[0] for i in range(4)] == pytest.approx([-0.1, 0.0, 0.1, 0.2])
    table.removeMF(0)
    assert table.getCount() == 3
    assert table.getMFVec3f(0) == pytest.approx([0.0, 1000.0, 0.0])


def test_a_project_protos_list_fields_read_as_written_or_at_their_defaults(
    robot: Any,
) -> None:
    mark = robot.getFromDef("MARK")
    tags = mark.getField("tags")
    assert tags.getTypeName() == "MFString"
    assert [tags.getMFString(i) for i in range(tags.getCount())] == ["a", "b"]
    assert mark.getField("weights").getMFFloat(1) == pytest.approx(1.5)
    codes = mark.getField("codes")  # written by the instance: [7], of the PROTO's kind
    assert codes.getTypeName() == "MFInt32"
    assert (codes.getCount(), codes.getMFInt32(0)) == (1, 7)
    info = robot.getFromDef("INFO").getField("info")
    assert [info.getMFString(i) for i in range(info.getCount())] == ["first line", "second line"]
    assert robot.getFromDef("EPUCK").getField("name").getCount() == -1  # a single field


def test_a_wrong_index_or_type_prints_webots_error_and_changes_nothing(
    robot: Any, capsys: pytest.CaptureFixture[str]
) -> None:
    table = robot.getFromDef("SENSOR").getField("lookupTable")
    capsys.readouterr()
    assert table.getMFVec3f(2) is None
    assert "get_mf_vec3f() called with an out of range index: 2" in capsys.readouterr().err
    assert table.getMFFloat(0) == 0.0
    assert "called with a field of type MFVec3f" in capsys.readouterr().err
    table.setMFVec3f(-3, [1.0, 1.0, 1.0])
    assert "out of range index: -3" in capsys.readouterr().err
    assert table.getCount() == 2
    with pytest.raises(InvalidArgumentError, match="expected a list of 3 numbers"):
        table.setMFVec3f(0, [1.0, 2.0, 3.0, 4.0])


TWIN_WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 1 1 }
DEF TEX Solid { translation 0.3 0.3 0 children [ Shape { appearance Appearance {
  texture DEF IMAGE ImageTexture { url [ "floor.png" "other.png" ] } } geometry Box {
  size 0.01 0.01 0.01 } } ] }
DEF SENSOR Solid { translation -0.3 0.3 0 children [ DEF RANGE DistanceSensor {
  lookupTable [ 0 1000 0, 0.07 0 0.01 ] } ] }
E-puck { supervisor TRUE controller "<extern>" }
"""
TWIN_PY = """from controller import Supervisor
robot = Supervisor()
table = robot.getFromDef("RANGE").getField("lookupTable")
url = robot.getFromDef("IMAGE").getField("url")
table.setMFVec3f(1, [0.1, 0.0, 0.02])
table.insertMFVec3f(-1, [0.2, 0.0, 0.0])
url.insertMFString(0, "first.png")
row = table.getMFVec3f(1)
print("rows %d row1 %.2f %.0f %.2f" % (table.getCount(), row[0], row[1], row[2]))
print("urls %d %s %s" % (url.getCount(), url.getMFString(0), url.getMFString(-1)))
robot.step(32)
"""
TWIN_C = """#include <stdio.h>
#include <webots/robot.h>
#include <webots/supervisor.h>
int main() {
  wb_robot_init();
  WbFieldRef table = wb_supervisor_node_get_field(wb_supervisor_node_get_from_def("RANGE"),
                                                  "lookupTable");
  WbFieldRef url = wb_supervisor_node_get_field(wb_supervisor_node_get_from_def("IMAGE"), "url");
  const double set[3] = {0.1, 0.0, 0.02}, added[3] = {0.2, 0.0, 0.0};
  wb_supervisor_field_set_mf_vec3f(table, 1, set);
  wb_supervisor_field_insert_mf_vec3f(table, -1, added);
  wb_supervisor_field_insert_mf_string(url, 0, "first.png");
  const double *row = wb_supervisor_field_get_mf_vec3f(table, 1);
  printf("rows %d row1 %.2f %.0f %.2f\\n", wb_supervisor_field_get_count(table), row[0], row[1],
         row[2]);
  printf("urls %d %s ", wb_supervisor_field_get_count(url),
         wb_supervisor_field_get_mf_string(url, 0));
  printf("%s\\n", wb_supervisor_field_get_mf_string(url, -1));
  wb_robot_step(32);
  wb_robot_cleanup();
  return 0;
}
"""
TWIN_CPP = """#include <cstdio>
#include <webots/Supervisor.hpp>
using namespace webots;
int main() {
  Supervisor robot;
  Field *table = robot.getFromDef("RANGE")->getField("lookupTable");
  Field *url = robot.getFromDef("IMAGE")->getField("url");
  const double set[3] = {0.1, 0.0, 0.02}, added[3] = {0.2, 0.0, 0.0};
  table->setMFVec3f(1, set);
  table->insertMFVec3f(-1, added);
  url->insertMFString(0, "first.png");
  const double *row = table->getMFVec3f(1);
  printf("rows %d row1 %.2f %.0f %.2f\\n", table->getCount(), row[0], row[1], row[2]);
  printf("urls %d %s ", url->getCount(), url->getMFString(0).c_str());
  printf("%s\\n", url->getMFString(-1).c_str());
  robot.step(32);
  return 0;
}
"""


@NEEDS_COMPILERS
@pytest.mark.usefixtures("own_cache")
def test_c_and_cpp_supervisors_edit_list_fields_as_python_does(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / "lists.wbt"
    path.write_text(TWIN_WORLD)
    world, report = import_wbt(str(path))
    twins = (
        write_source(tmp_path, "lists_py", TWIN_PY, ".py"),
        write_source(tmp_path, "lists_c", TWIN_C),
        write_source(tmp_path, "lists_cpp", TWIN_CPP, ".cpp"),
    )
    scene = read_scene(TWIN_WORLD)
    runs, outputs = run_twins(capfd, *twins, world=world, seconds=0.1, report=report, scene=scene)
    assert [(run.exit_status, run.error) for run in runs] == [(0, ""), (0, ""), (0, "")]
    assert outputs[0].splitlines()[:2] == [
        "rows 3 row1 0.10 0 0.02",
        "urls 3 first.png other.png",
    ]
    assert outputs[1] == outputs[0] and outputs[2] == outputs[0]
