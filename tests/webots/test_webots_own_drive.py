"""A two-wheeled robot of its own build (a plain ``Robot`` whose two RotationalMotors, named as
its author likes, turn two HingeJoints, as Webots' tutorials build one) is simulated on its own
wheels: its wheel radius, axle, left and right by where its node puts them, its motors'
``maxVelocity`` and its body's radius, its own devices by their names and none of the e-puck's
(#32)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from mazesim.webots.importer import import_wbt_text
from mazesim.webots.lockstep import run_world
from mazesim_process import mazesim_command

pytestmark = pytest.mark.usefixtures("fresh_robot")

#: Webots' tutorial robot, as a swagatk/webots_tutorials world builds it: a 4.5 cm cylinder
#: body, wheels of 2.5 cm on anchors 4.5 cm either side, two distance sensors of its own.
WORLD = """#VRML_SIM R2025a utf8
WorldInfo { basicTimeStep 16 }
RectangleArena { floorSize 4 4 }
Robot {
  children [
    DistanceSensor { translation 0.04 0.015 0.02 rotation 0 0 1 0.26 name "ps_0" }
    DEF Body Pose {
      translation 0 0 0.0415
      children [ Shape { geometry Cylinder { height 0.08 radius BODY } } ]
    }
    HingeJoint {
      jointParameters HingeJointParameters { axis 0 AXIS 0 anchor 0 0.045 0.025 }
      device [ RotationalMotor { name "LEFT" MAXV } PositionSensor { name "wheel_enc_1" } ]
      endPoint Solid {
        translation 0 0.045 0.025 rotation 1 0 0 1.57
        children [ DEF wheel Shape { geometry Cylinder { height 0.01 radius 0.025 } } ]
        boundingObject USE wheel
        physics Physics { }
      }
    }
    HingeJoint {
      jointParameters HingeJointParameters { axis 0 1 0 anchor 0 -0.045 0.025 }
      device [ RotationalMotor { name "RIGHT" MAXV } PositionSensor { name "wheel_enc_2" } ]
      endPoint Solid {
        translation 0 -0.045 0.025 rotation 1 0 0 1.57
        children [ USE wheel ]
        name "wheel_2"
        boundingObject USE wheel
        physics Physics { }
      }
    }
  ]
  boundingObject USE Body
  physics Physics { }
  controller "drive"
}
"""

#: Sets the motors' speeds for 1 s (62 steps of 16 ms), printing which devices it has.
DRIVE = """from controller import Robot
robot = Robot()
for name in ("ps0", "camera", "left wheel motor", "ps_0", "wheel_enc_1", "LEFT", "RIGHT"):
    print("has", name, robot.getDevice(name) is not None)
left, right = robot.getDevice("LEFT"), robot.getDevice("RIGHT")
for motor, speed in ((left, SPD_A), (right, SPD_B)):
    motor.setPosition(float("inf"))
    motor.setVelocity(speed)
robot.getDevice("wheel_enc_1").enable(16)
for _ in range(62):
    robot.step(16)
print("encoder", robot.getDevice("wheel_enc_1").getValue())
"""


def world(
    tmp_path: Path,
    speeds: tuple[float, float],
    *,
    left: str = "motor_1",
    right: str = "motor_2",
    axis: str = "1",
    body: float = 0.045,
    max_velocity: str = "",
) -> str:
    """A project with the tutorial robot and its ``drive`` controller; the world's path."""
    text = WORLD.replace("LEFT", left).replace("RIGHT", right).replace("AXIS", axis)
    text = text.replace("BODY", str(body)).replace("MAXV", max_velocity)
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "tutorial.wbt").write_text(text)
    folder = tmp_path / "controllers" / "drive"
    folder.mkdir(parents=True)
    code = DRIVE.replace("SPD_A", str(speeds[0])).replace("SPD_B", str(speeds[1]))
    code = code.replace("LEFT", left).replace("RIGHT", right)
    (folder / "drive.py").write_text(code)
    return str(tmp_path / "worlds" / "tutorial.wbt")


def test_the_import_takes_a_hand_built_two_wheeler_for_the_robot_it_simulates() -> None:
    text = WORLD.replace("AXIS", "1").replace("BODY", "0.045").replace("MAXV", "")
    _, report = import_wbt_text(text, "tutorial.wbt")
    (robot,) = report["robots"]
    assert robot["profile"] == "e-puck" and robot["model"] == "Robot", robot
    assert not any("not an e-puck" in warning for warning in report["warnings"])


