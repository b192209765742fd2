"""Webots' Python API as one table of names (``mazesim/webots/webots_api.toml``): every class
of the ``controller`` module has each of Webots' constants, answers each of Webots' methods and
properties (a property by its getter, by construction), and raises ``AttributeError`` for a
name Webots' API does not have, as Webots does (a misspelt call stops the controller)."""

from __future__ import annotations

import math
import subprocess
import sys
from collections.abc import Iterator
from typing import Any

import pytest

import mazesim
from mazesim.webots import controller, prepare
from mazesim.webots import simulation as simulations
from mazesim.webots.webots_api import NotSimulated, webots_class, webots_classes

#: Webots' classes of records and of constants, without the table's mixin (their missing names
#: raise AttributeError as any Python class's do).
RECORDS = {
    "AnsiCodes", "CameraRecognitionObject", "ContactPoint", "LidarPoint", "MouseState",
    "RadarTarget",
}  # fmt: skip


@pytest.fixture
def robot() -> Iterator[Any]:
    prepare(mazesim.load_world("arena"), seconds=5.0, noise=False)
    controller.Robot.created = None
    yield controller.Supervisor()
    controller.Robot.created = None
    simulations.release()


def _same(a: Any, b: Any) -> bool:
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    return bool(a == b)


def test_every_class_of_the_table_is_one_of_the_controller_module() -> None:
    missing = sorted(name for name in webots_classes() if not hasattr(controller, name))
    assert missing == []
    for name in webots_classes():
        cls = getattr(controller, name)
        assert webots_class(cls) == name or name in RECORDS
        assert name in RECORDS or issubclass(cls, NotSimulated), name


def test_every_class_has_webots_constants() -> None:
    missing = {
        name: sorted(c for c in found.constants if not hasattr(getattr(controller, name), c))
        for name, found in webots_classes().items()
    }
    assert {name: names for name, names in missing.items() if names} == {}


def test_every_webots_property_is_on_its_class() -> None:
    # A property without a method of its own (a Receiver's raw ``data``) answers as a method
    # mazesim does not simulate; every other one is a property of the class.
    missing = {
        name: sorted(
            p
            for p, methods in found.properties.items()
            if any(methods) and not hasattr(getattr(controller, name), p)
        )
        for name, found in webots_classes().items()
        if name not in RECORDS
    }
    assert {name: names for name, names in missing.items() if names} == {}


#: Public names a class of mazesim's ``controller`` module has beyond its Webots class's, and
#: why. A name inherited by accident (a Lidar's ``getValue`` from a scalar sensor base, once) is
#: a call that works here and stops the controller in Webots: it fails this table's test.
BEYOND_WEBOTS = {
    "Camera": {"BOTH", "COLOR", "RANGE_FINDER", "imageGetGrey"},  # releases before R2023b
    "CameraRecognitionObject": {  # the SWIG module of releases before R2023a
        "get_colors", "get_id", "get_model", "get_number_of_colors", "get_orientation",
        "get_position", "get_position_on_image", "get_size", "get_size_on_image",
    },
    # Served to the C library (native_calls.py: wb_*_get_min_range, wb_*_get_lookup_table).
    "DistanceSensor": {"getMaxRange", "getMinRange"},
    "GPS": {"getLookupTable", "lookup_table"},
    "InertialUnit": {"getLookupTable", "getValues", "lookup_table", "value"},
    "Field": {  # values served to the C library; importSFNode of releases before R2023b
        "c_sf_bool", "c_sf_color", "c_sf_float", "c_sf_int32", "c_sf_rotation", "c_sf_string",
        "c_sf_vec2f", "c_sf_vec3f", "importSFNode", "type",
    },
    "Motor": {"acceleration", "velocity"},  # properties of releases before R2023b
    "Mouse": {"state"},
    "MouseState": {"count", "index", "left", "middle", "right", "u", "v", "x", "y", "z"},
    "Node": {"from_scene"},  # mazesim's constructor
    "Robot": {  # Robot names of releases before R2023b, and the module's own instance
        "created", "getControllerArguments", "getControllerName", "getData", "getType",
        "getVacuumGripper", "joystick", "keyboard", "keyboardDisable", "keyboardEnable",
        "keyboardGetKey", "mouse", "setData",
    },
    # The Robot's, and Webots 8's names of simulationResetPhysics and worldReload (the C
    # library's too).
    "Supervisor": {"simulationPhysicsReset", "simulationRevert"},
}  # fmt: skip


def test_no_class_has_a_name_webots_class_has_not_beyond_the_named_ones() -> None:
    beyond: dict[str, set[str]] = {}
    for name, found in webots_classes().items():
        cls = getattr(controller, name)
        extra = {n for n in dir(cls) if not n.startswith("_") and not found.has(n)}
        if extra:
            beyond[name] = extra
    expected = {name: set(names) for name, names in BEYOND_WEBOTS.items()}
    expected["Supervisor"] |= expected["Robot"]
    assert beyond == expected


