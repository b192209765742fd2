"""A supervisor sees and moves the world's Solids that are not robots: a box with physics (a
movable body) where the robot pushed it, and a static wall, which the robot's sensors and
contacts then meet where it was put (#33)."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from mazesim.webots import controller, import_wbt
from mazesim.webots import simulation as simulations
from mazesim.webots.lockstep import run_world
from supervised_world import WORLD, drive, front, project_of, run_test_world, supervisor_of

pytestmark = pytest.mark.usefixtures("fresh_robot")


def test_the_import_report_says_which_nodes_hold_each_obstacle_and_body(tmp_path: Path) -> None:
    path = tmp_path / "solids.wbt"
    path.write_text(WORLD)
    _, report = import_wbt(str(path))
    lines = WORLD.splitlines()
    gate = [o for o in report["obstacles"] if o["kind"] == "box" and o["size"][0] == 0.02]
    assert len(gate) == 1 and lines[gate[0]["owners"][-1] - 1].startswith("DEF GATE Solid")
    assert gate[0]["walls"][1] == 1
    (box,) = report["bodies"]
    assert [lines[line - 1].strip()[:13] for line in box["owners"]] == [
        "DEF PLACE Pos",
        "DEF BOX Solid",
    ]


def test_a_box_moved_in_front_of_the_robot_is_read_by_its_front_sensors(tmp_path: Path) -> None:
    supervisor = supervisor_of(tmp_path)
    gate = supervisor.getFromDef("GATE").getField("translation")
    gate.setSFVec3f([0.1, 0.6, 0.05])  # out of the way first
    box = supervisor.getFromDef("BOX")
    assert box.getPosition() == pytest.approx([0.3, 0.3, 0.02], abs=1e-6)
    clear = front(supervisor)
    # In the frame of the Pose that holds it, as Webots sets a translation.
    box.getField("translation").setSFVec3f([-0.225, -0.3, 0.02])
    assert box.getPosition() == pytest.approx([0.075, 0.0, 0.02], abs=1e-6)
    assert box.getField("translation").getSFVec3f() == pytest.approx([-0.225, -0.3, 0.02])
    seen = front(supervisor)
    assert seen > clear + 300.0, (clear, seen)
    # The Pose above it stays where it is.
    assert supervisor.getFromDef("PLACE").getPosition() == pytest.approx([0.3, 0.3, 0.0])


def test_a_pushed_box_is_where_the_robot_pushed_it(tmp_path: Path) -> None:
    supervisor = supervisor_of(tmp_path)
    supervisor.getFromDef("GATE").getField("translation").setSFVec3f([0.1, 0.6, 0.05])
    box = supervisor.getFromDef("BOX")
    box.getField("translation").setSFVec3f([-0.22, -0.3, 0.02])
    drive(supervisor, 6.0, 40)
    x, y, z = box.getPosition()
    pushed = simulations.current().simulator.body_poses()[0]
    assert (x, y) == pytest.approx(pushed[:2], abs=1e-6)
    assert x > 0.12 and z == pytest.approx(0.02)
    assert box.getField("translation").getSFVec3f() == pytest.approx([x - 0.3, y - 0.3, z])
    vx = box.getVelocity()[0]
    assert vx > 0.01, "pushed along x"
    box.resetPhysics()
    assert box.getVelocity() == pytest.approx([0.0] * 6)


def test_moving_a_static_wall_clears_the_way(tmp_path: Path) -> None:
    supervisor = supervisor_of(tmp_path)
    drive(supervisor, 6.0, 40)
    blocked = simulations.current().simulator.pose[0]
    assert blocked < 0.1 - 0.01 - 0.037 + 1e-3, "the gate stops the robot"
    gate = supervisor.getFromDef("GATE")
    gate.getField("rotation").setSFRotation([0, 0, 1, math.pi / 2])  # along x now: a thin rail
    gate.getField("translation").setSFVec3f([0.1, 0.3, 0.05])
    assert gate.getPosition() == pytest.approx([0.1, 0.3, 0.05])
    drive(supervisor, 6.0, 40)
    assert simulations.current().simulator.pose[0] > 0.15, "through where the gate stood"


def test_a_move_beyond_the_limits_is_refused_and_changes_nothing(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    supervisor = supervisor_of(tmp_path)
    gate = supervisor.getFromDef("GATE").getField("translation")
    gate.setSFVec3f([5000.0, 0.0, 0.05])
    assert "cannot be moved there" in capsys.readouterr().err
    assert gate.getSFVec3f() == pytest.approx([0.1, 0.0, 0.05])
    drive(supervisor, 6.0, 40)
    assert simulations.current().simulator.pose[0] < 0.06, "the gate still stands"


def _trial(tmp_path: Path) -> list[Any]:
    """A run with noise in which the supervisor moves the gate and the box mid-way: each step's
    pose and box position."""
    supervisor = supervisor_of(tmp_path, noise=True, seed=7)
    box = supervisor.getFromDef("BOX")
    record = []
    for step in range(60):
        if step == 20:
            supervisor.getFromDef("GATE").getField("translation").setSFVec3f([0.1, 0.5, 0.05])
            box.getField("translation").setSFVec3f([-0.21, -0.29, 0.02])
        drive(supervisor, 5.0 + step % 3, 1)
        record.append((simulations.current().simulator.pose, tuple(box.getPosition())))
    simulations.release()
    controller.Robot.created = None
    return record


def test_the_same_seed_gives_the_same_run(tmp_path: Path) -> None:
    first, second = _trial(tmp_path), _trial(tmp_path)
    assert np.array_equal(np.array(first, dtype=object), np.array(second, dtype=object))
    assert first[-1][1][0] > 0.1, "the box was pushed"


def test_a_supervisor_robot_moves_a_gate_and_a_box_of_a_world_of_several_robots(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    keeper, pusher = run_test_world("keeper.wbt", tmp_path, monkeypatch)
    seen = json.loads((tmp_path / "keeper.json").read_text())
    assert seen["box_start"] == pytest.approx([0.3, 0.3, 0.02], abs=1e-6)
    assert seen["box_placed"] == pytest.approx([-0.06, 0.0, 0.02], abs=1e-6)
    # The gate stopped the pusher until the keeper moved it, then it pushed the box.
    assert pusher.xs[19] < -0.12 - 0.01 - 0.037 + 1e-3
    assert pusher.final_pose[0] > -0.12
    assert seen["box_end"][0] > -0.06 + 0.02


def test_a_robot_kept_as_an_obstacle_that_moves_itself_takes_its_obstacle_along(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    slider, pusher = run_test_world("slider.wbt", tmp_path, monkeypatch)
    assert slider.final_pose[1] == pytest.approx(0.25, abs=1e-6)
    # Stopped by the slider's body until it slid away, then on past where it stood.
    assert pusher.xs[19] < -0.08 - 0.02 - 0.037 + 1e-3
    assert pusher.final_pose[0] > -0.08


def test_a_world_without_an_e_puck_answers_a_supervisor_about_its_ball(tmp_path: Path) -> None:
    """No simulator holds the movable bodies of a world whose robots are no e-pucks (they do
    not move): a supervisor reading a ball's velocity reads it at rest, as Webots' API never
    raises there, and its controller goes on (it stopped with an internal IndexError)."""
    text = (
        "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\nRectangleArena { }\n"
        "DEF BALL Solid { translation 0.2 0 0.04 children [ DEF B Shape { geometry Sphere "
        '{ radius 0.04 } } ] name "ball" boundingObject USE B physics Physics { mass 0.05 } }\n'
        'Robot { name "referee" controller "referee" supervisor TRUE }\n'
    )
    out = tmp_path / "velocity.txt"
    referee = (
        "from controller import Supervisor\nrobot = Supervisor()\nrobot.step(32)\n"
        f"open({str(out)!r}, 'w').write(repr(robot.getFromDef('BALL').getVelocity()))\n"
        "robot.step(32)\n"
    )
    world = project_of(tmp_path, "ball.wbt", text, {"referee": referee})
    run = run_world(str(world), seconds=0.2, seed=1)
    assert [robot.exit_status for robot in run.robots] == [0], run.robots
    assert out.read_text() == repr([0.0] * 6)


def test_a_robot_mazesim_does_not_simulate_keeps_its_height(tmp_path: Path) -> None:
    """A Robot that is no e-puck (its body does not move, as a Robot without physics in
    Webots) stands at the height the file gives and a supervisor sets: its ``translation`` and
    ``getPosition`` read it (they read 0); an e-puck's read 0, on the floor."""
    text = (
        "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\nRectangleArena { }\n"
        'DEF BOT Robot { translation 0.5 0.2 0.3 name "bot" controller "<none>" }\n'
        'DEF EP E-puck { translation -0.2 0 0 name "ep" controller "<none>" }\n'
        'Robot { name "sup" controller "sup" supervisor TRUE }\n'
    )
    out = tmp_path / "heights.json"
    sup = (
        "import json\nfrom controller import Supervisor\nrobot = Supervisor()\nrobot.step(32)\n"
        "bot, ep = robot.getFromDef('BOT'), robot.getFromDef('EP')\n"
        "seen = [bot.getField('translation').getSFVec3f(), bot.getPosition(), ep.getPosition()]\n"
        "bot.getField('translation').setSFVec3f([0.4, 0.1, 0.5])\nrobot.step(32)\n"
        "seen += [bot.getField('translation').getSFVec3f(), bot.getPosition()]\n"
        f"open({str(out)!r}, 'w').write(json.dumps(seen))\n"
    )
    world = project_of(tmp_path, "heights.wbt", text, {"sup": sup})
    run = run_world(str(world), seconds=0.2, seed=1)
    assert [robot.exit_status for robot in run.robots] == [0, 0, 0], run.robots
    field, position, e_puck, moved_field, moved = json.loads(out.read_text())
    assert field == position == pytest.approx([0.5, 0.2, 0.3])
    assert e_puck == pytest.approx([-0.2, 0.0, 0.0], abs=1e-6)
    assert moved_field == moved == pytest.approx([0.4, 0.1, 0.5])
