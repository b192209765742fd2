"""Worlds as Webots users keep them (a referee robot beside the e-puck, files of R2019 with a
byte-order mark and Windows line endings, ``#`` inside strings), run through
``mazesim webots run`` in a subprocess or read as the command reads them."""

from __future__ import annotations

import math
import subprocess
from pathlib import Path

import pytest

import mazesim
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.devices import discretize
from mazesim.webots.importer import import_wbt, import_wbt_text
from mazesim.webots.scene import read_scene
from mazesim_process import mazesim_command

#: A competition-style world: a supervisor ``Robot`` (the referee) comes before the e-puck.
REFEREE_WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 16 }
RectangleArena { floorSize 1 1 }
DEF REFEREE Robot {
  name "referee"
  controller "referee"
  controllerArgs [ "--referee" ]
  supervisor TRUE
}
DEF EPUCK E-puck {
  translation -0.2 0.1 0
  name "my e-puck"
  controllerArgs [ "left" "3.5" ]
  customData "team #2"
}
"""

#: Prints what the robot knows of itself.
WHO_AM_I = """import sys
from controller import Robot

robot = Robot()
print("name:", robot.getName())
print("args:", sys.argv[1:])
print("supervisor:", robot.getSupervisor())
print("data:", robot.getCustomData())
robot.step(16)
"""


def run_webots(
    folder: Path,
    controller_text: str,
    world_text: str,
    *options: str,
    controller: str = "controller.py",
) -> subprocess.CompletedProcess[str]:
    """Runs a controller (written as ``controller``) in a world for 1 s (exit status 0
    expected)."""
    (folder / controller).write_text(controller_text)
    (folder / "world.wbt").write_bytes(world_text.encode("utf-8"))
    result = mazesim_command(
        *("webots", "run", controller, *options, "--world", "world.wbt", "--seconds", "1"),
        *("--out", "out", "--no-progress"),
        cwd=folder,
    )
    assert result.returncode == 0, result.stderr
    return result


def test_a_referee_robot_before_the_e_puck_lends_it_nothing(tmp_path: Path) -> None:
    out = run_webots(tmp_path, WHO_AM_I, REFEREE_WORLD).stdout
    assert "name: my e-puck" in out
    assert "args: ['left', '3.5']" in out
    assert "supervisor: False" in out
    assert "data: team #2" in out


def test_the_supervisors_self_is_the_e_puck_not_the_referee(tmp_path: Path) -> None:
    # The e-puck a supervisor too, as Webots needs it to be for its controller's look-ups.
    text = REFEREE_WORLD.replace('"team #2"\n', '"team #2"\n  supervisor TRUE\n')
    world_file = tmp_path / "world.wbt"
    world_file.write_text(text)
    world, report = import_wbt(str(world_file))
    assert report["robot_line"] == 10
    scene = read_scene(text, report["robot_model"], report["robot_line"])
    assert (scene.robot_def, scene.robot_name, scene.supervisor) == ("EPUCK", "my e-puck", True)
    assert [node.def_name for node in scene.nodes if node.robot] == ["EPUCK"]
    prepare(world, seconds=1.0, noise=False, report=report, scene=scene)
    controller.Robot.created = None
    supervisor = controller.Supervisor()
    assert supervisor.getSelf().getDef() == "EPUCK"
    assert supervisor.getFromDef("EPUCK") is supervisor.getSelf()
    referee = supervisor.getFromDef("REFEREE")
    assert referee is not supervisor.getSelf() and referee.getTypeName() == "Robot"
    simulations.release()


#: An R2019b world (NUE, y up) saved on Windows: a byte-order mark and CR LF line endings.
R2019_WORLD = (
    "\ufeff#VRML_SIM R2019b utf8\r\n"
    "WorldInfo {\r\n  basicTimeStep 16\r\n}\r\n"
    "RectangleArena { floorSize 2 1.5 }\r\n"
    "PointLight { location 0.5 0.3 -0.2 }\r\n"
    "DEF W1 Solid {\r\n"
    "  translation 0.3 0.05 0.1\r\n"
    "  rotation 0 1 0 0.7\r\n"
    "  children [ DEF WALL_SHAPE Shape { geometry Box { size 0.5 0.1 0.02 } } ]\r\n"
    "  boundingObject USE WALL_SHAPE\r\n"
    "}\r\n"
    'E-puck { translation -0.5 0 0 controllerArgs "--speed 3" }\r\n'
)


def test_an_r2019_world_with_a_byte_order_mark_is_read_in_its_nue_frame(tmp_path: Path) -> None:
    world_file = tmp_path / "old.wbt"
    world_file.write_bytes(R2019_WORLD.encode("utf-8"))
    world, report = import_wbt(str(world_file))
    scene = read_scene(world_file.read_text(encoding="utf-8"), report["robot_model"])
    assert scene.nue, "the header after the byte-order mark says R2019b"
    assert scene.controller_args == ["--speed", "3"]
    # The supervisor's view of the wall and the imported wall agree (Webots' converter's map).
    wall = next(node for node in scene.nodes if node.def_name == "W1")
    imported = [o for o in report["obstacles"] if o["size"] == pytest.approx([0.02, 0.5])]
    assert len(imported) == 1
    assert wall.translation is not None
    assert wall.translation[:2] == pytest.approx(imported[0]["center"])
    assert wall.translation == pytest.approx((-0.1, -0.3, 0.05))
    # The robot too: its start and its node.
    robot = next(node for node in scene.nodes if node.robot)
    assert robot.translation is not None and report["robot"] is not None
    assert robot.translation[:2] == pytest.approx((report["robot"]["x"], report["robot"]["y"]))
    assert scene.lights[0].position == pytest.approx((0.2, -0.5, 0.3))


def test_a_gps_of_an_nue_world_reads_the_world_files_own_coordinates() -> None:
    world = mazesim.load_world("arena")
    gps_entry = {"type": "GPS", "name": "gps", "translation": [0.0, 0.0, 0.0]}
    scene = read_scene("#VRML_SIM R2020b utf8\nE-puck { translation -0.2 0 0.1 }\n")
    prepare(world, seconds=1.0, noise=False, report={"extension_devices": [gps_entry]}, scene=scene)
    controller.Robot.created = None
    robot = controller.Robot()
    gps = robot.getDevice("gps")
    gps.enable(32)
    # The robot where the importer puts that E-puck: (x, y, z) -> (-z, -x, y).
    simulations.current().move_robot(-0.1, 0.2, 0.0)
    robot.step(32)
    assert gps.getValues() == pytest.approx([-0.2, 0.0, 0.1], abs=1e-6)
    simulations.release()


def test_a_gps_in_the_turret_slot_reads_its_height() -> None:
    text = "#VRML_SIM R2023b utf8\nE-puck { turretSlot [ GPS { } ] }\n"
    world, report = import_wbt_text(text, "turret.wbt")
    prepare(world, seconds=1.0, noise=False, report=report, scene=read_scene(text))
    controller.Robot.created = None
    robot = controller.Robot()
    gps = robot.getDevice("gps")
    gps.enable(32)
    robot.step(32)
    # The E-puck PROTO's turret slot is 48.6 mm up and 9.5 mm behind the robot's centre.
    assert gps.getValues() == pytest.approx([-0.0095, 0.0, 0.0486], abs=1e-6)
    simulations.release()


def test_a_hash_inside_a_string_is_no_comment() -> None:
    scene = read_scene(
        '#VRML_SIM R2023b utf8\nE-puck {\n  name "e-puck #1"  # the first one\n'
        '  controllerArgs [ "--colour" "#ff0000" ]\n}\n'
    )
    assert scene.robot_name == "e-puck #1"
    assert scene.controller_args == ["--colour", "#ff0000"]


def test_a_robot_of_a_project_proto_is_found_on_its_line() -> None:
    # The import names a project's own e-puck PROTO by the robot it stands in for, E-puck: the
    # robot on the report's line is that node all the same, with its own name.
    text = (
        '#VRML_SIM R2022a utf8\nRobot {\n  name "supervisor"\n  supervisor TRUE\n}\n'
        'DEF e-puck(1) epuck_custom {\n  name "e-puck(1)"\n  controller "e-puck"\n}\n'
    )
    scene = read_scene(text, robot_model="E-puck", robot_line=6)
    assert (scene.robot_name, scene.robot_def) == ("e-puck(1)", "e-puck(1)")
    assert not scene.supervisor, "the supervisor is another robot"


def test_strict_accepts_an_e_puck_with_its_ground_sensors_module(tmp_path: Path) -> None:
    world = (
        "#VRML_SIM R2023b utf8\n"
        "WorldInfo { basicTimeStep 16 }\n"
        "RectangleArena { floorSize 1 1 }\n"
        "E-puck { groundSensorsSlot [ E-puckGroundSensors { } ] }\n"
    )
    reads_ground = (
        "from controller import Robot\n"
        "robot = Robot()\n"
        "gs = [robot.getDevice(f'gs{i}') for i in range(3)]\n"
        "for sensor in gs:\n"
        "    sensor.enable(16)\n"
        "robot.step(16)\n"
        "print('ground', [round(sensor.getValue()) for sensor in gs])\n"
    )
    result = run_webots(tmp_path, reads_ground, world, "--strict", "--no-noise")
    assert "mazesim: warning" not in result.stderr
    assert "ground [856, 856, 856]" in result.stdout


def test_devices_of_a_world_before_r2022a_read_in_the_y_up_protos_frames() -> None:
    # The E-puck of R2021 and before is a Y-up PROTO: its accelerometer reads gravity along y,
    # its gyro the yaw rate about y; north defaults to the world's x (NUE), and a compass
    # reads it in the device frame x right, y up, z back.
    scene = read_scene("#VRML_SIM R2021b utf8\nE-puck { }\n")
    assert scene.y_up_devices and scene.north == pytest.approx((0.0, -1.0))
    # As the import reports an unturned device of a Y-up PROTO: its x axis is the robot's right.
    compass_entry = {
        "type": "Compass",
        "name": "compass",
        "translation": [0.0, 0.0, 0.03],
        "yaw": -math.pi / 2,
    }
    report = {"extension_devices": [compass_entry]}
    prepare(mazesim.load_world("arena"), seconds=2.0, noise=False, report=report, scene=scene)
    controller.Robot.created = None
    robot = controller.Robot()
    devices = [robot.getDevice(name) for name in ("accelerometer", "gyro", "compass")]
    for device in devices:
        device.enable(32)
    robot.step(32)
    accelerometer, gyro, compass = (device.getValues() for device in devices)
    assert accelerometer == pytest.approx([0.0, 9.81, 0.0])
    # Facing the start's -z (west in NUE), north is on the robot's right: +x.
    assert compass == pytest.approx([1.0, 0.0, 0.0], abs=1e-9)
    left, right = robot.getDevice("left wheel motor"), robot.getDevice("right wheel motor")
    for motor, speed in ((left, -2.0), (right, 2.0)):
        motor.setPosition(float("inf"))
        motor.setVelocity(speed)
    robot.step(32)
    robot.step(32)
    spin = gyro_table_rate(robot.getDevice("gyro").getValues())
    assert spin[0] == pytest.approx(0.0) and spin[2] == pytest.approx(0.0)
    assert spin[1] > 0.5, "turning left (counter-clockwise seen from above) about +y"
    simulations.release()


#: An e-puck of R2021a with a compass in its groundSensorsSlot, half a turn about the slot's y
#: axis (a swarm project reads its robots' headings so).
GROUND_SLOT_COMPASS = """#VRML_SIM R2021a utf8
WorldInfo { coordinateSystem "NUE" }
RectangleArena { floorSize 1 1 }
E-puck {
  groundSensorsSlot [ Compass { rotation 0 1 0 3.14159 } ]
}
"""


def test_a_compass_turned_down_in_the_ground_slot_reads_in_its_own_frame() -> None:
    # The slot's frame is a quarter turn down from the robot's: the compass's x axis points up,
    # its y axis to the robot's right and its z axis forward, so Webots reads north (the NUE
    # world's x, the unturned robot's right) on y, and on -z once the robot faces north's left.
    world, report = import_wbt_text(GROUND_SLOT_COMPASS, "compass.wbt")
    scene = read_scene(GROUND_SLOT_COMPASS, report.get("robot_model"), report.get("robot_line"))
    prepare(world, seconds=2.0, noise=False, report=report, scene=scene)
    controller.Robot.created = None
    robot = controller.Robot()
    compass = robot.getDevice("compass")
    compass.enable(32)
    robot.step(32)
    assert compass.getValues() == pytest.approx([0.0, 1.0, 0.0], abs=1e-3)
    simulations.current().move_robot(0.0, 0.0, math.pi / 2)
    robot.step(32)
    assert compass.getValues() == pytest.approx([0.0, 0.0, -1.0], abs=1e-3)
    simulations.release()


def gyro_table_rate(values: list[float]) -> list[float]:
    """The E-puck gyro's raw counts back in rad/s (its table: 13.315805 rad/s -> 100000)."""
    return [v * 13.315805 / 100000.0 for v in values]


