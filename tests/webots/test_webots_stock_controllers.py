"""A robot whose world file leaves its ``controller`` field out runs its PROTO's default
controller, as in Webots: the E-puck's ``e-puck_avoid_obstacles``, a Braitenberg avoider."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from mazesim.webots import stock_controllers
from mazesim.webots.lockstep import controller_name, controller_of, run_world
from mazesim_process import mazesim_command
from supervised_world import supervisor_in

#: Two e-pucks in an arena: one whose controller only steps, one that names no controller.
WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 1 1 }
E-puck { translation -0.3 0.3 0 name "still" controller "still" }
E-puck { translation 0 0 0 name "default" }
"""
STILL = """from controller import Robot
robot = Robot()
while robot.step(32) != -1:
    pass
"""


def test_a_node_without_a_controller_field_names_its_protos_default(tmp_path: Path) -> None:
    world = str(tmp_path / "worlds" / "w.wbt")
    robot = {"name": "e", "model": "E-puck", "controller": None}
    assert controller_name(robot) == "e-puck_avoid_obstacles"
    found, why = controller_of(robot, world, {})
    assert (found, why) == (stock_controllers.__file__, "")
    none, why = controller_of({**robot, "controller": ""}, world, {})
    assert none is None and why == "no controller", "an empty field names no controller"
    # A project's own controller of that name wins over Webots' stock one.
    own = tmp_path / "controllers" / "e-puck_avoid_obstacles" / "e-puck_avoid_obstacles.py"
    own.parent.mkdir(parents=True)
    own.write_text(STILL)
    assert controller_of(robot, world, {}) == (str(own), "")
    assert controller_name({"name": "r", "model": "Robot"}) == "", "no PROTO default"


def test_the_stock_avoider_turns_away_from_the_side_it_sees() -> None:
    assert stock_controllers.wheel_speeds([0.0] * 8) == pytest.approx((3.14, 3.14))
    right = stock_controllers.wheel_speeds([2000.0, 2000.0, 0, 0, 0, 0, 0, 0])
    left = stock_controllers.wheel_speeds([0, 0, 0, 0, 0, 0, 2000.0, 2000.0])
    # Webots' weights turn it left, away from an obstacle on the right and in front, and, as
    # its left wheel alone slows for ps6 and ps7, left for one on the left front too.
    assert right == pytest.approx(
        (3.14 - 2 * 2000 / 4096 * 1.3 * 6.28, 3.14 - 2 * 2000 / 4096 * 6.28)
    )
    assert right[0] < right[1] < 0, "close on the right front: it backs away turning left"
    assert left == pytest.approx((3.14 - 2 * 2000 / 4096 * 0.75 * 6.28, 3.14))
    assert max(abs(s) for s in stock_controllers.wheel_speeds([4096.0] * 8)) <= 6.28


def test_an_e_puck_without_a_controller_field_drives_in_a_world_run(tmp_path: Path) -> None:
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "w.wbt").write_text(WORLD)
    (tmp_path / "controllers" / "still").mkdir(parents=True)
    (tmp_path / "controllers" / "still" / "still.py").write_text(STILL)
    run = run_world(str(tmp_path / "worlds" / "w.wbt"), seconds=4.0, seed=1)
    still, default = run.robots
    assert Path(str(default.controller)).name == "stock_controllers.py"
    assert default.exit_status == 0, default.error
    assert still.distance_m < 1e-6
    # Half of full speed (3.14 rad/s, 0.063 m/s) ahead for 4 s, clear of the walls.
    assert 0.2 < default.distance_m < 0.26
    assert default.collisions == 0


def test_a_controller_given_with_its_world_runs_beside_the_protos_default(tmp_path: Path) -> None:
    """``webots run CONTROLLER --world WORLD.wbt``: an E-puck that leaves its controller field
    out runs e-puck_avoid_obstacles beside the given controller, as in Webots."""
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "w.wbt").write_text(WORLD)
    still = tmp_path / "controllers" / "still" / "still.py"
    still.parent.mkdir(parents=True)
    still.write_text(STILL)
    out = tmp_path / "run"
    result = mazesim_command(
        *("webots", "run", str(still), "--world", str(tmp_path / "worlds" / "w.wbt")),
        *("--seconds", "4", "--seed", "1", "--out", str(out)),
        cwd=tmp_path,
        env=dict(os.environ, MPLBACKEND="Agg"),
    )
    assert result.returncode == 0, result.stderr
    summary = json.loads((out / "summary.json").read_text())
    ran = {robot["name"]: robot for robot in summary["robots"]}
    assert Path(ran["still"]["controller"]) == still, "the given controller, on its robot"
    assert ran["still"]["distance_m"] < 1e-6
    assert Path(ran["default"]["controller"]).name == "stock_controllers.py"
    assert 0.2 < ran["default"]["distance_m"] < 0.26, "the PROTO's default drove it"


