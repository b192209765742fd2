"""Webots' API as real controllers use it: the ``controller`` package and its submodules, the
devices' node types, the supervisor's scene tree and the radio of a robot alone in its world."""

from __future__ import annotations

import importlib
import math
import sys
from collections.abc import Iterator
from pathlib import Path
from types import ModuleType

import pytest

import mazesim
from mazesim.webots import controller, prepare, run_controller
from mazesim.webots import simulation as simulations
from mazesim.webots.node_types import NODE_TYPES
from mazesim.webots.scene import read_scene

CONTROLLERS = Path(__file__).resolve().parents[1] / "data" / "controllers"
WORLDS = Path(__file__).resolve().parents[1] / "data" / "webots-worlds"
SUPERVISED = CONTROLLERS / "worlds" / "supervised_arena.wbt"
#: Webots' submodules (R2023b): module -> the classes it defines.
SUBMODULES = {
    "accelerometer": ["Accelerometer"],
    "altimeter": ["Altimeter"],
    "ansi_codes": ["AnsiCodes"],
    "brake": ["Brake"],
    "camera": ["Camera", "CameraRecognitionObject"],
    "compass": ["Compass"],
    "connector": ["Connector"],
    "device": ["Device"],
    "display": ["Display"],
    "distance_sensor": ["DistanceSensor"],
    "emitter": ["Emitter"],
    "field": ["Field"],
    "gps": ["GPS"],
    "gyro": ["Gyro"],
    "inertial_unit": ["InertialUnit"],
    "joystick": ["Joystick"],
    "keyboard": ["Keyboard"],
    "led": ["LED"],
    "lidar": ["Lidar", "LidarPoint"],
    "light_sensor": ["LightSensor"],
    "motion": ["Motion"],
    "motor": ["Motor"],
    "mouse": ["Mouse", "MouseState"],
    "node": ["ContactPoint", "Node"],
    "pen": ["Pen"],
    "position_sensor": ["PositionSensor"],
    "radar": ["Radar", "RadarTarget"],
    "range_finder": ["RangeFinder"],
    "receiver": ["Receiver"],
    "robot": ["Robot"],
    "skin": ["Skin"],
    "speaker": ["Speaker"],
    "supervisor": ["Supervisor"],
    "touch_sensor": ["TouchSensor"],
    "vacuum_gripper": ["VacuumGripper"],
}


@pytest.fixture(autouse=True)
def release() -> Iterator[None]:
    yield
    controller.Robot.created = None
    simulations.release()


def supervisor_in(path: Path) -> controller.Supervisor:
    """A supervisor of the robot in a ``.wbt`` world, as ``mazesim webots run`` prepares it."""
    scene = read_scene(path.read_text())
    # As a world whose robot is a supervisor: Webots refuses a plain robot's supervisor calls.
    scene.supervisor, scene.supervisor_refused = True, False
    prepare(mazesim.load_world(str(path)), seconds=5.0, noise=False, scene=scene)
    controller.Robot.created = None
    return controller.Supervisor()


def test_each_submodule_gives_the_packages_classes() -> None:
    for module_name, classes in SUBMODULES.items():
        module = importlib.import_module(f"mazesim.webots.controller.{module_name}")
        assert module_name in controller.SUBMODULES
        for name in classes:
            assert getattr(module, name) is getattr(controller, name), f"{module_name}.{name}"


def test_a_controller_importing_submodules_runs_and_sys_modules_is_restored() -> None:
    before = ModuleType("controller")
    sys.modules["controller"] = before
    sys.modules["controller.stale"] = ModuleType("controller.stale")
    try:
        run = run_controller(
            CONTROLLERS / "submodule_imports.py", mazesim.load_world("arena"), seconds=1.0
        )
        assert (run.exit_status, run.error) == (0, "")
        assert run.reached_end and run.distance_m > 0.05
        assert sys.modules["controller"] is before
        assert sys.modules["controller.stale"].__name__ == "controller.stale"
        assert "controller.distance_sensor" not in sys.modules
    finally:
        sys.modules.pop("controller", None)
        sys.modules.pop("controller.stale", None)
    run_controller(CONTROLLERS / "submodule_imports.py", mazesim.load_world("arena"), seconds=0.1)
    assert not [name for name in sys.modules if name.split(".")[0] == "controller"]


