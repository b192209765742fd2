"""An imported E-puck's body starts and stops as its wheels' friction allows (issue #32).

Webots' E-puck motors reach their speed at once, but the body is moved by the wheels' friction
on the floor: a full-speed turn in place takes about 10 ms to start, more than an 8 ms basic time
step (see ``mazesim.webots.traction``). A controller that turns toward a heading window narrower
than one step's turn relies on it. mazesim's own worlds keep their kinematic robots. The
figures of docs/webots.md's paragraph on it are these tests'.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

import mazesim
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.requirements import motor_limits, prepare_controller
from mazesim.webots.scene import read_scene
from mazesim.webots.traction import epuck_traction
from mazesim_process import mazesim_command

#: Webots' simulated e-puck (the ``e-puck`` profile): wheel radius, effective wheel distance.
RADIUS, AXLE, TOP = 0.02, 0.05685, 6.28


def test_a_turn_in_place_from_rest_takes_more_than_one_8_ms_step_to_start() -> None:
    traction = epuck_traction("1", RADIUS, AXLE, TOP)
    kinematic = RADIUS * 2 * TOP / AXLE
    left, right = traction.drive(-TOP, TOP, 0.008)
    first = RADIUS * (right - left) / AXLE
    # The friction allows about 430 rad/s^2: 3.5 rad/s at the step's end, which ODE's step
    # moves the body by.
    assert 0.75 * kinematic < first < 0.82 * kinematic
    assert traction.turn_rate == pytest.approx(0.008 * 433, rel=0.02)
    # At that rate the full turn rate takes about 10 ms to reach; the first step turns 1.6 deg.
    assert kinematic / (traction.turn_rate / 0.008) == pytest.approx(0.010, abs=0.0005)
    assert math.degrees(first * 0.008) == pytest.approx(1.6, abs=0.05)
    for _ in range(3):
        left, right = traction.drive(-TOP, TOP, 0.008)
    assert (left, right) == pytest.approx((-TOP, TOP))
    # Reversing the turn goes through rest: the first step of the reversal still turns forward.
    left, right = traction.drive(TOP, -TOP, 0.008)
    assert right > left


def test_a_full_speed_start_takes_two_8_ms_steps_and_any_change_one_32_ms_step() -> None:
    traction = epuck_traction("1", RADIUS, AXLE, TOP)
    speeds = [traction.drive(TOP, TOP, 0.008) for _ in range(2)]
    assert speeds[0][0] < TOP and speeds[0] == pytest.approx((speeds[0][1], speeds[0][0]))
    assert speeds[1] == pytest.approx((TOP, TOP))
    # At Webots' default 32 ms the friction allows any change within the step: a reversal of
    # a full-speed turn is made at once, so a 32 ms world moves as a kinematic one.
    traction.stop()
    assert (traction.speed, traction.turn_rate) == (0.0, 0.0)
    assert traction.drive(-TOP, TOP, 0.032) == pytest.approx((-TOP, TOP))
    assert traction.drive(TOP, -TOP, 0.032) == pytest.approx((TOP, -TOP))
    # Commands past the motors' limit are clamped first, as Webots' motors clamp them.
    assert traction.drive(50.0, 50.0, 0.032) == pytest.approx((TOP, TOP))


def test_only_an_e_puck_proto_with_physics_has_traction() -> None:
    assert read_scene("#VRML_SIM R2023b utf8\nE-puck { }\n").traction_version == "1"
    assert read_scene('#VRML_SIM R2023b utf8\nE-puck { version "2" }\n').traction_version == "2"
    kinematic = read_scene("#VRML_SIM R2023b utf8\nE-puck { kinematic TRUE }\n")
    assert kinematic.traction_version is None
    assert read_scene("#VRML_SIM R2023b utf8\nEPuck { }\n").traction_version is None


def turned_in_first_step(scene_text: str | None) -> float:
    """Yaw (rad) turned in the first 8 ms step of a full-speed turn in place from rest."""
    world = mazesim.World.from_toml(
        'format = "mazesim-world"\nversion = 1\nbasic_time_step_ms = 8\n', "open.toml"
    )
    scene = None if scene_text is None else read_scene(scene_text)
    prepare(world, seconds=1.0, noise=False, scene=scene)
    controller.Robot.created = None
    robot = controller.Robot()
    for name, speed in (("left wheel motor", -TOP), ("right wheel motor", TOP)):
        motor = robot.getDevice(name)
        motor.setPosition(float("inf"))
        motor.setVelocity(speed)
    before = simulations.current().simulator.pose[2]
    robot.step(8)
    turned = float(simulations.current().simulator.pose[2]) - float(before)
    simulations.release()
    return turned


def test_an_imported_e_puck_turns_less_in_its_first_step_than_a_mazesim_world_s() -> None:
    kinematic = turned_in_first_step(None)
    assert kinematic == pytest.approx(RADIUS * 2 * TOP / AXLE * 0.008, rel=1e-5)
    imported = turned_in_first_step("#VRML_SIM R2023b utf8\nE-puck { }\n")
    assert 0.75 * kinematic < imported < 0.82 * kinematic


#: Turns in place at full speed for one 8 ms step, then ends.
TURN_ONE_STEP = """from controller import Robot
robot = Robot()
for name, speed in (("left wheel motor", -6.28), ("right wheel motor", 6.28)):
    motor = robot.getDevice(name)
    motor.setPosition(float("inf"))
    motor.setVelocity(speed)
