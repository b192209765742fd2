"""A supervisor imports nodes into the ``children`` of a node other than the root, placed in
that node's frame, and into an empty ``endPoint`` field (``importSFNodeFromString``); removes
them (``removeMF``, ``removeSF``, ``Node.remove()``), and they go with their parent (#33)."""

from __future__ import annotations

from pathlib import Path

import pytest

from mazesim.webots.native_calls import NativeCalls
from supervised_world import front, supervisor_in

pytestmark = pytest.mark.usefixtures("fresh_robot")

#: An e-puck supervisor at the origin facing +x; a shelf and a socket (holding a Slot) 0.2 m
#: ahead, each turned a quarter turn, and so a node at (0, 0.12) in their frame stands at
#: (0.08, 0) in the world, just ahead of the robot.
WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 2 2 }
DEF SHELF Pose {
  translation 0.2 0 0
  rotation 0 0 1 1.5707963267948966
  children [ ]
}
DEF SOCKET Pose {
  translation 0.2 0 0
  rotation 0 0 1 1.5707963267948966
  children [
    DEF SLOT Slot { }
  ]
}
DEF EPUCK E-puck { translation 0 0 0 supervisor TRUE controller "<extern>" }
"""

#: A static board 0.3 m long along its x axis, at (0, 0.12) of its parent's frame.
BOARD = (
    "DEF BOARD Solid { translation 0 0.12 0.05 children [ Shape { geometry DEF BOARD_BOX "
    'Box { size 0.3 0.04 0.1 } } ] name "board" boundingObject USE BOARD_BOX }'
)


def test_a_node_imported_into_a_poses_children_stands_in_its_frame(tmp_path: Path) -> None:
    supervisor = supervisor_in(tmp_path, WORLD)
    shelf = supervisor.getFromDef("SHELF")
    children = shelf.getField("children")
    clear = front(supervisor)
    children.importMFNodeFromString(-1, BOARD)
    board = supervisor.getFromDef("BOARD")
    assert children.getCount() == 1 and children.getMFNode(0) is board
    assert board.getParentNode() is shelf
    assert supervisor.getFromId(board.getId()) is board
    assert board.getField("translation").getSFVec3f() == pytest.approx([0.0, 0.12, 0.05])
    assert board.getPosition() == pytest.approx([0.08, 0.0, 0.05], abs=1e-9)
    # Across the robot's way (not along it, as it would stand unturned at (0, 0.12)).
    seen = front(supervisor)
    assert seen > clear + 300.0, (clear, seen)
    children.removeMF(0)
    assert children.getCount() == 0 and supervisor.getFromDef("BOARD") is None
    assert front(supervisor) == pytest.approx(clear, abs=50.0)


def test_a_node_imported_into_a_slot_end_point_is_there_until_removed(tmp_path: Path) -> None:
    supervisor = supervisor_in(tmp_path, WORLD)
    slot = supervisor.getFromDef("SLOT")
    end_point = slot.getField("endPoint")
    assert end_point.getSFNode() is None
    clear = front(supervisor)
    end_point.importSFNodeFromString(BOARD)
    board = end_point.getSFNode()
    assert board is not None and board is supervisor.getFromDef("BOARD")
    assert board.getParentNode() is slot
    assert board.getPosition() == pytest.approx([0.08, 0.0, 0.05], abs=1e-9)
    assert front(supervisor) > clear + 300.0
    end_point.removeSF()
    assert end_point.getSFNode() is None and supervisor.getFromDef("BOARD") is None
    assert front(supervisor) == pytest.approx(clear, abs=50.0)


def test_a_full_end_point_and_a_robot_take_no_import(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    supervisor = supervisor_in(tmp_path, WORLD)
    end_point = supervisor.getFromDef("SLOT").getField("endPoint")
    end_point.importSFNodeFromString(BOARD)
    capsys.readouterr()
    end_point.importSFNodeFromString(BOARD.replace("BOARD", "OTHER"))
    assert "holds a node" in capsys.readouterr().err
    assert supervisor.getFromDef("OTHER") is None
    supervisor.getFromDef("SHELF").getField("translation").importSFNodeFromString(BOARD)
    assert "nothing changed" in capsys.readouterr().err


def test_a_movable_body_takes_no_import(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    supervisor = supervisor_in(tmp_path)  # its BOX is a light box with physics
    children = supervisor.getFromDef("BOX").getField("children")
    count = children.getCount()
    capsys.readouterr()
    children.importMFNodeFromString(-1, BOARD)
    assert "moves in the simulation" in capsys.readouterr().err
    assert children.getCount() == count and supervisor.getFromDef("BOARD") is None


def test_imported_nodes_go_with_their_parent(tmp_path: Path) -> None:
    supervisor = supervisor_in(tmp_path, WORLD)
    clear = front(supervisor)
    slot = supervisor.getFromDef("SLOT")
    slot.getField("endPoint").importSFNodeFromString(BOARD)
    assert front(supervisor) > clear + 300.0
    supervisor.getFromDef("SOCKET").remove()
    assert supervisor.getFromDef("BOARD") is None and supervisor.getFromDef("SLOT") is None
    assert front(supervisor) == pytest.approx(clear, abs=50.0)
    # A reset takes out what was imported into the shelf, as Webots' reset does.
    supervisor.getFromDef("SHELF").getField("children").importMFNodeFromString(0, BOARD)
    assert front(supervisor) > clear + 300.0
    supervisor.simulationReset()
    supervisor.step(32)
    assert supervisor.getFromDef("SHELF").getField("children").getCount() == 0
    assert front(supervisor) == pytest.approx(clear, abs=50.0)


def test_a_compiled_supervisor_imports_into_an_end_point(tmp_path: Path) -> None:
    supervisor = supervisor_in(tmp_path, WORLD)
    calls = NativeCalls(supervisor, [])
    (slot,) = calls.call("wb_supervisor_node_get_from_def", [b"SLOT"])
    end_point, _ = calls.call("wb_supervisor_node_get_field", [slot, b"endPoint"])
    clear = front(supervisor)
    calls.call("wb_supervisor_field_import_sf_node_from_string", [end_point, BOARD.encode()])
    (board,) = calls.call("wb_supervisor_field_get_sf_node", [end_point])
    assert board and front(supervisor) > clear + 300.0
    calls.call("wb_supervisor_field_remove_sf", [end_point])
    (gone,) = calls.call("wb_supervisor_field_get_sf_node", [end_point])
    assert not gone, "NULL: the field is empty again"