def test_with_keys_a_controller_given_with_its_world_still_runs_alone(tmp_path: Path) -> None:
    from argparse import Namespace

    from mazesim.cli.webots_world import whole_world_run

    (tmp_path / "worlds").mkdir()
    world = tmp_path / "worlds" / "w.wbt"
    world.write_text(WORLD)
    still = str(tmp_path / "still.py")
    args = Namespace(controller=still, world=str(world), keys=None, strict=False)
    whole = whole_world_run(args, still)
    assert whole is not None and whole.controller == str(world) and whole.world is None
    assert whole.robot_controller == [f"still={still}"], "named by its controller field"
    assert whole_world_run(Namespace(**{**vars(args), "keys": "k.txt"}), still) is None
    assert whole_world_run(Namespace(**{**vars(args), "strict": True}), still) is None
    alone = tmp_path / "worlds" / "alone.wbt"
    alone.write_text(WORLD.replace('E-puck { translation 0 0 0 name "default" }\n', ""))
    assert whole_world_run(Namespace(**{**vars(args), "world": str(alone)}), still) is None


def test_the_stock_controller_lacks_nothing() -> None:
    """The modules beside mazesim's stock controller are mazesim's own, not the controller's:
    its run says of no missing feature that they name."""
    from mazesim.webots.requirements import prepare_controller

    prepared = prepare_controller(stock_controllers.__file__)
    assert prepared.missing == [] and prepared.runnable


def test_the_e_pucks_default_controller_is_the_cores_name_everywhere() -> None:
    from mazesim._core import EPUCK_DEFAULT_CONTROLLER
    from mazesim.webots.proto_fields import declared_fields

    assert EPUCK_DEFAULT_CONTROLLER == "e-puck_avoid_obstacles"
    assert declared_fields("E-puck").strings["controller"] == EPUCK_DEFAULT_CONTROLLER
    assert (
        stock_controllers.stock_controller(EPUCK_DEFAULT_CONTROLLER) == stock_controllers.__file__
    )


def test_an_unnamed_e_puck_is_called_by_its_protos_default_name() -> None:
    from mazesim.webots.proto_fields import robot_label

    unnamed = {"model": "E-puck", "name": None, "def_name": "EPUCK_1"}
    # Webots names a robot by its `name` field, whose default the PROTO declares: its DEF name
    # is no name a controller or a summary sees.
    assert robot_label(unnamed) == "e-puck"
    assert robot_label(dict(unnamed, model="e-puck2")) == "e-puck"
    assert robot_label(dict(unnamed, name="scout")) == "scout"
    assert robot_label({"model": "Pioneer3dx", "name": None, "def_name": "P3"}) == "P3"


def test_e_pucks_sharing_the_default_name_are_told_apart_by_def_or_index() -> None:
    from mazesim.webots.lockstep import RobotRun, _tell_apart
    from mazesim.webots.proto_fields import robot_label

    robots = [
        {"model": "E-puck", "name": None, "def_name": "A"},
        {"model": "E-puck", "name": None, "def_name": None},
        {"model": "E-puck", "name": "scout", "def_name": "S"},
    ]
    runs = [RobotRun(i, robot_label(r), "E-puck", None, "") for i, r in enumerate(robots)]
    _tell_apart(runs, robots)
    assert [run.name for run in runs] == ["A", "e-puck(1)", "scout"]
    alone = [RobotRun(0, robot_label(robots[0]), "E-puck", None, "")]
    _tell_apart(alone, robots[:1])
    assert alone[0].name == "e-puck"


#: An e-puck saved expanded (a plain ``Robot`` with the e-puck's devices) that names no
#: controller, beside one that does: Webots runs ``<generic>`` on the first, which runs nothing.
PLAIN_WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 1 1 }
E-puck { translation -0.3 0.3 0 name "still" controller "still" }
Robot {
  translation 0 0 0
  children [
    DistanceSensor { translation 0.03 -0.01 0.033 rotation 0 0 1 -0.3 name "ps0" }
    HingeJoint { device [ RotationalMotor { name "left wheel motor" } ]
      endPoint Solid { translation 0 0.026 0.02 } }
    HingeJoint { device [ RotationalMotor { name "right wheel motor" } ]
      endPoint Solid { translation 0 -0.026 0.02 } }
  ]
  name "plain"
  model "GCtronic e-puck"
}
"""


def test_a_plain_robot_e_puck_without_a_controller_field_runs_webots_generic(
    tmp_path: Path,
) -> None:
    """A public course world's e-puck saved expanded drove about as the E-puck PROTO's default
    avoider would, where Webots runs a plain Robot node's default, ``<generic>``: nothing."""
    plain = {"name": "p", "model": "E-puck", "controller": None, "node_type": "Robot"}
    assert controller_name(plain) == "<generic>"
    assert controller_name({**plain, "node_type": "E-puck"}) == "e-puck_avoid_obstacles"
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "w.wbt").write_text(PLAIN_WORLD)
    (tmp_path / "controllers" / "still").mkdir(parents=True)
    (tmp_path / "controllers" / "still" / "still.py").write_text(STILL)
    run = run_world(str(tmp_path / "worlds" / "w.wbt"), seconds=2.0, seed=1)
    assert [r.name for r in run.robots] == ["still", "plain"]
    assert run.robots[1].controller is None
    assert run.robots[1].distance_m < 1e-6


def test_a_plain_robot_supervisor_reads_its_own_controller_field_as_generic(
    tmp_path: Path,
) -> None:
    text = PLAIN_WORLD.replace('model "GCtronic e-puck"', 'model "GCtronic e-puck" supervisor TRUE')
    robot = supervisor_in(tmp_path, text, robot="Robot {")
    assert robot.getSelf().getField("controller").getSFString() == "<generic>"