robot.step(8)
"""


def test_every_e_puck_of_a_world_of_several_has_its_own_traction(tmp_path: Path) -> None:
    """In a world run (each robot's controller in its own process, in lockstep) each imported
    E-puck's first step turns as that robot's PROTO would alone: a kinematic one by the whole
    kinematic turn, an e-puck and an e-puck2 by what their own masses' friction allows."""
    from mazesim.webots.lockstep import run_world

    robots = {
        "stiff": "kinematic TRUE",
        "one": "",
        "two": 'version "2"',
    }
    header = "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 8 }\n"
    nodes = [
        f'E-puck {{ translation {0.3 * k} 0 0 name "{name}" controller "turn" {fields} }}\n'
        for k, (name, fields) in enumerate(robots.items())
    ]
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "turns.wbt").write_text(header + "".join(nodes))
    (tmp_path / "controllers" / "turn").mkdir(parents=True)
    (tmp_path / "controllers" / "turn" / "turn.py").write_text(TURN_ONE_STEP)
    run = run_world(str(tmp_path / "worlds" / "turns.wbt"), seconds=0.1, noise=False)
    turned = {robot.name: robot.final_pose[2] for robot in run.robots}
    for name, fields in robots.items():
        alone = turned_in_first_step(f"{header}E-puck {{ {fields} }}\n")
        assert turned[name] == pytest.approx(alone, abs=1e-6), name
    assert turned["stiff"] == pytest.approx(turned_in_first_step(None), abs=1e-6)
    assert turned["two"] < turned["one"] < 0.82 * turned["stiff"]


#: An R2020a (Y-up) world: an unturned e-puck with a Compass in its turret slot.
NUE_COMPASS_WORLD = """#VRML_SIM R2020a utf8
WorldInfo { basicTimeStep 8 }
RectangleArena { floorSize 1 1 }
E-puck {
  translation 0 0 -0.1
  controller "probe"
  turretSlot [ Compass { } ]
}
"""

#: Prints the compass's first reading.
COMPASS_PROBE = """from controller import Robot
robot = Robot()
compass = robot.getDevice("compass")
compass.enable(8)
robot.step(8)
print("north:", " ".join(f"{v:.4f}" for v in compass.getValues()))
"""


def test_a_compass_in_the_turret_of_a_y_up_e_puck_reads_north_in_its_own_frame(
    tmp_path: Path,
) -> None:
    # In a world before R2022a north is the world's x; an unturned device's frame is the
    # world's, so it reads (1, 0, 0), whatever the import reports of its x axis.
    (tmp_path / "probe.py").write_text(COMPASS_PROBE)
    (tmp_path / "world.wbt").write_text(NUE_COMPASS_WORLD)
    result = mazesim_command(
        *("webots", "run", "probe.py", "--world", "world.wbt", "--seconds", "0.1"),
        *("--out", "out", "--no-progress"),
        cwd=tmp_path,
    )
    assert result.returncode == 0, result.stderr
    line = next(x for x in result.stdout.splitlines() if x.startswith("north:"))
    north = [float(v) for v in line.split()[1:]]
    assert north == pytest.approx([1.0, 0.0, 0.0], abs=1e-3)
    assert math.atan2(north[0], north[2]) == pytest.approx(math.pi / 2, abs=1e-3)