def test_a_property_reads_as_its_getter_on_every_device_of_the_e_puck(robot: Any) -> None:
    checked = 0
    for index in range(robot.getNumberOfDevices()):
        device = robot.getDeviceByIndex(index)
        found = webots_classes()[webots_class(type(device)) or ""]
        for prop, (getter, _) in found.properties.items():
            if not getter or not hasattr(type(device), getter):
                continue
            try:
                expected = getattr(device, getter)()
            except TypeError:  # a getter that takes arguments
                continue
            assert _same(getattr(device, prop), expected), (device, prop)
            checked += 1
    assert checked > 50


def test_a_webots_method_mazesim_does_not_simulate_answers(
    robot: Any, capsys: pytest.CaptureFixture[str]
) -> None:
    simulated = 0
    for name in sorted(webots_classes()["Supervisor"].methods):
        if hasattr(type(robot), name):
            simulated += 1
            continue
        assert callable(getattr(robot, name)), name
    assert simulated > 60
    unanswered = sorted(webots_classes()["Supervisor"].methods - set(dir(type(robot))))
    if unanswered:
        assert getattr(robot, unanswered[0])() is None
        assert f"Supervisor.{unanswered[0]}() is not available" in capsys.readouterr().err


@pytest.mark.parametrize("name", ["getDevcie", "someFutureWebotsCall", "setvelocity"])
def test_a_name_webots_does_not_have_raises_as_in_webots(robot: Any, name: str) -> None:
    with pytest.raises(AttributeError) as raised:
        getattr(robot, name)
    assert str(raised.value) == f"'Supervisor' object has no attribute '{name}'"
    motor = robot.getDevice("left wheel motor")
    assert not hasattr(motor, name)


def test_a_misspelt_call_gets_pythons_suggestion(robot: Any) -> None:
    # Python's display of an uncaught AttributeError suggests from its ``name`` and ``obj``.
    with pytest.raises(AttributeError) as raised:
        robot.getDevcie("ps0")
    assert raised.value.name == "getDevcie" and raised.value.obj is robot
    script = (
        "from mazesim.webots.webots_api import NotSimulated\n"
        "class Robot(NotSimulated):\n"
        "    def getDevice(self): pass\n"
        "Robot.__module__ = 'mazesim.webots.robot'\n"
        "Robot().getDevcie\n"
    )
    shown = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=False
    ).stderr
    assert "'Robot' object has no attribute 'getDevcie'. Did you mean: 'getDevice'?" in shown


def test_a_controllers_subclass_answers_as_its_webots_class(
    robot: Any, capsys: pytest.CaptureFixture[str]
) -> None:
    class Epuck(controller.Supervisor):  # type: ignore[misc]
        pass

    assert webots_class(Epuck) == "Supervisor"
    sensor = robot.getDevice("ps0")
    sensor.enable(32)
    robot.step(32)
    assert sensor.value == sensor.getValue() > 0.0
    with pytest.raises(AttributeError):
        sensor.getValeu  # noqa: B018


def test_assigning_a_webots_property_calls_its_setter(robot: Any) -> None:
    # Webots' Motor has target_velocity and target_position: assigning one drives the wheel.
    motor = robot.getDevice("left wheel motor")
    motor.target_position = float("inf")
    motor.target_velocity = 2.5
    assert motor.getVelocity() == 2.5 and math.isinf(motor.getTargetPosition())
    sensor = robot.getDevice("ps0")
    sensor.sampling_period = 64
    assert sensor.getSamplingPeriod() == 64
    with pytest.raises(AttributeError):
        motor.force  # noqa: B018  (write-only in Webots)


def test_a_camera_fov_assigned_says_what_webots_says(
    robot: Any, capsys: pytest.CaptureFixture[str]
) -> None:
    camera = robot.getDevice("camera")
    before = camera.fov
    camera.fov = 0.5  # Webots' property calls setFov: the e-puck's camera has no zoom
    assert camera.fov == before == camera.getFov()
    assert "can only be called on a zoom camera" in capsys.readouterr().err


def test_a_read_only_property_a_controller_assigns_holds_its_own_value(robot: Any) -> None:
    """A controller written for Webots before R2023b (no properties) keeps its own data in a
    Robot subclass under names R2023b made read-only properties: ``self.name = ...``."""
    assert robot.name == robot.getName() and robot.time == robot.getTime()
    robot.name = "robot3"
    robot.time = 0
    assert (robot.name, robot.time) == ("robot3", 0)
    assert robot.getName() != "robot3"  # Webots' own value is as it was
    robot.step(32)
    assert robot.time == 0 and robot.getTime() > 0
    # A property with a setter still calls it.
    robot.custom_data = "own"
    assert robot.getCustomData() == "own"
