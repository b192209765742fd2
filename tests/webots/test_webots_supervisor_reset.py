"""A supervisor resets the world between trials and moves things in it, as in Webots: its
``simulationReset`` puts every robot, moved wall and movable body back where the world file has
them at the end of the next step; moving the robot leaves the bodies where they are;
``setVelocity`` sets a body moving (#33)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from mazesim.webots import controller
from mazesim.webots import simulation as simulations
from supervised_world import drive, run_test_world, supervisor_of

#: Where the robot's centre stops when the gate, where the file puts it, holds it back.
BLOCKED_X = 0.1 - 0.01 - 0.037 + 1e-3

pytestmark = pytest.mark.usefixtures("fresh_robot")


def push_the_box(supervisor: controller.Supervisor) -> list[float]:
    """Moves the gate out of the way, puts the box ahead of the robot and pushes it: where the
    box ends."""
    supervisor.getFromDef("GATE").getField("translation").setSFVec3f([0.1, 0.6, 0.05])
    box = supervisor.getFromDef("BOX")
    box.getField("translation").setSFVec3f([-0.22, -0.3, 0.02])  # in its Pose's frame
    drive(supervisor, 6.0, 40)
    pushed = box.getPosition()
    assert pushed[0] > 0.12, "the robot pushed the box"
    return pushed


def test_a_reset_puts_the_robot_the_moved_wall_and_the_box_back(tmp_path: Path) -> None:
    supervisor = supervisor_of(tmp_path)
    push_the_box(supervisor)
    supervisor.simulationReset()
    supervisor.step(32)
    simulation = simulations.current()
    assert simulation.simulator.pose == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)
    box = supervisor.getFromDef("BOX")
    assert box.getPosition() == pytest.approx([0.3, 0.3, 0.02], abs=1e-6)
    assert box.getVelocity() == pytest.approx([0.0] * 6)
    gate = supervisor.getFromDef("GATE")
    assert gate.getField("translation").getSFVec3f() == pytest.approx([0.1, 0.0, 0.05])
    assert gate.getPosition() == pytest.approx([0.1, 0.0, 0.05])
    assert supervisor.getTime() == 0.0, "the clock starts again"
    # The gate stands where the file has it again: it stops the robot.
    drive(supervisor, 6.0, 40)
    assert simulation.simulator.pose[0] < BLOCKED_X
    assert simulation.simulator.body_poses()[0][:2] == pytest.approx((0.3, 0.3), abs=1e-6)


def test_a_reset_run_goes_on_as_a_fresh_one(tmp_path: Path) -> None:
    supervisor = supervisor_of(tmp_path)
    push_the_box(supervisor)
    supervisor.simulationReset()
    supervisor.step(32)
    drive(supervisor, 4.0, 30)
    after_reset = simulations.current().simulator.pose
    simulations.release()
    fresh = supervisor_of(tmp_path)
    drive(fresh, 4.0, 30)
    assert simulations.current().simulator.pose == after_reset


def test_moving_the_robot_leaves_the_pushed_box_where_it_is(tmp_path: Path) -> None:
    supervisor = supervisor_of(tmp_path)
    pushed = push_the_box(supervisor)
    supervisor.getSelf().getField("translation").setSFVec3f([-0.4, -0.4, 0.0])
    supervisor.getSelf().getField("rotation").setSFRotation([0.0, 0.0, 1.0, 1.0])
    box = supervisor.getFromDef("BOX")
    assert box.getPosition() == pytest.approx(pushed, abs=1e-6)
    assert simulations.current().simulator.pose[:2] == pytest.approx((-0.4, -0.4), abs=1e-6)
    supervisor.step(32)  # it coasts on a little, as it did before the move
    assert box.getPosition()[:2] == pytest.approx(pushed[:2], abs=0.01)


def test_set_velocity_sets_the_box_sliding_and_the_floor_slows_it(tmp_path: Path) -> None:
    supervisor = supervisor_of(tmp_path)
    box = supervisor.getFromDef("BOX")
    box.setVelocity([0.0, -0.5, 0.0, 0.0, 0.0, 1.5])
    assert box.getVelocity() == pytest.approx([0.0, -0.5, 0.0, 0.0, 0.0, 1.5])
    supervisor.step(32)
    # Coulomb friction 1 (Webots' default contact): g off the speed per second; the torque of
    # that friction stops a 4 cm box's turn at 1.5 rad/s within 3 ms.
    vx, vy, _, _, _, wz = box.getVelocity()
    assert vy == pytest.approx(-(0.5 - 9.81 * 0.032), abs=1e-4) and abs(vx) < 1e-6 and wz == 0.0
    x, y, _ = box.getPosition()
    assert y == pytest.approx(0.3 - (0.5 * 0.032 - 0.5 * 9.81 * 0.032**2), abs=1e-4)
    assert x == pytest.approx(0.3, abs=1e-6)
    supervisor.simulationResetPhysics()
    assert box.getVelocity() == pytest.approx([0.0] * 6)


def test_a_velocity_beyond_the_limits_is_refused_and_changes_nothing(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    supervisor = supervisor_of(tmp_path)
    box = supervisor.getFromDef("BOX")
    box.setVelocity([50.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    assert "velocity of node Solid (DEF BOX) cannot be set" in capsys.readouterr().err
    assert box.getVelocity() == pytest.approx([0.0] * 6)
    # A robot's velocity comes from its wheels: accepted, nothing changes.
    supervisor.getSelf().setVelocity([1.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    supervisor.step(32)
    assert simulations.current().simulator.pose == pytest.approx((0.0, 0.0, 0.0), abs=1e-9)


def test_a_supervisor_resets_a_world_of_several_robots(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    robots = run_test_world("resetter.wbt", tmp_path, monkeypatch)
    assert len(robots) == 2
    seen = json.loads((tmp_path / "resetter.json").read_text())
    assert seen["box_sliding"][1] < -0.1, "setVelocity set the box sliding"
    before, after = seen["before_reset"], seen["after_reset"]
    assert before["box"][1] < 0.3 - 0.02 and before["pusher"][0] > -0.2 + 0.02
    assert after["box"] == pytest.approx([0.3, 0.3, 0.02], abs=1e-6)
    assert after["box_velocity"] == pytest.approx([0.0] * 6)
    assert after["gate"] == pytest.approx([-0.12, 0.0, 0.05])
    assert after["pusher"] == pytest.approx([-0.2, 0.0, 0.0], abs=1e-6)
    assert after["time"] == 0.0
    # Its motors back in position control, the pusher, whose controller set its speed once,
    # stays at its start, as in Webots.
    assert seen["pusher_end"] == pytest.approx([-0.2, 0.0, 0.0], abs=1e-6)


def test_webots_8_names_revert_the_world_and_reset_its_physics(tmp_path: Path) -> None:
    # Webots 8's simulationRevert and simulationPhysicsReset, as its supervisors call them.
    supervisor = supervisor_of(tmp_path)
    box = supervisor.getFromDef("BOX")
    box.setVelocity([0.0, -0.5, 0.0, 0.0, 0.0, 0.0])
    supervisor.simulationPhysicsReset()
    assert box.getVelocity() == pytest.approx([0.0] * 6)
    push_the_box(supervisor)
    supervisor.simulationRevert()  # in a run of one controller: a reset, the controller goes on
    supervisor.step(32)
    assert simulations.current().simulator.pose == pytest.approx((0.0, 0.0, 0.0), abs=1e-6)
    assert box.getPosition() == pytest.approx([0.3, 0.3, 0.02], abs=1e-6)
    assert supervisor.getTime() == 0.0