def test_a_controller_that_limits_its_motors_is_told_at_its_start(tmp_path: Path) -> None:
    (tmp_path / "ramp.py").write_text(
        "from controller import Robot\nrobot = Robot()\n"
        "robot.getDevice('left wheel motor').setAvailableTorque(0.1)\n"
        "robot.getDevice('left wheel motor').setAcceleration(2.0)\n"
    )
    prepared = prepare_controller(str(tmp_path / "ramp.py"))
    assert prepared.runnable
    # A motor's acceleration is modelled (tests/webots/test_webots_device_calls.py), its torque
    # limit is not.
    assert [m for m in prepared.missing if m.startswith("motor torque")] == [
        "motor torque limits (setAvailableTorque): mazesim's wheels reach their commanded speed "
        "as Webots' motors do at full torque (with none, 0, they do not drive, as in Webots); "
        "only the floor's friction limits how fast an imported E-puck's body starts"
    ]
    (tmp_path / "ramp.c").write_text(
        "#include <webots/motor.h>\n"
        "void f(WbDeviceTag m) { wb_motor_set_available_torque (m, 1); }\n"
    )
    assert motor_limits(str(tmp_path / "ramp.c"), "c") == ["wb_motor_set_available_torque"]
    (tmp_path / "plain.py").write_text("from controller import Robot\nrobot = Robot()\n")
    (tmp_path / "ramp.py").unlink()
    assert prepare_controller(str(tmp_path / "plain.py")).missing == []


def test_a_differential_wheels_e_puck_of_webots_8_keeps_its_kinematic_wheels() -> None:
    assert read_scene("#VRML_SIM V8.6 utf8\nE-puck { }\n").traction_version is None
    assert read_scene("#VRML_SIM R2018a utf8\nE-puck { }\n").traction_version == "1"


#: Spins its e-puck in place at full speed until the run ends.
SPIN = TURN_ONE_STEP.replace("robot.step(8)\n", "while robot.step(8) != -1:\n    pass\n")

#: Lets the spinner reach full turn rate, puts it back at the origin facing +x, and writes its
#: yaw after each of the next two steps to the file in SPIN_LOG.
PUT_BACK = """import json, os
from controller import Supervisor
robot = Supervisor()
spinner = robot.getFromDef("SPINNER")
for _ in range(10):
    robot.step(8)
spinner.getField("translation").setSFVec3f([0.0, 0.0, 0.0])
spinner.getField("rotation").setSFRotation([0.0, 0.0, 1.0, 0.0])
yaws = []
for _ in range(2):
    robot.step(8)
    x, y, z, angle = spinner.getField("rotation").getSFRotation()
    yaws.append(z * angle)
with open(os.environ["SPIN_LOG"], "w") as handle:
    json.dump(yaws, handle)
"""


def test_an_e_puck_a_supervisor_puts_elsewhere_starts_again_from_rest(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """In a world run, a spinning E-puck that another robot's supervisor puts back at a pose
    turns in its next step only what friction allows from rest, as a run of one robot whose
    own supervisor moves it does; the step after, it turns more."""
    from mazesim.webots.lockstep import run_world

    header = "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 8 }\n"
    (tmp_path / "worlds").mkdir()
    (tmp_path / "worlds" / "spin.wbt").write_text(
        header
        + 'DEF SPINNER E-puck { name "spinner" controller "spin" }\n'
        + 'Robot { translation 0.5 0.5 0 name "referee" controller "put_back" supervisor TRUE }\n'
    )
    for name, text in (("spin", SPIN), ("put_back", PUT_BACK)):
        (tmp_path / "controllers" / name).mkdir(parents=True)
        (tmp_path / "controllers" / name / f"{name}.py").write_text(text)
    log = tmp_path / "yaws.json"
    monkeypatch.setenv("SPIN_LOG", str(log))
    run = run_world(str(tmp_path / "worlds" / "spin.wbt"), seconds=0.2, noise=False)
    assert [robot.exit_status for robot in run.robots] == [0, 0], run.robots[1].error
    first, second = json.loads(log.read_text())
    from_rest = turned_in_first_step(header + "E-puck { }\n")
    assert first == pytest.approx(from_rest, abs=1e-6)
    assert first < 0.82 * turned_in_first_step(None) < second - first
