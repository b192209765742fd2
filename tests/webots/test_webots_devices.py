"""The controller module's classes and devices in-process: every Webots class and constant, the
camera's rendering, light sensors, accelerometer, gyro, extension-slot devices, the supervisor's
fields, and what the module answers for what it does not simulate."""

from __future__ import annotations

import math
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import mazesim
from mazesim.errors import InvalidArgumentError
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.importer import robot_warnings
from mazesim.webots.keyboard import KeyScript, key_code
from mazesim.webots.scene import read_scene

#: Every class that Webots' Python ``controller`` module exports (R2023b).
WEBOTS_CLASSES = (
    "Accelerometer Altimeter AnsiCodes Brake Camera CameraRecognitionObject Compass Connector "
    "ContactPoint Device Display DistanceSensor Emitter Field GPS Gyro InertialUnit Joystick "
    "Keyboard LED Lidar LidarPoint LightSensor Motion Motor Mouse Node Pen PositionSensor Radar "
    "RadarTarget RangeFinder Receiver Robot Skin Speaker Supervisor TouchSensor VacuumGripper"
).split()
PROFILE = mazesim.RobotProfile.builtin("e-puck")


def make_robot(
    world: str = "arena", report: dict[str, Any] | None = None, supervisor: bool = False
) -> Any:
    prepare(mazesim.load_world(world), seconds=5.0, noise=False, report=report)
    controller.Robot.created = None
    return controller.Supervisor() if supervisor else controller.Robot()


@pytest.fixture(autouse=True)
def release() -> Iterator[None]:
    yield
    controller.Robot.created = None
    simulations.release()


def drive(robot: Any, left: float, right: float) -> None:
    for name, speed in (("left wheel motor", left), ("right wheel motor", right)):
        motor = robot.getDevice(name)
        motor.setPosition(math.inf)
        motor.setVelocity(speed)


def test_every_webots_class_and_constant_is_importable() -> None:
    namespace: dict[str, Any] = {}
    exec("from mazesim.webots.controller import *", namespace)
    for name in WEBOTS_CLASSES:
        assert isinstance(namespace.get(name), type), f"'from controller import *' lacks {name}"
    assert (controller.Keyboard.UP, controller.Keyboard.SHIFT) == (315, 0x10000)
    assert controller.Motor.ROTATIONAL == 0 and controller.DistanceSensor.INFRA_RED == 1
    assert controller.Node.ROBOT != controller.Node.SOLID and controller.Node.NO_NODE == 0
    assert controller.Field.SF_VEC3F == 5 and controller.Field.MF_NODE == 0x19
    assert controller.Supervisor.SIMULATION_MODE_FAST == 2 and controller.GPS.WGS84 == 1
    assert controller.AnsiCodes.RESET == "\x1b[0m" and controller.Robot.EVENT_KEYBOARD == 4


def test_devices_are_found_by_name_property_style_and_old_style() -> None:
    robot = make_robot()
    ps0 = robot.getDevice("ps0")
    assert controller.DistanceSensor("ps0") is ps0, "old controllers build devices by name"
    assert ps0.name == "ps0" and ps0.node_type == ps0.getNodeType()
    ps0.sampling_period = 32
    robot.step(32)
    assert ps0.value == ps0.getValue() and ps0.getSamplingPeriod() == 32
    motor = robot.getDevice("left wheel motor")
    motor.target_position = math.inf
    motor.velocity = 2.0
    assert motor.getVelocity() == 2.0 and math.isinf(motor.getTargetPosition())
    assert robot.time == robot.getTime() and robot.basic_time_step == 32.0


def test_the_wheels_devices_come_in_the_e_puck_protos_order() -> None:
    # Each wheel's motor, then its sensor (a C controller's tags 1 to 4; some check them).
    robot = make_robot()
    names = [robot.getDeviceByIndex(i).getName() for i in range(4)]
    assert names == [
        "left wheel motor", "left wheel sensor", "right wheel motor", "right wheel sensor"
    ]  # fmt: skip


def test_what_is_not_simulated_answers_instead_of_raising(
    capsys: pytest.CaptureFixture[str],
) -> None:
    robot = make_robot()
    assert robot.getUrdf().startswith("<?xml")
    assert robot.getKeyboard().getKeyCode() is None  # a Webots method mazesim lacks
    assert "Keyboard.getKeyCode() is not available in mazesim" in capsys.readouterr().err
    with pytest.raises(AttributeError):  # not a name of Webots' API: raised, as in Webots
        robot.someFutureWebotsCall(1, 2)
    with pytest.raises(AttributeError):
        robot._private_name  # noqa: B018
    assert robot.getDeviceByIndex(999) is None
    assert math.isnan(robot.batterySensorGetValue())
    receiver = robot.getDevice("receiver")
    assert receiver.getQueueLength() == 0 and receiver.getData() is None
    assert "the receiver queue is empty" in capsys.readouterr().err
    assert robot.getDevice("emitter").send(b"ping") == 1
    assert not robot.getMouse().getState().left and not robot.getJoystick().isConnected()
    assert controller.Display("display") is None
    assert 'Device "display" was not found' in capsys.readouterr().err


def test_step_validates_its_duration() -> None:
    robot = make_robot()
    for duration in (-1, 2**31):
        with pytest.raises(InvalidArgumentError, match="duration in ms from 0 to 2147483647"):
            robot.step(duration)
    assert robot.step(0) == 0 and robot.getTime() == pytest.approx(0.032)