def test_it_rolls_on_its_own_wheels_with_only_its_own_devices(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    run = run_world(world(tmp_path, (2.0, 2.0)), seconds=1.2)
    (robot,) = run.robots
    assert robot.exit_status == 0, robot.error
    out = capfd.readouterr().out
    for name, held in [("ps0", False), ("camera", False), ("left wheel motor", False)]:
        assert f"has {name} {held}" in out
    for name in ("ps_0", "wheel_enc_1", "motor_1", "motor_2"):
        assert f"has {name} True" in out
    # 62 steps of 16 ms at 2 rad/s on wheels of 2.5 cm: 4.96 cm ahead (the e-puck's 2 cm
    # wheels would roll it 3.97 cm).
    x, y, heading = robot.final_pose
    assert x == pytest.approx(62 * 0.016 * 2.0 * 0.025, abs=2e-3), robot.final_pose
    assert abs(y) < 1e-3 and abs(heading) < 1e-3
    (line,) = [line for line in out.splitlines() if line.startswith("encoder")]
    assert float(line.split()[1]) == pytest.approx(62 * 0.016 * 2.0, abs=1e-6)


def test_it_turns_on_its_own_axle_left_and_right_by_where_its_wheels_sit(
    tmp_path: Path,
) -> None:
    # The motor named "a" turns the wheel at y = +4.5 cm, its left: a faster left wheel turns
    # the robot clockwise, at 0.025 * (1 - 3) / 0.09 rad/s (the e-puck's axle: 0.05685 m).
    run = run_world(world(tmp_path, (3.0, 1.0), left="a", right="b"), seconds=1.2)
    (robot,) = run.robots
    assert robot.exit_status == 0, robot.error
    turned = math.remainder(robot.final_pose[2], math.tau)
    assert turned == pytest.approx(62 * 0.016 * 0.025 * (1.0 - 3.0) / 0.09, rel=0.02)


def test_its_motors_max_velocity_is_its_own(tmp_path: Path) -> None:
    # maxVelocity 20: a speed of 15 rad/s is the motors' (the e-puck's 6.28 would hold it).
    path = world(tmp_path, (15.0, 15.0), max_velocity="maxVelocity 20")
    (robot,) = run_world(path, seconds=1.2).robots
    assert robot.final_pose[0] == pytest.approx(62 * 0.016 * 15.0 * 0.025, abs=1e-2)


def test_its_body_is_as_wide_as_its_bounding_object(tmp_path: Path) -> None:
    # A body of 15 cm radius driving 1.5 m at the arena's wall (2 m ahead) stops 15 cm short.
    path = world(tmp_path, (10.0, 10.0), body=0.15, max_velocity="maxVelocity 20")
    controller = tmp_path / "controllers" / "drive" / "drive.py"
    controller.write_text(controller.read_text().replace("range(62)", "range(600)"))
    (robot,) = run_world(path, seconds=10.0).robots
    assert robot.final_pose[0] == pytest.approx(2.0 - 0.15, abs=0.01), robot.final_pose


def test_wheels_whose_axis_points_right_are_refused_with_a_warning(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    # Its left hinge turns about 0 -1 0: a positive speed rolls that wheel backward in Webots,
    # which mazesim's robot does not do: the e-puck's wheels stand in, and a warning says so.
    (robot,) = run_world(world(tmp_path, (2.0, 2.0), axis="-1"), seconds=1.2).robots
    assert robot.exit_status == 0, robot.error
    err = capfd.readouterr().err
    assert "its own two wheels do not drive it" in err and "'motor_1'" in err
    assert robot.final_pose[0] == pytest.approx(62 * 0.016 * 2.0 * 0.02, abs=2e-3)


def test_a_y_up_robot_of_a_world_before_r2022a_rolls_on_its_own_wheels(tmp_path: Path) -> None:
    # Webots' NUE frame (R2021a): the body's forward is its -z, its left -x, up y; the wheels
    # turn about -1 0 0 (as the E-puck PROTO's of those releases), anchors 4.5 cm left and right.
    path = world(tmp_path, (2.0, 2.0))
    text = Path(path).read_text().replace("R2025a", "R2021a")
    text = text.replace("axis 0 1 0 anchor 0 0.045 0.025", "axis -1 0 0 anchor -0.045 0.025 0")
    text = text.replace("axis 0 1 0 anchor 0 -0.045 0.025", "axis -1 0 0 anchor 0.045 0.025 0")
    text = text.replace("translation 0 0 0.0415", "translation 0 0.0415 0")
    text = text.replace("translation 0 0.045 0.025", "translation -0.045 0.025 0")
    text = text.replace("translation 0 -0.045 0.025", "translation 0.045 0.025 0")
    Path(path).write_text(text.replace("Pose", "Transform"))
    (robot,) = run_world(path, seconds=1.2).robots
    assert robot.exit_status == 0, robot.error
    x, y, _ = robot.final_pose
    assert x == pytest.approx(62 * 0.016 * 2.0 * 0.025, abs=2e-3) and abs(y) < 1e-3


def test_a_run_of_its_controller_alone_rolls_it_alike(tmp_path: Path) -> None:
    path = world(tmp_path, (2.0, 2.0))
    controller = str(tmp_path / "controllers" / "drive" / "drive.py")
    result = mazesim_command(
        *("webots", "run", controller, "--world", path, "--seconds", "1.2", "--out", "out"),
        "--no-progress",
        cwd=tmp_path,
    )
    assert result.returncode == 0, result.stderr
    assert "a two-wheeled robot of its own build" in result.stderr
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["final_pose"][0] == pytest.approx(62 * 0.016 * 2.0 * 0.025, abs=2e-3), summary


def test_webots_mybot_with_the_e_puck_s_motor_names_rolls_on_its_own_wheels(
    tmp_path: Path,
) -> None:
    # Webots' MyBot (samples/devices): the E-puck's motor names, both hinges anchored on the
    # axle's midpoint, the wheels where their end points sit, 4.5 cm either side.
    path = world(tmp_path, (2.0, 2.0), left="left wheel motor", right="right wheel motor")
    text = Path(path).read_text().replace("anchor 0 0.045 0.025", "anchor 0 0 0.025")
    Path(path).write_text(text.replace("anchor 0 -0.045 0.025", "anchor 0 0 0.025"))
    _, report = import_wbt_text(Path(path).read_text(), "mybot.wbt")
    assert report["robot_model"] == "Robot" and report["robots"][0]["profile"] == "e-puck"
    (robot,) = run_world(path, seconds=1.2).robots
    assert robot.exit_status == 0, robot.error
    assert robot.final_pose[0] == pytest.approx(62 * 0.016 * 2.0 * 0.025, abs=2e-3)


def test_a_robot_with_the_e_puck_s_wheels_keeps_the_e_puck_profile(tmp_path: Path) -> None:
    # Wheels of 2 cm, 2.6 cm either side (the E-puck PROTO's, as an e-puck saved expanded has):
    # the e-puck profile's numbers, measured on Webots' E-puck, stand (it turns as an axle of
    # 0.05685 m, not the 0.052 m its anchors span).
    path = world(tmp_path, (-1.0, 1.0))
    text = Path(path).read_text().replace("0.045 0.025", "0.026 0.02").replace("radius 0.025", "")
    Path(path).write_text(text.replace("height 0.01", "height 0.01 radius 0.02"))
    (robot,) = run_world(path, seconds=1.2).robots
    assert robot.exit_status == 0, robot.error
    turned = math.remainder(robot.final_pose[2], math.tau)
    assert turned == pytest.approx(62 * 0.016 * 0.02 * 2.0 / 0.05685, rel=0.02)


def test_a_robot_with_a_ps0_of_its_own_still_rolls_on_its_own_wheels(tmp_path: Path) -> None:
    # Its sensor named ps0 makes it an e-puck by name (its model E-puck), not its wheels: they
    # are 2.5 cm, 9 cm apart, and roll it so.
    path = world(tmp_path, (2.0, 2.0))
    Path(path).write_text(Path(path).read_text().replace('name "ps_0"', 'name "ps0"'))
    _, report = import_wbt_text(Path(path).read_text(), "tutorial.wbt")
    assert report["robot_model"] == "E-puck"
    (robot,) = run_world(path, seconds=1.2).robots
    assert robot.final_pose[0] == pytest.approx(62 * 0.016 * 2.0 * 0.025, abs=2e-3)


def test_a_downward_sensor_is_as_high_as_the_robot_rests_on_its_wheels(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    """A line follower built on its axle (its origin 1.4 cm up, on wheels of that radius) with
    an infra-red sensor 5.4 mm below its origin looking down: 8.6 mm above the floor. Its
    height was read from the origin as if the origin were on the floor (5.4 mm below it: 0
    on white, always black)."""
    wheel = (
        "HingeJoint {{ jointParameters HingeJointParameters {{ axis 0 1 0 anchor 0 {y} 0 }} "
        'device [ RotationalMotor {{ name "{name}" }} ] endPoint Solid {{ translation 0 {y} 0 '
        "rotation 1 0 0 1.5708 children [ Shape {{ geometry Cylinder {{ height 0.011 radius "
        '0.014 }} }} ] name "{name}" boundingObject Cylinder {{ height 0.011 radius 0.014 }} '
        "physics Physics {{ }} }} }}\n"
    )
    text = (
        "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\nRectangleArena { }\n"
        "Robot { translation 0 0 0.014 children [\n"
        'DistanceSensor { translation 0.02 0 -0.0054 rotation 0 1 0 1.5708 name "down" '
        'type "infra-red" }\n'
        + wheel.format(y=0.0305, name="left")
        + wheel.format(y=-0.0305, name="right")
        + '] boundingObject Box { size 0.04 0.04 0.01 } physics Physics { } controller "down" }\n'
    )
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "down.wbt").write_text(text)
    (tmp_path / "controllers" / "down").mkdir(parents=True)
    (tmp_path / "controllers" / "down" / "down.py").write_text(
        "from controller import Robot\nr = Robot()\ns = r.getDevice('down')\ns.enable(32)\n"
        "r.step(32)\nprint('down', s.getValue())\n"
    )
    run = run_world(str(tmp_path / "worlds" / "down.wbt"), seconds=0.1, noise=False)
    assert run.robots[0].exit_status == 0, run.robots[0].error
    (line,) = [line for line in capfd.readouterr().out.splitlines() if line.startswith("down")]
    # Webots' default table [0 0 0, 0.1 1000 0] on a white floor: 8.6 mm reads 86.
    assert float(line.split()[1]) == pytest.approx(86.0, abs=0.5), line