def test_the_sensor_submodule_gives_the_base_of_every_sampled_device(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # Webots R2023b and later: controller/sensor.py defines Sensor, the base class of the
    # sampled devices, which its package does not export; controllers import it from there.
    script = tmp_path / "sensor_base.py"
    script.write_text(
        "from controller import Robot\n"
        "from controller.sensor import Sensor\n"
        "robot = Robot()\n"
        "names = ['ps0', 'ls0', 'camera', 'receiver', 'left wheel sensor', 'gs0']\n"
        "devices = [robot.getDevice(name) for name in names]\n"
        "print([isinstance(device, Sensor) for device in devices])\n"
        "print(isinstance(robot.getDevice('left wheel motor'), Sensor))\n"
        "devices[0].enable(32)\n"
        "robot.step(32)\n"
        "print(devices[0].getSamplingPeriod())\n"
    )
    world = mazesim.load_world("line-follow")
    run = run_controller(script, world, seconds=0.1)
    assert (run.exit_status, run.error) == (0, ""), run.error
    lines = capsys.readouterr().out.splitlines()
    assert lines[:3] == ["[True, True, True, True, True, True]", "False", "32"]
    assert "Sensor" not in controller.__all__


def test_node_type_constants_are_webots_values_and_distinct() -> None:
    values = [getattr(controller.Node, name) for name in NODE_TYPES]
    assert len(set(values)) == len(values)
    node = controller.Node
    assert (node.NO_NODE, node.ROBOT, node.DISTANCE_SENSOR, node.ROTATIONAL_MOTOR) == (
        0,
        34,
        42,
        57,
    )
    assert (node.SOLID, node.WORLD_INFO) == (80, 84)


def test_devices_report_their_node_types(capsys: pytest.CaptureFixture[str]) -> None:
    report = {"extension_devices": [{"type": "GPS", "name": "gps", "translation": [0, 0, 0.04]}]}
    prepare(mazesim.load_world("arena"), seconds=1.0, report=report)
    controller.Robot.created = None
    robot = controller.Robot()
    node = controller.Node
    expected = {
        "ps0": node.DISTANCE_SENSOR,
        "gs1": node.DISTANCE_SENSOR,
        "left wheel motor": node.ROTATIONAL_MOTOR,
        "right wheel sensor": node.POSITION_SENSOR,
        "led8": node.LED,
        "camera": node.CAMERA,
        "ls3": node.LIGHT_SENSOR,
        "accelerometer": node.ACCELEROMETER,
        "gyro": node.GYRO,
        "emitter": node.EMITTER,
        "receiver": node.RECEIVER,
        "speaker": node.SPEAKER,
        "gps": node.GPS,
    }
    for name, node_type in expected.items():
        device = robot.getDevice(name)
        assert (device.getNodeType(), device.node_type) == (node_type, node_type), name
    controller.Robot.created = None
    simulations.release()
    run = run_controller(CONTROLLERS / "device_inventory.py", mazesim.load_world("arena"))
    assert run.exit_status == 0
    lines = capsys.readouterr().out.splitlines()
    assert {"ps7: DISTANCE_SENSOR", "left wheel motor: ROTATIONAL_MOTOR", "camera: CAMERA"} <= set(
        lines
    )


def test_an_extension_slot_distance_sensor_is_a_distance_sensor() -> None:
    entry = {"type": "DistanceSensor", "name": "front", "translation": [0.04, 0.0, 0.02]}
    prepare(mazesim.load_world("arena"), seconds=1.0, report={"extension_devices": [entry]})
    controller.Robot.created = None
    front = controller.Robot().getDevice("front")
    distance_sensor = importlib.import_module("mazesim.webots.controller.distance_sensor")
    assert isinstance(front, controller.DistanceSensor)
    assert isinstance(front, distance_sensor.DistanceSensor)
    assert front.getNodeType() == controller.Node.DISTANCE_SENSOR
    assert front.getType() == front.GENERIC and front.max_value == 1000.0


def test_the_roots_children_are_the_world_files_top_level_nodes() -> None:
    supervisor = supervisor_in(SUPERVISED)
    root = supervisor.getRoot()
    children = root.getField("children")
    types = [children.getMFNode(i).getTypeName() for i in range(children.getCount())]
    assert types == [
        "WorldInfo",
        "Viewpoint",
        "TexturedBackground",
        "TexturedBackgroundLight",
        "RectangleArena",
        "Solid",
        "Pose",
        "E-puck",
    ]
    defs = [children.getMFNode(i).getDef() for i in range(children.getCount())]
    assert defs == ["", "", "", "", "", "WALL", "TARGET", "EPUCK"]
    robot = children.getMFNode(-1)
    assert robot is supervisor.getSelf() is supervisor.getFromDef("EPUCK")
    assert children.getMFNode(-3) is supervisor.getFromDef("WALL")
    assert children.getMFNode(8) is None and children.getMFNode(-9) is None
    arena = children.getMFNode(4)
    assert (arena.getBaseTypeName(), arena.isProto(), arena.getType()) == (
        "Solid",
        True,
        controller.Node.SOLID,
    )
    assert robot.getBaseTypeName() == "Robot" and robot.getType() == controller.Node.ROBOT
    assert children.getMFNode(0).getType() == controller.Node.WORLD_INFO
    assert arena.getPosition() == [0.0, 0.0, 0.0], "a Solid's default translation"
    assert arena.getParentNode() is root and root.getParentNode() is None
    for node in [root, *[children.getMFNode(i) for i in range(children.getCount())]]:
        assert supervisor.getFromId(node.getId()) is node


def test_top_level_nodes_read_their_fields_and_the_robot_is_live() -> None:
    supervisor = supervisor_in(SUPERVISED)
    target = supervisor.getFromDef("TARGET")
    assert target.getField("translation").getSFVec3f() == pytest.approx([-0.3, 0.3, 0.0])
    assert target.getField("rotation").getSFRotation() == pytest.approx([0, 0, 1, 0.7])
    assert target.getPosition() == pytest.approx([-0.3, 0.3, 0.0])
    orientation = target.getOrientation()
    assert orientation[0] == pytest.approx(math.cos(0.7)) and orientation[3] == pytest.approx(
        math.sin(0.7)
    )
    wall = supervisor.getFromDef("WALL")
    assert wall.getField("name").getSFString() == "wall"
    assert wall.getField("rotation").getSFRotation() == [0.0, 0.0, 1.0, 0.0]
    robot = supervisor.getRoot().getField("children").getMFNode(-1)
    translation = robot.getField("translation")
    assert translation.getSFVec3f() == pytest.approx([-0.2, -0.1, 0.0], abs=1e-6)
    assert robot.getField("rotation").getSFRotation()[3] == pytest.approx(0.3, abs=1e-6)
    translation.setSFVec3f([0.1, 0.2, 0.0])
    assert simulations.current().simulator.pose[:2] == pytest.approx((0.1, 0.2), abs=1e-6)


def test_nue_worlds_give_their_nodes_in_the_files_own_frame() -> None:
    # As Webots before R2022a: the supervisor reads the file's own NUE values (y up), which
    # mazesim converts, as the importer does, for the simulation.
    supervisor = supervisor_in(WORLDS / "e-puck.R2021c_NUE.wbt")
    box = supervisor.getRoot().getField("children").getMFNode(5)
    assert box.getTypeName() == "WoodenBox"
    assert box.getPosition() == pytest.approx([-0.2, 0.05, 0.683174])
    assert box.getField("translation").getSFVec3f() == pytest.approx([-0.2, 0.05, 0.683174])
    assert box.getField("rotation").getSFRotation() == pytest.approx([0, 1, 0, 0.5])
    # The robot: the file's "rotation 0 1 0 1.57", its height 0 on y.
    robot = supervisor.getSelf()
    assert robot.getField("rotation").getSFRotation() == pytest.approx([0, 1, 0, 1.57], abs=1e-6)
    assert robot.getPosition() == pytest.approx([0.0, 0.0, 0.0], abs=1e-6)
    orientation = robot.getOrientation()
    assert orientation[0] == pytest.approx(math.cos(1.57), abs=1e-6)
    assert orientation[2] == pytest.approx(math.sin(1.57), abs=1e-6), "about y, the NUE up"
    # Moving it in the file's frame puts it where the importer puts that place.
    robot.getField("translation").setSFVec3f([0.3, 0.0, -0.1])
    x, y, _ = simulations.current().simulator.pose
    assert (x, y) == pytest.approx((0.1, -0.3), abs=1e-6)
    assert robot.getPosition() == pytest.approx([0.3, 0.0, -0.1], abs=1e-6)


def test_reset_physics_stops_the_robot() -> None:
    supervisor = supervisor_in(SUPERVISED)
    for name in ("left wheel motor", "right wheel motor"):
        motor = supervisor.getDevice(name)
        motor.setPosition(math.inf)
        motor.setVelocity(5.0)
    for _ in range(5):
        supervisor.step(32)
    robot = supervisor.getSelf()
    assert abs(robot.getVelocity()[0]) + abs(robot.getVelocity()[1]) > 0.05
    robot.resetPhysics()
    assert robot.getVelocity() == [0.0] * 6


def test_a_channel_webots_refuses_is_refused_or_ignored_as_webots_does(
    capsys: pytest.CaptureFixture[str],
) -> None:
    """Webots' channel is a C int: a number beyond int32 is refused (Webots' Python API passed
    its low 32 bits on); below -1 (the broadcast channel) Webots prints its error and keeps
    the channel."""
    prepare(mazesim.load_world("arena"), seconds=1.0)
    controller.Robot.created = None
    robot = controller.Robot()
    for device, function in (("emitter", "wb_emitter"), ("receiver", "wb_receiver")):
        tuned = robot.getDevice(device)
        tuned.setChannel(7)
        for huge in (2**40, -(2**31) - 1):
            with pytest.raises(mazesim.InvalidArgumentError, match=r"channel .*int32.*found"):
                tuned.setChannel(huge)
        capsys.readouterr()
        tuned.setChannel(-5)
        assert (
            f"Error: {function}_set_channel() called with an invalid channel=-5."
            in capsys.readouterr().err
        )
        assert tuned.getChannel() == 7
        tuned.setChannel(controller.Emitter.CHANNEL_BROADCAST)
        assert tuned.getChannel() == -1


def test_a_robot_alone_sends_to_nobody_and_receives_nothing(
    capsys: pytest.CaptureFixture[str],
) -> None:
    prepare(mazesim.load_world("arena"), seconds=1.0)
    controller.Robot.created = None
    robot = controller.Robot()
    emitter, receiver = robot.getDevice("emitter"), robot.getDevice("receiver")
    assert isinstance(emitter, controller.Emitter) and isinstance(receiver, controller.Receiver)
    emitter.setChannel(7)
    receiver.setChannel(7)
    assert (emitter.getChannel(), receiver.getChannel()) == (7, 7)
    assert emitter.send("hello") == 1 and emitter.send(b"\x01\x02") == 1
    receiver.enable(32)
    for _ in range(3):
        robot.step(32)
    assert receiver.getQueueLength() == 0
    capsys.readouterr()
    assert receiver.getBytes() is None and receiver.getString() is None
    assert receiver.getData() is None and receiver.getDataSize() == -1
    assert math.isnan(receiver.getSignalStrength())
    assert all(math.isnan(v) for v in receiver.getEmitterDirection())
    receiver.nextPacket()
    errors = capsys.readouterr().err
    assert errors.count("the receiver queue is empty") == 7