def test_camera_sees_the_line_ahead_the_floor_below_and_the_sky_above() -> None:
    robot = make_robot("line-follow")
    camera = robot.getDevice("camera")
    assert camera.getImage() is None
    camera.enable(32)
    robot.step(32)
    width, height = camera.getWidth(), camera.getHeight()
    assert (width, height, camera.getFov()) == (52, 39, pytest.approx(0.84))
    image = camera.getImage()
    assert isinstance(image, bytes) and len(image) == width * height * 4
    gray = controller.Camera.imageGetGray
    grey = np.array([[gray(image, width, x, y) for x in range(width)] for y in range(height)])
    # The robot starts on the line facing along it: dark in the bottom middle, white beside.
    assert grey[-1, width // 2] < 40 and grey[-1, 2] > 220 and grey[-1, -3] > 220
    # Above the horizon: the sky, not the floor.
    assert controller.Camera.imageGetBlue(image, width, 0, 0) > controller.Camera.imageGetRed(
        image, width, 0, 0
    )
    array = camera.getImageArray()
    assert len(array) == width and len(array[0]) == height
    x, y = 10, height - 1
    assert array[x][y] == [
        controller.Camera.imageGetRed(image, width, x, y),
        controller.Camera.imageGetGreen(image, width, x, y),
        controller.Camera.imageGetBlue(image, width, x, y),
    ]


def test_the_per_pixel_accessors_refuse_a_pixel_outside_the_image() -> None:
    """imageGetRed and its kind check their own arguments, for every pixel a controller reads:
    a pixel left of, right of or below the image is refused, not read from elsewhere in the
    buffer (x = -1 was the last pixel's red), and a bool or a float is no coordinate."""
    width, height = 4, 3
    image = bytes(range(4 * width * height))
    assert controller.Camera.imageGetRed(image, width, 1, 2) == 4 * (2 * width + 1) + 2
    assert controller.Camera.imageGetGrey(image, width, 0, 0) == (0 + 1 + 2) // 3
    for x, y in ((-1, 0), (width, 0), (0, height), (0, -1)):
        for accessor in (controller.Camera.imageGetRed, controller.Camera.imageGetGray):
            with pytest.raises(InvalidArgumentError, match="expected a pixel inside the image"):
                accessor(image, width, x, y)
    for bad in ((image, True, 0, 0), (image, width, 1.0, 0), ("image", width, 0, 0)):
        with pytest.raises(TypeError, match=r"Camera\.imageGetBlue: expected"):
            controller.Camera.imageGetBlue(*bad)
    # A call of the wrong arity is the package's refusal too, not Python's bare TypeError.
    for arguments in ((image, width, 0), (image, width, 0, 0, 0)):
        with pytest.raises(InvalidArgumentError, match=r"Camera\.imageGetGray"):
            controller.Camera.imageGetGray(*arguments)


def test_a_camera_slower_than_the_step_is_black_until_its_first_image() -> None:
    """Webots returns an enabled camera's image buffer from the step after it is enabled, drawn
    only when the first sampling period ends: a controller that enables its camera at 100 ms and
    reads it after a 32 ms step gets a black image, not None."""
    robot = make_robot("line-follow")
    camera = robot.getDevice("camera")
    camera.enable(100)
    assert camera.getImageArray() is None, "no buffer before the first step"
    robot.step(32)
    width, height = camera.getWidth(), camera.getHeight()
    black = camera.getImageArray()
    assert black == [[[0, 0, 0]] * height] * width
    assert camera.getImage() == bytes(width * height * 4)
    for _ in range(3):  # 128 ms: the first image is drawn
        robot.step(32)
    drawn = np.frombuffer(camera.getImage(), dtype=np.uint8)
    assert drawn.max() > 200, "the lit floor beside the line"


def test_camera_sees_a_wall_it_faces_and_saves_images(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    robot = make_robot("arena")
    simulation = simulations.current()
    simulation.move_robot(0.35, 0.0, 0.0)
    camera = robot.getDevice("camera")
    camera.enable(32)
    robot.step(32)
    image = camera.getImage()
    width, height = camera.getWidth(), camera.getHeight()
    # The wall 0.15 m ahead, 0.1 m high, fills the middle of the view up to well above it.
    middle = [controller.Camera.imageGetGray(image, width, width // 2, y) for y in range(height)]
    assert middle[height // 2] == round(255 * 0.8)
    assert middle[2] == middle[height // 2], "a 0.1 m wall 0.12 m from the lens fills the top"
    assert camera.saveImage(str(tmp_path / "view.png"), 100) == 0
    assert (tmp_path / "view.png").read_bytes()[:4] == b"\x89PNG"
    assert camera.saveImage(str(tmp_path / "view.bmp"), 100) == -1
    # Webots' camera.c's words.
    assert "called with unsupported image format (should be PNG or JPEG)" in (
        capsys.readouterr().err
    )
    # A PNG's quality is not read (a public controller passes 'PNG', which Webots ignores); a
    # JPEG's must be a whole number from 1 to 100, else Webots' error and nothing saved.
    assert camera.saveImage(str(tmp_path / "named.png"), "PNG") == 0
    assert (tmp_path / "named.png").read_bytes()[:4] == b"\x89PNG"
    for quality in ("PNG", 0, 101, 50.5, True):
        assert camera.saveImage(str(tmp_path / "bad.jpg"), quality) == -1
        assert "called with invalid 'quality' argument" in capsys.readouterr().err
    assert not (tmp_path / "bad.jpg").exists()


def test_light_sensors_accelerometer_and_gyro() -> None:
    robot = make_robot()
    ls3, accelerometer, gyro = (robot.getDevice(n) for n in ("ls3", "accelerometer", "gyro"))
    for device in (ls3, accelerometer, gyro):
        device.enable(32)
    assert all(math.isnan(v) for v in accelerometer.getValues())
    drive(robot, 4.0, 4.0)
    robot.step(32)
    # Starting to move forward: a push along the device's x, gravity along z.
    ax, ay, az = accelerometer.getValues()
    assert ax == pytest.approx(4.0 * PROFILE.wheel_radius / 0.032, rel=0.05)
    assert abs(ay) < 1e-6 and az == pytest.approx(9.81)
    assert ls3.getValue() == pytest.approx(2047.5)
    robot.step(32)
    assert accelerometer.getValues()[0] == pytest.approx(0.0, abs=1e-3), "steady speed"
    drive(robot, -3.0, 3.0)
    robot.step(32)
    spin = 2.0 * PROFILE.wheel_radius * 3.0 / PROFILE.axle_length
    # The E-puck PROTO's gyro table maps +-13.315805 rad/s to +-100000.
    assert gyro.getValues() == pytest.approx([0.0, 0.0, spin * 100000 / 13.315805], rel=0.01)


def test_noisy_light_sensors_are_reproducible_from_the_seed() -> None:
    def readings(seed: int) -> list[float]:
        prepare(mazesim.load_world("arena"), seconds=1.0, seed=seed)
        controller.Robot.created = None
        robot = controller.Robot()
        sensor = robot.getDevice("ls0")
        sensor.enable(32)
        values = []
        for _ in range(5):
            robot.step(32)
            values.append(sensor.getValue())
        return values

    assert readings(7) == readings(7)
    assert readings(7) != readings(8)
    assert np.std(readings(7)) > 0.0


EXTENSIONS = [
    {"type": "GPS", "name": "gps", "slot": "turretSlot", "translation": [0.01, 0.0, 0.05]},
    {"type": "Compass", "name": "compass", "slot": "turretSlot", "translation": [0, 0, 0.05]},
    {"type": "InertialUnit", "name": "inertial unit", "slot": "turretSlot"},
    {"type": "TouchSensor", "name": "bumper", "slot": "bodySlot"},
    {
        "type": "DistanceSensor",
        "name": "front range",
        "slot": "turretSlot",
        "translation": [0.02, 0.0, 0.03],
        "yaw": 0.0,
        "fields": {"lookupTable": [[0.0, 0.0, 0.0], [1.0, 1000.0, 0.0]]},
    },
    {"type": "Radio", "name": "radio", "slot": "turretSlot"},
]


def test_extension_slot_devices_from_the_import_report(capsys: pytest.CaptureFixture[str]) -> None:
    robot = make_robot(report={"extension_devices": EXTENSIONS})
    assert "the Radio device 'radio' in the world is not simulated" in capsys.readouterr().err
    names = ("gps", "compass", "inertial unit", "bumper", "front range")
    gps, compass, imu, bumper, front = (robot.getDevice(n) for n in names)
    for device in (gps, compass, imu, bumper, front):
        device.enable(32)
    simulations.current().move_robot(0.1, 0.2, 0.5)
    robot.step(32)
    expected_gps = [0.1 + 0.01 * math.cos(0.5), 0.2 + 0.01 * math.sin(0.5), 0.05]
    assert gps.getValues() == pytest.approx(expected_gps)
    # North (+y in ENU) seen from a robot turned 0.5 rad: the heading is atan2(n0, n1).
    north = compass.getValues()
    assert math.atan2(north[0], north[1]) == pytest.approx(0.5)
    assert imu.getRollPitchYaw() == pytest.approx([0.0, 0.0, 0.5])
    assert imu.getQuaternion()[3] == pytest.approx(math.cos(0.25))
    # The arena's wall at x = 0.5 (0.005 thick), along the ray at 0.5 rad from the sensor.
    sx = 0.1 + 0.02 * math.cos(0.5)
    expected = (0.5 - 0.005 - sx) / math.cos(0.5)
    assert front.getValue() == pytest.approx(1000.0 * expected, rel=1e-3)
    assert front.getMaxRange() == 1.0 and front.getType() == front.GENERIC
    assert bumper.getValue() == 0.0
    simulations.current().move_robot(0.45, 0.2, 0.0)
    drive(robot, 3.0, 3.0)
    for _ in range(10):
        robot.step(32)
    assert bumper.getValue() == 1.0, "pushing against the wall"


def test_supervisor_reads_and_sets_the_robots_fields(capsys: pytest.CaptureFixture[str]) -> None:
    supervisor = make_robot(supervisor=True)
    me = supervisor.getSelf()
    assert me.getType() == controller.Node.ROBOT and supervisor.getSupervisor()
    translation, rotation = me.getField("translation"), me.getField("rotation")
    translation.setSFVec3f([0.1, -0.2, 0.0])
    rotation.setSFRotation([0.0, 0.0, -1.0, 1.0])
    assert me.getPosition() == pytest.approx([0.1, -0.2, 0.0])
    assert rotation.getSFRotation() == pytest.approx([0.0, 0.0, 1.0, -1.0], abs=1e-6)
    assert me.getOrientation()[0] == pytest.approx(math.cos(-1.0), abs=1e-6)
    # Webots' Python Field reads a field by its own type whatever the getter: a thesis's
    # supervisor takes the angle of ``getField("rotation").getSFVec3f()[3]``. The C API's
    # typed function still refuses, with Webots' error.
    assert rotation.getSFVec3f() == pytest.approx([0.0, 0.0, 1.0, -1.0], abs=1e-6)
    assert translation.getSFRotation() == pytest.approx([0.1, -0.2, 0.0])
    assert me.getField("name").getSFFloat() == me.getField("name").getSFString()
    assert capsys.readouterr().err == ""
    assert translation.c_sf_rotation() is None
    assert "called with a field of type SFVec3f" in capsys.readouterr().err
    # Missing values are 0, as in the C array Webots' Python API copies the list into.
    rotation.setSFRotation([0.0, 0.0, -1.0])
    assert rotation.getSFRotation()[3] == pytest.approx(0.0, abs=1e-9)
    rotation.setSFRotation([0.0, 0.0, -1.0, 1.0])
    assert me.getField("mass") is None
    supervisor.simulationReset()
    supervisor.step(32)
    assert me.getPosition() == pytest.approx([0.0, 0.0, 0.0], abs=1e-6)
    children = supervisor.getRoot().getField("children")
    assert children.getCount() == 1 and children.getTypeName() == "MFNode"
    assert children.getMFNode(0) is me and children.getMFNode(-1) is me, "a mazesim world"
    children.importMFNodeFromString(-1, "Solid {}")
    assert "the run's world is no Webots world file" in capsys.readouterr().err
    assert children.getCount() == 1
    supervisor.simulationQuit(5)
    assert supervisor.step(32) == -1 and simulations.current().quit_status == 5


def test_get_from_def_knows_the_worlds_def_names(capsys: pytest.CaptureFixture[str]) -> None:
    text = "DEF EPUCK E-puck {\n  supervisor TRUE\n  camera_width 80\n}\nDEF WALL_1 Solid {\n}\n"
    scene = read_scene(text)
    assert (scene.robot_def, scene.supervisor, scene.camera_width) == ("EPUCK", True, 80)
    simulation = prepare(mazesim.load_world("arena"), seconds=1.0, scene=scene)
    controller.Robot.created = None
    robot = controller.Robot()
    assert robot.getSupervisor() and simulation.supervisor
    assert robot.getDevice("camera").getWidth() == 80
    controller.Robot.created = None
    supervisor = controller.Supervisor()
    assert supervisor.getFromDef("EPUCK") is supervisor.getSelf()
    wall = supervisor.getFromDef("WALL_1")
    assert wall is not None and wall.getTypeName() == "Solid" and wall.getDef() == "WALL_1"
    capsys.readouterr()
    assert supervisor.getFromDef("NOPE") is None
    assert capsys.readouterr().err == "", "Webots returns None for a missing DEF silently"
    assert supervisor.getFromDef("") is None
    assert "called with a NULL or empty 'def' argument" in capsys.readouterr().err


def test_key_codes_and_script_errors() -> None:
    assert key_code("a") == key_code("A") == 65
    assert key_code("SHIFT+UP") == controller.Keyboard.SHIFT + controller.Keyboard.UP
    assert key_code("ALT+CONTROL+x") == 0x40000 + 0x20000 + 88
    with pytest.raises(InvalidArgumentError, match="<keys>:1: expected a time in seconds"):
        KeyScript.parse("soon UP\n")
    with pytest.raises(InvalidArgumentError, match="<keys>:2: expected 'time_s key"):
        KeyScript.parse("1 UP\n2\n")
    with pytest.raises(InvalidArgumentError, match="expected a modifier"):
        KeyScript.parse("1 HYPER+A\n")


def test_a_key_script_longer_than_its_bound_is_refused_before_it_is_read(
    tmp_path: Path,
) -> None:
    from mazesim.webots.keyboard import MAX_KEY_SCRIPT_CHARACTERS, read_keys

    script = tmp_path / "keys.txt"
    line = "1 UP\n"
    script.write_text(line * (MAX_KEY_SCRIPT_CHARACTERS // len(line)))
    assert read_keys(script) is not None  # at the bound: read
    script.write_text(line * (MAX_KEY_SCRIPT_CHARACTERS // len(line) + 1))
    with pytest.raises(
        InvalidArgumentError, match=f"at most {MAX_KEY_SCRIPT_CHARACTERS} characters, found more"
    ):
        read_keys(script)


def test_keyboard_gives_each_held_key_once_per_step() -> None:
    prepare(mazesim.load_world("arena"), seconds=1.0, keys=KeyScript.parse("0 UP\n"))
    controller.Robot.created = None
    robot = controller.Robot()
    keyboard = robot.getKeyboard()
    assert keyboard.getKey() == -1, "disabled"
    keyboard.enable(32)
    robot.step(32)
    assert (keyboard.getKey(), keyboard.getKey()) == (controller.Keyboard.UP, -1)
    robot.step(32)
    assert keyboard.getKey() == controller.Keyboard.UP


def test_keyboard_is_read_once_per_sampling_period() -> None:
    prepare(mazesim.load_world("arena"), seconds=2.0, keys=KeyScript.parse("0 UP\n"))
    controller.Robot.created = None
    robot = controller.Robot()
    keyboard = robot.getKeyboard()
    keyboard.enable(160)  # five basic steps of 32 ms
    keys = []
    for _ in range(20):
        robot.step(32)
        keys.append(keyboard.getKey())
    # Held all along, the key is returned at each 160 ms sampling, -1 at the steps between.
    assert [i for i, k in enumerate(keys) if k == controller.Keyboard.UP] == [4, 9, 14, 19]
    assert keys.count(-1) == 16


def test_a_robot_that_is_not_an_e_puck_is_warned_about() -> None:
    assert robot_warnings({"robot_model": "Pioneer3dx", "warnings": []}) == [
        "the world's robot is a Pioneer3dx, not an e-puck: mazesim runs it as the e-puck"
    ]
    assert robot_warnings({"robot_model": "e-puck2", "warnings": []}) == []
    assert robot_warnings({"robot_model": "Khepera", "warnings": ["Khepera is no e-puck"]}) == []
    assert robot_warnings({"warnings": []}) == []


def test_unknown_robot_profiles_fall_back_to_the_e_puck() -> None:
    assert simulations.robot_profile_name({"robot_profile": "no-such-robot"}) == "e-puck"
    assert simulations.robot_profile_name(None) == "e-puck"


def test_gps_reads_in_the_old_nue_frame_of_worlds_before_r2022a() -> None:
    assert read_scene("#VRML_SIM R2021c utf8\nWorldInfo {}\n").nue
    assert read_scene("#VRML_SIM V8.5 utf8\n").nue
    assert not read_scene("#VRML_SIM R2023b utf8\n").nue
    assert read_scene('#VRML_SIM R2023b utf8\nWorldInfo { coordinateSystem "NUE" }\n').nue
    scene = read_scene("#VRML_SIM R2021a utf8\n")
    gps_entry = {"type": "GPS", "name": "gps", "translation": [0.0, 0.0, 0.04]}
    prepare(
        mazesim.load_world("arena"),
        seconds=1.0,
        noise=False,
        report={"extension_devices": [gps_entry]},
        scene=scene,
    )
    controller.Robot.created = None
    robot = controller.Robot()
    gps = robot.getDevice("gps")
    gps.enable(32)
    simulations.current().move_robot(0.1, 0.2, 0.0)
    robot.step(32)
    # The inverse of the importer's (Webots' converter's) map (x, y, z) -> (-z, -x, y).
    assert gps.getValues() == pytest.approx([-0.2, 0.04, -0.1])


def test_the_reports_robot_profile_picks_the_devices_by_name() -> None:
    robot = make_robot(report={"robot_profile": "alphabot2"})
    assert robot.getModel() == "alphabot2"
    profile = mazesim.RobotProfile.builtin("alphabot2")
    names = [profile.distance_sensor_names, profile.ground_sensor_names]
    # Lists, or methods giving them (the robot-profile interface allows both).
    for name in [n for group in names for n in (group() if callable(group) else group)]:
        assert isinstance(robot.getDevice(name), controller.DistanceSensor), name
    assert robot.getDevice("left wheel motor").getMaxVelocity() == profile.max_wheel_speed
    line4 = robot.getDevice("line4")
    line4.enable(32)
    robot.step(32)
    assert line4.getValue() == pytest.approx(float(simulations.current().ground_readings()[4]))


def test_other_def_nodes_have_their_translation_from_the_world_file() -> None:
    world = Path(__file__).parents[1] / "data" / "webots-worlds" / "collision_avoidance.wbt"
    # Its E-puck made a supervisor, as Webots needs it to be for a controller's look-ups.
    text = world.read_text().replace("E-puck {", "E-puck {\n  supervisor TRUE", 1)
    scene = read_scene(text)
    prepare(mazesim.load_world(str(world)), seconds=1.0, scene=scene)
    controller.Robot.created = None
    supervisor = controller.Supervisor()
    wall = supervisor.getFromDef("WALL_1")
    assert wall.getPosition() == pytest.approx([0.5, 0.0, 0.05])
    ball = supervisor.getFromDef("BALL").getField("translation")
    assert ball.getSFVec3f() == pytest.approx([0.2, 0.0, 0.1])
    ball.setSFVec3f([0.1, 0.1, 0.1])
    assert supervisor.getFromDef("BALL").getPosition() == pytest.approx([0.1, 0.1, 0.1])
    assert supervisor.getFromDef("WALL_SHAPE").getField("translation") is None


LIT_WORLD = """#VRML_SIM R2023b utf8
WorldInfo { basicTimeStep 32 }
PointLight {
  location 0 0.3 0.033
  intensity 0.1
  attenuation 0 0 1
}
DirectionalLight { on FALSE direction 1 0 0 }
"""


def test_light_sensors_see_the_worlds_point_light() -> None:
    scene = read_scene(LIT_WORLD)
    assert len(scene.lights) == 1 and scene.lights[0].position == (0.0, 0.3, 0.033)
    prepare(mazesim.load_world("arena"), seconds=1.0, noise=False, scene=scene)
    controller.Robot.created = None
    robot = controller.Robot()
    sensors = [robot.getDevice(f"ls{i}") for i in range(8)]
    for sensor in sensors:
        sensor.enable(32)
    robot.step(32)
    values = [sensor.getValue() for sensor in sensors]
    # The light is 0.3 m to the robot's left (+y): ls5 faces it, ls2 faces away.
    assert values[5] == min(values) and values[2] == pytest.approx(4095.0)
    x, y, heading = PROFILE.distance_sensor_poses()[5]
    distance = 0.3 - y
    irradiance = 0.1 * math.cos(heading - math.pi / 2) / distance**2
    # The PROTO's table: 1 W/m^2 or less reads 4095, 2 W/m^2 reads 0.
    expected = 4095.0 * (2.0 - irradiance)
    assert values[5] == pytest.approx(expected, rel=0.02)
    nue = read_scene("#VRML_SIM R2021a utf8\nPointLight { location 1 2 3 }\n")
    assert nue.lights[0].position == (-3.0, -1.0, 2.0)


def test_a_camera_tilted_down_by_the_world_sees_only_floor() -> None:
    scene = read_scene("E-puck {\n  camera_rotation 0 1 0 0.6\n  camera_height 20\n}\n")
    assert scene.camera_pitch == pytest.approx(0.6)
    prepare(mazesim.load_world("line-follow"), seconds=1.0, scene=scene)
    controller.Robot.created = None
    robot = controller.Robot()
    camera = robot.getDevice("camera")
    camera.enable(32)
    robot.step(32)
    image = camera.getImage()
    assert camera.getHeight() == 20 and len(image) == 52 * 20 * 4
    top_row = [controller.Camera.imageGetGray(image, 52, x, 0) for x in range(52)]
    # Tilted 0.6 rad down, even the top row looks at the floor: white, with the line ahead.
    assert max(top_row) == 255 and min(top_row) == 0


def test_a_world_s_display_has_its_size_and_accepts_drawings_silently(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # A Display in the turret (a path planner drawing its map): Webots draws on it; here the
    # drawings are accepted and dropped, as the C library does, and its size is the node's.
    display_entry = {
        "type": "Display",
        "name": "display",
        "slot": "turretSlot",
        "fields": {"width": 200.0, "height": 120.0},
    }
    robot = make_robot(report={"extension_devices": [display_entry]})
    display = robot.getDevice("display")
    assert (display.getWidth(), display.getHeight()) == (200, 120)
    display.setColor(0x222222)
    display.fillRectangle(0, 0, 200, 120)
    display.drawLine(0, 0, 10, 10)
    display.drawText("Confidence", 2, 2)
    display.drawOval(5, 5, 2, 2)
    image = display.imageCopy(0, 0, 30, 20)
    assert (image.width, image.height) == (30, 20)
    display.imagePaste(image, 5, 5, False)
    display.imageDelete(image)
    assert "not available" not in capsys.readouterr().err
    assert robot.step(32) == 0


def test_a_python_controller_that_draws_on_a_display_is_told_it_is_not_drawn(
    tmp_path: Path,
) -> None:
    from mazesim.webots.requirements import DISPLAY_NOTE, prepare_controller

    source = tmp_path / "planner.py"
    source.write_text(
        "from controller import Robot\nrobot = Robot()\ndisplay = robot.getDevice('display')\n"
        "display.fillRectangle(0, 0, 10, 10)\n",
        encoding="utf-8",
    )
    assert f"Python controller planner.py: {DISPLAY_NOTE}" in prepare_controller(str(source)).notes
    source.write_text("from controller import Robot\nrobot = Robot()\n", encoding="utf-8")
    assert not [n for n in prepare_controller(str(source)).notes if DISPLAY_NOTE in n]


def test_the_robots_name_and_custom_data_come_from_the_world() -> None:
    text = (
        'E-puck {\n  name "scout"\n  customData "lap 3"\n  supervisor TRUE\n'
        '  turretSlot [ GPS { name "g" } ]\n}\n'
    )
    scene = read_scene(text)
    assert (scene.robot_name, scene.robot_custom_data) == ("scout", "lap 3")
    prepare(mazesim.load_world("arena"), seconds=1.0, scene=scene)
    controller.Robot.created = None
    supervisor = controller.Supervisor()
    assert supervisor.getName() == "scout" and supervisor.getCustomData() == "lap 3"
    assert supervisor.getSelf().getField("name").getSFString() == "scout"


def test_python_ray_casts_agree_with_the_cores_proximity_sensors() -> None:
    from mazesim.webots.devices import PROXIMITY_TABLE
    from mazesim.webots.rays import WallBoxes
    from mazesim.webots.sensors import DeviceMount, LookupTable

    world = mazesim.load_world("arena")
    simulator = mazesim.Simulator(world, robot="e-puck", noise=False)
    walls = WallBoxes(world)
    table = LookupTable(PROXIMITY_TABLE)
    near = 0
    for pose in [(0.45, 0.0, 0.3), (0.0, 0.455, 1.2), (-0.44, -0.3, 2.8)]:
        simulator.set_pose(*pose)
        readings = simulator.distance_sensors()
        near += int(np.sum(readings > 150.0))
        for index, (x, y, heading) in enumerate(PROFILE.distance_sensor_poses()):
            sx, sy, direction = DeviceMount((x, y, 0.0), heading).world_pose(pose)
            ray = np.array([[math.cos(direction), math.sin(direction)]])
            distance, reflectance = walls.cast((sx, sy), ray)
            expected = table(min(float(distance[0]) / float(reflectance[0]), 0.07), None)
            assert readings[index] == pytest.approx(expected, rel=0.02, abs=1.0), (pose, index)
    assert near >= 4, "the poses put walls within the sensors' reach"


def test_the_level_cameras_column_rays_render_as_per_pixel_rays() -> None:
    from mazesim.webots.camera import CameraView, render
    from mazesim.webots.rays import FloorPaint, WallBoxes

    world = mazesim.load_world("seed-maze")
    walls, floor = WallBoxes(world), FloorPaint(world)
    for pose in [(0.12, 0.12, 0.0), (0.62, 0.6, 2.0), (1.1, 0.9, -1.0)]:
        level = render(CameraView(), walls, floor, pose)
        # A pitch too small to move any ray takes the per-pixel path.
        per_pixel = render(CameraView(pitch=1e-12), walls, floor, pose)
        assert np.array_equal(level, per_pixel)
        assert len(np.unique(level[:, :, 0])) >= 3, "walls, floor and sky are all in view"


def test_an_e_puck_distance_sensor_in_a_slot_is_the_ds_its_proto_holds() -> None:
    from mazesim.webots import import_wbt_text

    text = (
        "#VRML_SIM R2023b utf8\n"
        "E-puck {\n  turretSlot [\n    E-puckDistanceSensor {\n      translation 0.04 0 0\n"
        "    }\n  ]\n}\n"
    )
    _, report = import_wbt_text(text)
    [ds] = [d for d in report["extension_devices"] if d["name"] == "ds"]
    assert ds["type"] == "DistanceSensor"
    assert ds["yaw"] == pytest.approx(0.16)
    assert ds["fields"]["type"] == "infra-red"
    assert ds["fields"]["model"] == "e-puck distance sensor"
    assert not any("E-puckDistanceSensor" in w for w in report["warnings"])
    robot = make_robot(report=report)
    sensor = robot.getDevice("ds")
    sensor.enable(32)
    assert sensor.getType() == sensor.INFRA_RED
    readings = []
    for gap in (0.02, 0.06):  # from the sensor to the arena's wall at x = 0.495
        simulations.current().move_robot(0.495 - 0.04 - gap, 0.0, -0.16)
        robot.step(32)
        readings.append(sensor.getValue())
    # The PROTO's table: 383.84 at 2 cm, 104.09 at 6 cm (times the wall's reflection factor).
    assert readings[0] > 3.0 * readings[1] > 0.0, readings


def test_sharps_infra_red_ranger_protos_are_the_distance_sensors_they_hold() -> None:
    """Webots' ``SharpGP2D120`` (and its kin of ``projects/devices/sharp``) is a DistanceSensor
    of the datasheet's table reading volts: mounted in a slot, or among a plain robot's
    children, ``getDevice`` finds it, which a C++ controller dereferences at once."""
    from mazesim.webots import import_wbt_text

    text = (
        "#VRML_SIM R2023b utf8\n"
        "E-puck {\n  groundSensorsSlot [\n    SharpGP2D120 {\n      translation 0.01 0 0.03\n"
        '      name "sharp_front"\n    }\n    SharpGP2Y0A02YK0F { }\n  ]\n}\n'
        'Robot {\n  name "other"\n  children [\n    SharpGP2Y0A41SK0F { translation 0.05 0 0 }\n'
        "  ]\n}\n"
    )
    _, report = import_wbt_text(text)
    devices = {d["name"]: d for d in report["extension_devices"]}
    assert set(devices) == {"sharp_front", "Sharp's IR sensor GP2Y0A02YK0F"}
    sharp = devices["sharp_front"]
    assert sharp["type"] == "DistanceSensor" and sharp["fields"]["model"] == "GP2D120"
    assert sharp["fields"]["lookupTable"][0] == [0.03, 3.03, 0.005]
    assert sharp["translation"] == pytest.approx([0.04, 0.0, 0.0303])
    assert not any("Sharp" in w for w in report["warnings"])
    robot = make_robot(report=report)
    sensor = robot.getDevice("sharp_front")
    sensor.enable(32)
    assert sensor.getType() == sensor.GENERIC
    readings = []
    for gap in (0.05, 0.1, 0.2):  # from the sensor to the arena's wall at x = 0.495
        simulations.current().move_robot(0.495 - 0.04 - gap, 0.0, 0.0)
        robot.step(32)
        readings.append(sensor.getValue())
    # The datasheet's volts: 2.33 at 5 cm, 1.25 at 10 cm, 0.66 at 20 cm.
    assert readings == pytest.approx([2.33, 1.25, 0.66], abs=0.03)
    far = robot.getDevice("Sharp's IR sensor GP2Y0A02YK0F")
    assert far.getLookupTable()[:3] == [0.15, 2.75, 0.015]


def test_robotis_lds01_is_the_lidar_it_holds_and_an_unknown_proto_among_children_is_said() -> None:
    """Webots' ``RobotisLds01`` among a plain robot's children is the Lidar "LDS-01" of its
    PROTO (360 ranges all round, 0.12 to 3.5 m): it was dropped without a word, and the
    controller's ``getDevice('LDS-01')`` found nothing. A PROTO mazesim does not read there
    is named in a warning, as one in a slot is; one of Webots' solid PROTOs (an expanded
    E-puck's ring is a SolidPipe) is a part of the body, not said."""
    from mazesim.webots import import_wbt_text

    text = (
        "#VRML_SIM R2023b utf8\n"
        'Robot {\n  name "e-puck"\n  children [\n    DEF TURRET_SLOT Pose {\n'
        "      translation 0 0 0.07\n      children [\n        RobotisLds01 { }\n"
        "        HokuyoUnheardOf { }\n      ]\n    }\n    SolidPipe { }\n  ]\n}\n"
    )
    _, report = import_wbt_text(text)
    lidar = {d["name"]: d for d in report["extension_devices"]}["LDS-01"]
    assert lidar["type"] == "Lidar"
    fields = lidar["fields"]
    assert (fields["horizontalResolution"], fields["numberOfLayers"]) == (360, 1)
    assert (fields["minRange"], fields["maxRange"], fields["fieldOfView"]) == (0.12, 3.5, 6.28318)
    assert lidar["translation"] == pytest.approx([0.0, 0.0, 0.09])
    said = [w for w in report["warnings"] if "in the robot's children" in w]
    assert len(said) == 1 and "HokuyoUnheardOf" in said[0], report["warnings"]


def test_hokuyo_scanner_protos_are_the_lidars_they_hold() -> None:
    """Webots' Hokuyo PROTOs (given by URL, as worlds since R2022b name them) are the Lidars of
    Webots' guide: the URG-04LX 667 ranges over 240 degrees, 0.06 to 4.096 m; its PROTO field
    ``resolution`` is the Lidar's ``horizontalResolution``. A localiser's
    ``getDevice('Hokuyo URG-04LX')`` found nothing and its ``enable`` stopped on None; now the
    scan reads the arena's wall ahead."""
    from mazesim.webots import import_wbt_text

    url = "https://raw.githubusercontent.com/cyberbotics/webots/R2023b/projects/devices/hokuyo"
    text = (
        "#VRML_SIM R2023b utf8\n"
        f'EXTERNPROTO "{url}/protos/HokuyoUrg04lx.proto"\n'
        f'EXTERNPROTO "{url}/protos/HokuyoUrg04lxug01.proto"\n'
        "E-puck {\n  turretSlot [\n    HokuyoUrg04lx { translation 0 0 0.02 }\n"
        '    HokuyoUrg04lxug01 { name "rear" resolution 100 noise 0.01 }\n  ]\n}\n'
    )
    _, report = import_wbt_text(text)
    lidars = {d["name"]: d for d in report["extension_devices"]}
    assert set(lidars) == {"Hokuyo URG-04LX", "rear"}, report["warnings"]
    urg, rear = lidars["Hokuyo URG-04LX"]["fields"], lidars["rear"]["fields"]
    assert (urg["horizontalResolution"], urg["numberOfLayers"], urg["fieldOfView"]) == (
        667,
        1,
        4.18879,
    )
    assert (urg["minRange"], urg["maxRange"]) == (0.06, 4.096)
    assert (rear["horizontalResolution"], rear["noise"], rear["maxRange"]) == (100, 0.01, 5.6)
    assert "resolution" not in rear
    assert not any("Hokuyo" in w for w in report["warnings"]), report["warnings"]
    robot = make_robot(report=report)
    lidar = robot.getDevice("Hokuyo URG-04LX")
    lidar.enable(32)
    assert (lidar.getHorizontalResolution(), lidar.getMaxRange()) == (667, 4.096)
    assert lidar.getFov() == pytest.approx(4.18879)
    simulations.current().move_robot(0.0, 0.0, 0.0)
    robot.step(32)
    ahead = lidar.getRangeImage()[333]
    # From the arena's centre to its wall at x = 0.495, less the turret's reach forward (0).
    assert ahead == pytest.approx(0.495, abs=0.01), ahead


def test_a_distance_sensor_the_world_adds_gives_its_aperture() -> None:
    """A DistanceSensor the world mounts (not one of the E-puck's own) answers getAperture, as a
    C controller's link asks of every distance sensor: the world's ``aperture``, else the
    node's default."""
    from mazesim.webots import import_wbt_text

    text = (
        "#VRML_SIM R2023b utf8\n"
        "E-puck {\n  turretSlot [\n"
        '    DistanceSensor { name "wide" }\n'
        '    DistanceSensor { name "narrow" aperture 0.3 }\n'
        "    E-puckDistanceSensor { }\n  ]\n}\n"
    )
    _, report = import_wbt_text(text)
    robot = make_robot(report=report)
    apertures = [robot.getDevice(name).getAperture() for name in ("wide", "narrow", "ds")]
    assert apertures == pytest.approx([1.5708, 0.3, 0.1])


def test_webots_errors_print_at_most_a_message_long(capsys: pytest.CaptureFixture[str]) -> None:
    """Webots' error for a field or file name a controller passed quotes the name; one of a
    hundred thousand characters prints as a line of at most a message's length, its start and
    its end kept."""
    from mazesim.errors import MOST_MESSAGE
    from mazesim.webots.devices import _print_error

    _print_error("Error: field '" + "x" * 100_000 + "' does not exist in node 'E-puck'.")
    printed = capsys.readouterr().err.rstrip("\n")
    assert len(printed) < MOST_MESSAGE + 100  # with the note of what was left out
    assert printed.startswith("Error: field 'xxx") and printed.endswith("in node 'E-puck'.")
