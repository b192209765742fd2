"""A supervisor imports nodes into the running world and removes them: an imported Solid is
met and seen by the robot from the next step on, found by its DEF name and moved by its
fields; a removed one is gone; the robot runs on as it was; a supervisor's reset takes the
imported nodes out, as Webots' does (#33)."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import pytest

from mazesim.webots import controller
from mazesim.webots import simulation as simulations
from mazesim.webots.native_calls import NativeCalls
from supervised_world import drive, front, run_test_world, supervisor_in

pytestmark = pytest.mark.usefixtures("fresh_robot")

#: A static box 0.04 m wide, 0.08 m ahead of the robot (its centre), which faces +x.
AHEAD = (
    "DEF CRATE Solid { translation 0.08 0 0.05 children [ Shape { geometry DEF CRATE_BOX "
    'Box { size 0.04 0.3 0.1 } } ] name "crate" boundingObject USE CRATE_BOX }'
)


def without_gate(supervisor: controller.Supervisor) -> None:
    supervisor.getFromDef("GATE").getField("translation").setSFVec3f([0.1, 0.6, 0.05])


def crate_ahead(tmp_path: Path) -> tuple[controller.Supervisor, Any, int, float]:
    """The supervisor of a world without the gate, after it imported the crate ahead: with the
    root's ``children`` field, their count and the front sensors' reading before the import."""
    supervisor = supervisor_in(tmp_path)
    without_gate(supervisor)
    children = supervisor.getRoot().getField("children")
    count = children.getCount()
    clear = front(supervisor)
    children.importMFNodeFromString(-1, AHEAD)
    return supervisor, children, count, clear


def test_an_imported_solid_is_in_the_scene_tree_and_seen_from_the_next_step(
    tmp_path: Path,
) -> None:
    supervisor, children, count, clear = crate_ahead(tmp_path)
    assert children.getCount() == count + 1
    crate = supervisor.getFromDef("CRATE")
    assert crate is children.getMFNode(-1) and crate.getTypeName() == "Solid"
    assert crate.getParentNode() is supervisor.getRoot()
    assert supervisor.getFromId(crate.getId()) is crate
    ids = [children.getMFNode(i).getId() for i in range(children.getCount())]
    assert len(set(ids)) == len(ids)
    assert crate.getPosition() == pytest.approx([0.08, 0.0, 0.05])
    assert crate.getField("name").getSFString() == "crate"
    seen = front(supervisor)
    assert seen > clear + 300.0, (clear, seen)
    # Its translation moves it in the simulation, as a node of the file.
    crate.getField("translation").setSFVec3f([0.08, 0.8, 0.05])
    assert front(supervisor) == pytest.approx(clear, abs=50.0)


def test_a_robot_driving_forward_stops_on_an_imported_box(tmp_path: Path) -> None:
    supervisor = supervisor_in(tmp_path)
    without_gate(supervisor)
    supervisor.getRoot().getField("children").importMFNodeFromString(0, AHEAD)
    assert supervisor.getRoot().getField("children").getMFNode(0).getDef() == "CRATE"
    drive(supervisor, 6.0, 60)
    x, _, _ = simulations.current().simulator.pose
    # Its front (0.037 m from its centre) is held at the box's face, 0.06 m ahead.
    assert 0.015 < x < 0.024, x
    assert simulations.current().simulator.colliding


def test_a_removed_node_is_gone_from_the_tree_and_the_simulation(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    supervisor = supervisor_in(tmp_path)
    children = supervisor.getRoot().getField("children")
    count = children.getCount()
    gate = supervisor.getFromDef("GATE")
    blocked = front(supervisor)
    gate.remove()
    assert children.getCount() == count - 1
    capsys.readouterr()
    assert supervisor.getFromDef("GATE") is None
    assert capsys.readouterr().err == "", "a missing DEF gives None silently, as in Webots"
    clear = front(supervisor)
    assert clear < blocked - 30.0
    children.importMFNodeFromString(-1, AHEAD)
    assert front(supervisor) > blocked + 200.0
    children.removeMF(-1)
    assert supervisor.getFromDef("CRATE") is None and children.getCount() == count - 1
    drive(supervisor, 6.0, 30)
    assert simulations.current().simulator.pose[0] > 0.1, (
        "nothing ahead (the gate held it at 0.053)"
    )


def test_a_run_that_imports_a_box_out_of_reach_goes_on_bit_for_bit(tmp_path: Path) -> None:
    far = AHEAD.replace("translation 0.08 0 0.05", "translation -0.8 -0.8 0.05")

    def run(importing: bool) -> list[tuple[float, ...]]:
        supervisor = supervisor_in(tmp_path, noise=True)
        poses = []
        for step in range(40):
            if importing and step == 10:
                supervisor.getRoot().getField("children").importMFNodeFromString(-1, far)
            drive(supervisor, 5.0 if step < 25 else -3.0, 1)
            simulator = simulations.current().simulator
            readings = tuple(float(v) for v in simulator.distance_sensors())
            poses.append((*simulator.pose, *simulator.encoders, simulator.time, *readings))
            poses.append(tuple(v for pose in simulator.body_poses() for v in pose))
        return poses

    assert run(importing=True) == run(importing=False)


def test_an_imported_box_with_physics_is_pushed_and_a_removed_one_is_gone(tmp_path: Path) -> None:
    supervisor = supervisor_in(tmp_path)
    without_gate(supervisor)
    simulator = simulations.current().simulator
    children = supervisor.getRoot().getField("children")
    children.importMFNodeFromString(
        -1,
        "DEF CUBE Solid { translation 0.08 0 0.02 children [ Shape { geometry DEF CUBE_BOX Box "
        "{ size 0.04 0.04 0.04 } } ] boundingObject USE CUBE_BOX physics Physics { density -1 "
        "mass 0.05 } }",
    )
    cube = supervisor.getFromDef("CUBE")
    assert len(simulator.body_poses()) == 2
    assert cube.getPosition() == pytest.approx([0.08, 0.0, 0.02], abs=1e-6)
    drive(supervisor, 6.0, 40)
    x, y, _ = cube.getPosition()
    assert x > 0.12 and (x, y) == pytest.approx(simulator.body_poses()[1][:2], abs=1e-6)
    assert cube.getVelocity()[0] > 0.01, "pushed along x"
    # The box of the file (inside the top-level Pose PLACE) goes with its Pose; the cube stays.
    before = simulator.body_poses()[1]
    supervisor.getFromDef("PLACE").remove()
    assert simulator.body_poses() == [before]
    assert cube.getPosition()[:2] == pytest.approx(before[:2], abs=1e-6)
    cube.remove()
    assert simulator.body_poses() == [] and supervisor.getFromDef("BOX") is None


def test_robots_are_not_imported_nor_removed(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    supervisor = supervisor_in(tmp_path)
    children = supervisor.getRoot().getField("children")
    count = children.getCount()
    capsys.readouterr()
    children.importMFNodeFromString(-1, "DEF TWO E-puck { translation 0.5 0.5 0 }")
    refused = capsys.readouterr().err
    assert "robots" in refused and "nothing changed" in refused, refused
    children.importMFNodeFromString(7, AHEAD)
    assert "out of range position: 7" in capsys.readouterr().err
    supervisor.getSelf().remove()
    assert "the robot's own node stays" in capsys.readouterr().err
    assert children.getCount() == count and supervisor.getFromDef("TWO") is None
    assert front(supervisor) > 160.0, "the gate is still there (134 without it)"


def test_a_compiled_supervisors_import_and_removal_change_the_world(tmp_path: Path) -> None:
    supervisor = supervisor_in(tmp_path)
    without_gate(supervisor)
    calls = NativeCalls(supervisor, [])
    (root,) = calls.call("wb_supervisor_node_get_root", [])
    children, _ = calls.call("wb_supervisor_node_get_field", [root, b"children"])
    (count,) = calls.call("wb_supervisor_field_get_count", [children])
    clear = front(supervisor)
    calls.call("wb_supervisor_field_import_mf_node_from_string", [children, -1, AHEAD.encode()])
    assert calls.call("wb_supervisor_field_get_count", [children]) == [count + 1]
    (crate,) = calls.call("wb_supervisor_node_get_from_def", [b"CRATE"])
    assert crate and front(supervisor) > clear + 300.0
    calls.call("wb_supervisor_node_remove", [crate])
    assert calls.call("wb_supervisor_field_get_count", [children]) == [count]
    assert front(supervisor) == pytest.approx(clear, abs=50.0)
    assert not math.isnan(clear)


def test_a_supervisor_robot_imports_and_removes_a_crate_in_a_world_of_several_robots(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    robots = run_test_world("spawner.wbt", tmp_path, monkeypatch)
    seen = json.loads((tmp_path / "spawner.json").read_text())
    assert seen["count_with"] == seen["count_before"] + 1 == seen["count_after"] + 1
    assert seen["crate"] == pytest.approx([-0.09, 0.0, 0.05]) and seen["gone"]
    _, pusher, bystander = robots
    assert bystander.final_pose[0] > 0.6, "the other e-puck drove on in the changed world"
    # Held at the crate's face (x = -0.10) while it stood, then on past it.
    assert pusher.xs[35] < -0.1 - 0.037 + 1e-3
    assert pusher.final_pose[0] > -0.12


def test_a_supervisor_reset_takes_an_imported_box_out(tmp_path: Path) -> None:
    supervisor, children, count, clear = crate_ahead(tmp_path)
    assert front(supervisor) > clear + 300.0
    supervisor.simulationReset()
    supervisor.step(32)  # the reset is applied at the end of the next step, as in Webots
    assert children.getCount() == count and supervisor.getFromDef("CRATE") is None
    without_gate(supervisor)  # the reset put the gate back where the file has it
    assert front(supervisor) == pytest.approx(clear, abs=50.0), "the crate is out too"
    # A later import takes a new place and is met again.
    children.importMFNodeFromString(-1, AHEAD)
    assert children.getCount() == count + 1 and front(supervisor) > clear + 300.0


def test_an_imported_robot_that_is_no_e_puck_is_an_obstacle_with_the_importers_warning(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    supervisor = supervisor_in(tmp_path)
    without_gate(supervisor)
    children = supervisor.getRoot().getField("children")
    clear = front(supervisor)
    capsys.readouterr()
    children.importMFNodeFromString(
        -1,
        'DEF ROVER Robot { translation 0.08 0 0.05 name "rover" controller "<none>" children [ '
        "Shape { geometry DEF ROVER_BOX Box { size 0.04 0.3 0.1 } } ] "
        "boundingObject USE ROVER_BOX }",
    )
    said = capsys.readouterr().err
    assert "mazesim: warning:" in said and "not an e-puck (Robot)" in said, said
    assert "its collision shapes are static obstacles" in said
    rover = supervisor.getFromDef("ROVER")
    assert rover is not None and rover.getPosition() == pytest.approx([0.08, 0.0, 0.05])
    assert front(supervisor) > clear + 300.0
    rover.remove()
    assert front(supervisor) == pytest.approx(clear, abs=50.0)