def test_an_r2023_world_keeps_the_enu_device_frames() -> None:
    scene = read_scene("#VRML_SIM R2023b utf8\nE-puck { }\n")
    assert not scene.y_up_devices and scene.north is None
    prepare(mazesim.load_world("arena"), seconds=1.0, noise=False, scene=scene)
    controller.Robot.created = None
    robot = controller.Robot()
    accelerometer = robot.getDevice("accelerometer")
    accelerometer.enable(32)
    robot.step(32)
    assert accelerometer.getValues() == pytest.approx([0.0, 0.0, 9.81])
    simulations.release()


#: An E-puck as Webots saves it after a run: its wheel joints' positions in hidden fields.
SAVED_EPUCK = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
RectangleArena { floorSize 1 1 }
E-puck {
  hidden position_0_0 12.3
  hidden position_0_1 -3.2
  hidden linearVelocity_0 0 0 0
  translation 0 0 0
}
"""


def test_wheel_sensors_start_where_a_saved_world_left_the_wheels() -> None:
    # Webots restores the joints' hidden positions, so its wheel sensors start there and
    # Webots' tutorial's setPosition(10.0) turns the left wheel back from 12.3 rad.
    scene = read_scene(SAVED_EPUCK, "E-puck", 4)
    assert scene.wheel_positions == (12.3, -3.2)
    prepare(mazesim.load_world("arena"), seconds=5.0, noise=False, scene=scene)
    controller.Robot.created = None
    robot = controller.Robot()
    sensors = [robot.getDevice(f"{side} wheel sensor") for side in ("left", "right")]
    for sensor in sensors:
        sensor.enable(32)
    robot.step(32)
    resolution = 2 * math.pi / 1000
    assert sensors[0].getValue() == pytest.approx(12.3, abs=resolution)
    assert sensors[1].getValue() == pytest.approx(-3.2, abs=resolution)
    # Position control starts at the joints' positions (Webots' WbMotor): nothing turns.
    left_motor = robot.getDevice("left wheel motor")
    assert left_motor.getTargetPosition() == 12.3
    left_motor.setPosition(10.0)
    for _ in range(40):
        robot.step(32)
    assert sensors[0].getValue() == pytest.approx(10.0, abs=resolution)
    assert sensors[1].getValue() == pytest.approx(-3.2, abs=resolution), "the right wheel stays"
    simulations.release()
    fresh = read_scene(SAVED_EPUCK.replace("hidden", "# hidden"))
    assert fresh.wheel_positions == (0.0, 0.0)


def test_a_saved_wheel_position_beyond_a_whole_number_of_steps_reads_as_it_is() -> None:
    # 1e308 rad to a resolution of 2 pi / 1000 is more steps than a number holds: the wheel
    # sensor reads the saved value (the rounding raised OverflowError from inside mazesim).
    scene = read_scene(SAVED_EPUCK.replace("12.3", "1e308"), "E-puck", 4)
    prepare(mazesim.load_world("arena"), seconds=5.0, noise=False, scene=scene)
    controller.Robot.created = None
    robot = controller.Robot()
    sensor = robot.getDevice("left wheel sensor")
    sensor.enable(32)
    left = robot.getDevice("left wheel motor")
    left.setPosition(float("inf"))
    left.setVelocity(1.0)
    for _ in range(3):
        assert robot.step(32) != -1
    assert sensor.getValue() == 1e308
    simulations.release()
    assert discretize(1e308, 0.001) == 1e308 and discretize(-0.7, 1.0) == 0.0


def test_a_world_written_compactly_by_hand_gives_the_robots_arguments() -> None:
    text = (
        "#VRML_SIM R2023b utf8\nWorldInfo{basicTimeStep\t16}\n"
        'DEF R E-puck{translation -0.2,0,0\tname "bot" controllerArgs["a","b"]}\n'
    )
    scene = read_scene(text)
    assert (scene.robot_def, scene.robot_name, scene.controller_args) == ("R", "bot", ["a", "b"])


def test_the_robot_reports_its_controllers_name_and_arguments(tmp_path: Path) -> None:
    asks = (
        "from controller import Node, Robot\n"
        "robot = Robot()\n"
        "print('controller:', robot.getControllerName())\n"
        "print('arguments:', robot.getControllerArguments())\n"
        "print('robot type:', robot.getType() == Node.ROBOT)\n"
        "robot.step(16)\n"
    )
    result = run_webots(tmp_path, asks, REFEREE_WORLD)
    assert "controller: controller\n" in result.stdout
    assert "arguments: left 3.5\n" in result.stdout
    assert "robot type: True\n" in result.stdout
    assert "not available" not in result.stderr


def test_ground_sensors_without_the_module_are_none_as_in_webots(tmp_path: Path) -> None:
    reads_gs0 = (
        "from controller import Robot\n"
        "robot = Robot()\n"
        "print('gs0 found:', robot.getDevice('gs0') is not None)\n"
        "robot.getDevice('gs1')\n"
        "robot.step(16)\n"
    )
    bare = "#VRML_SIM R2023b utf8\nRectangleArena { }\nE-puck { }\n"
    result = run_webots(tmp_path, reads_gs0, bare)
    assert "gs0 found: False" in result.stdout
    assert 'Device "gs0" was not found on robot "e-puck"' in result.stderr
    assert result.stderr.count("has no ground sensors module") == 1
    module = "groundSensorsSlot [ E-puckGroundSensors { } ]"
    equipped = bare.replace("E-puck { }", f"E-puck {{ {module} }}")
    result = run_webots(tmp_path, reads_gs0, equipped)
    assert "gs0 found: True" in result.stdout
    assert "ground sensors module" not in result.stderr


def test_the_camera_of_an_e_puck_in_a_world_without_walls_sees_floor_and_sky(
    tmp_path: Path,
) -> None:
    world_file = tmp_path / "open.wbt"
    world_file.write_text("#VRML_SIM R2023b utf8\nE-puck { }\n")
    prepare(mazesim.load_world(str(world_file)), seconds=1.0, noise=False)
    controller.Robot.created = None
    robot = controller.Robot()
    camera = robot.getDevice("camera")
    camera.enable(32)
    robot.step(32)  # warnings are errors here: no RuntimeWarning for rays that meet nothing
    image = camera.getImageArray()
    assert image is not None and len(image) == camera.getWidth()
    top, bottom = image[0][0], image[0][camera.getHeight() - 1]
    assert top != bottom, "sky above, floor below"
    simulations.release()


#: Two e-pucks, each with its own controller, as leader-follower worlds have them.
LEADER_FOLLOWER = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 16 }
RectangleArena { floorSize 1 1 }
DEF LEADER E-puck { translation 0.2 0 0 name "leader" controller "leader" }
DEF FOLLOWER E-puck {
  translation -0.3 0.2 0
  name "follower"
  controller "follower"
  controllerArgs [ "--gap" "0.1" ]
}
"""


def test_the_e_puck_whose_controller_runs_is_the_robot(tmp_path: Path) -> None:
    result = run_webots(tmp_path, WHO_AM_I, LEADER_FOLLOWER, controller="follower.py")
    assert "name: follower" in result.stdout
    assert "args: ['--gap', '0.1']" in result.stdout
    assert 'an e-puck running "leader": a run of the controller "follower" alone' in result.stderr
    trajectory = (tmp_path / "out" / "trajectory.csv").read_text().splitlines()
    assert trajectory[1].split(",")[1:] == ["-0.30000", "0.20000"], "the follower's start"
    # The Python API: the first e-puck unless a controller is named.
    world_file = tmp_path / "world.wbt"
    assert import_wbt(str(world_file))[1]["robot"] == {"x": 0.2, "y": 0.0, "yaw": 0.0}
    _, report = import_wbt(str(world_file), controller="follower")
    assert report["robot"] is not None and report["robot"]["x"] == pytest.approx(-0.3)
