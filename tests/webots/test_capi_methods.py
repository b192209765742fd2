"""Every public method of the Python ``controller`` module's device, robot, supervisor, node and
field classes has its Webots C function, declared in mazesim's headers and defined in its
controller library, and its C++ method, so that a C or C++ controller builds wherever a Python
one runs: a missing function is a link error, a whole project lost.

Each Python method maps to Webots' C name by Webots' rule (``wb_<device>_<verb>``, the method's
words in snake case: ``GPS.getSpeedVector`` is ``wb_gps_get_speed_vector``), with the names
Webots spells otherwise listed in :data:`C_NAMES`, and the methods that have no C or C++
function, with why, in :data:`PYTHON_ONLY`.
"""

from __future__ import annotations

import inspect
import re
import shutil
import subprocess
from functools import cache
from pathlib import Path

import pytest
from test_capi_devices import WITHOUT_C

from mazesim.webots import controller
from mazesim.webots.devices import Device
from mazesim.webots.native_controller import CAPI
from mazesim.webots.webots_api import WebotsClass, webots_classes
from native_controllers import NEEDS_COMPILERS, run_twins

HEADERS = CAPI / "include" / "webots"
CONTROLLERS = Path(__file__).resolve().parents[1] / "data" / "controllers"

#: Classes of the Python module that C and C++ do not have as classes with methods.
WITHOUT_FUNCTIONS = {
    # Webots' C structs, read by their fields (C++ uses the same structs).
    "CameraRecognitionObject": "the struct WbCameraRecognitionObject",
    "ContactPoint": "the struct WbContactPoint",
    "LidarPoint": "the struct WbLidarPoint",
    "MouseState": "the struct WbMouseState",
    "RadarTarget": "the struct WbRadarTarget",
    # Constants of <webots/utils/ansi_codes.h>.
    "AnsiCodes": "macros of <webots/utils/ansi_codes.h>",
    # Without a C or C++ side yet, inert in Python (named as needed before a build, as the
    # devices of WITHOUT_C are).
    "Motion": "no <webots/utils/motion.h> yet",
    **{name: "no C header yet (test_capi_devices.WITHOUT_C)" for name in WITHOUT_C},
}

#: Python methods whose C function Webots names otherwise than by the rule.
C_NAMES = {
    "Camera.getRecognitionSamplingPeriod": "wb_camera_recognition_get_sampling_period",
    "Camera.getRecognitionNumberOfObjects": "wb_camera_recognition_get_number_of_objects",
    "Camera.getRecognitionObjects": "wb_camera_recognition_get_objects",
    "Camera.hasRecognitionSegmentation": "wb_camera_recognition_has_segmentation",
    "Camera.enableRecognitionSegmentation": "wb_camera_recognition_enable_segmentation",
    "Camera.disableRecognitionSegmentation": "wb_camera_recognition_disable_segmentation",
    "Camera.isRecognitionSegmentationEnabled": "wb_camera_recognition_is_segmentation_enabled",
    "Camera.getRecognitionSegmentationImage": "wb_camera_recognition_get_segmentation_image",
    "Camera.saveRecognitionSegmentationImage": "wb_camera_recognition_save_segmentation_image",
    "Receiver.getBytes": "wb_receiver_get_data",
    "RangeFinder.rangeImageGetDepth": "wb_range_finder_image_get_depth",
    "Supervisor.getRoot": "wb_supervisor_node_get_root",
    "Supervisor.getSelf": "wb_supervisor_node_get_self",
    "Supervisor.getFromDef": "wb_supervisor_node_get_from_def",
    "Supervisor.getFromId": "wb_supervisor_node_get_from_id",
    "Supervisor.getFromDevice": "wb_supervisor_node_get_from_device",
    "Supervisor.getSelected": "wb_supervisor_node_get_selected",
    # A C controller asks for any device by name; the keyboard has its own functions.
    "Robot.getKeyboard": "wb_keyboard_enable",
    "Robot.getMouse": "wb_mouse_enable",
    "Robot.getJoystick": "wb_joystick_enable",
    "Mouse.enable3dPosition": "wb_mouse_enable_3d_position",
    "Mouse.disable3dPosition": "wb_mouse_disable_3d_position",
    "Mouse.is3dPositionEnabled": "wb_mouse_is_3d_position_enabled",
}

#: Python methods whose C++ method Webots names otherwise.
CPP_NAMES = {"Receiver.getBytes": "getData"}

#: Python methods without a C function or C++ method, and why.
PYTHON_ONLY = {
    # Python's conveniences over what C reads as a pointer.
    "Camera.getImageArray": "C reads the image's bytes (wb_camera_get_image)",
    "Camera.getRecognitionSegmentationImageArray": "C reads the segmentation image's bytes",
    "Receiver.getInts": "C reads the packet's bytes (wb_receiver_get_data)",
    "Receiver.getFloats": "C reads the packet's bytes (wb_receiver_get_data)",
    "Receiver.getBools": "C reads the packet's bytes (wb_receiver_get_data)",
    "Robot.getControllerArguments": "C and C++ read their arguments from main's argv",
    # Readings mazesim's Python classes inherit that Webots' device has not.
    "DistanceSensor.getMinRange": "mazesim's own reading, not in Webots' API",
    "DistanceSensor.getMaxRange": "mazesim's own reading, not in Webots' API",
    "GPS.getLookupTable": "a GPS node has no lookup table",
    "InertialUnit.getLookupTable": "an InertialUnit node has no lookup table",
    "InertialUnit.getValues": "Webots' InertialUnit reads getRollPitchYaw",
    # mazesim's own: how a node is made from the world, and the values the C library is served.
    "Node.from_scene": "mazesim's constructor",
    **{
        f"Field.c_sf_{kind}": "serves wb_supervisor_field_get_sf_* (native_calls.py)"
        for kind in ("bool", "int32", "float", "vec2f", "vec3f", "rotation", "color", "string")
    },
    # Devices whose C side does not exist yet (see WITHOUT_FUNCTIONS).
    **{f"Robot.get{name}": "no C header yet (test_capi_devices.WITHOUT_C)" for name in WITHOUT_C},
}


def snake(method: str) -> str:
    """Webots' C words of a method's name: ``getSFVec3f`` is ``get_sf_vec3f``."""
    words = re.sub(r"([a-z0-9])([A-Z])", r"\1_\2", method)
    return re.sub(r"([A-Z]+)([A-Z][a-z])", r"\1_\2", words).lower()


def c_prefix(name: str) -> str:
    if name in ("Node", "Field"):
        return f"wb_supervisor_{name.lower()}_"
    if name == "DifferentialWheels":
        return "wb_differential_wheels_"
    module = next(m for m, names in controller.SUBMODULE_CLASSES.items() if name in names)
    return f"wb_{module}_"


def own_methods(cls: type) -> list[str]:
    """The public methods a class of the Python module defines or inherits from mazesim's
    classes, but those of its base class of the module (Device, Robot), checked there."""
    base = Device if issubclass(cls, Device) and cls is not Device else None
    if cls in (controller.Supervisor, controller.DifferentialWheels):
        base = controller.Robot
    names = []
    for name in dir(cls):
        if name.startswith("_"):
            continue
        value = inspect.getattr_static(cls, name)
        if not isinstance(value, (staticmethod, classmethod)) and not inspect.isfunction(value):
            continue
        if base is not None and hasattr(base, name):
            continue
        names.append(name)
    return names


def python_methods() -> list[tuple[str, str]]:
    """(class, method) of every public method of the classes with C functions."""
    pairs = []
    # Webots 8's DifferentialWheels has no submodule (Webots 8's module had none).
    for names in [*controller.SUBMODULE_CLASSES.values(), ("DifferentialWheels",)]:
        for name in names:
            cls = getattr(controller, name)
            if name not in WITHOUT_FUNCTIONS:
                pairs.extend((name, method) for method in own_methods(cls))
    return sorted(pairs)


def c_name(name: str, method: str) -> str:
    key = f"{name}.{method}"
    if key in C_NAMES:
        return C_NAMES[key]
    devices = {n for n in controller.__all__ if n != "Device"}
    if name == "Robot" and method.startswith("get") and method[3:] in devices:
        return "wb_robot_get_device"
    # Python's aliases (Motor.getMaxForce is getAvailableTorque) are Webots' own functions.
    return c_prefix(name) + snake(method)


def declared_c_functions() -> set[str]:
    text = "\n".join(path.read_text() for path in HEADERS.rglob("*.h"))
    text = re.sub(r"/\*.*?\*/|//[^\n]*", "", text, flags=re.S)
    return set(re.findall(r"\b(wb_\w+)\s*\(", text))


@cache
def defined_c_functions() -> frozenset[str]:
    """The functions mazesim's controller library defines (its objects' exported symbols)."""
    import tempfile

    names: set[str] = set()
    with tempfile.TemporaryDirectory() as work:
        for source in sorted((CAPI / "src").glob("*.c")):
            obj = Path(work) / f"{source.stem}.o"
            subprocess.run(
                ["gcc", "-c", "-w", "-I", str(CAPI / "include"), str(source), "-o", str(obj)],
                check=True,
            )
            symbols = subprocess.run(
                ["nm", "--defined-only", "-g", str(obj)], check=True, capture_output=True, text=True
            ).stdout
            names.update(line.split()[-1] for line in symbols.splitlines() if line.strip())
    return frozenset(names)


@cache
def cpp_methods() -> dict[str, set[str]]:
    """The methods of each class of namespace webots in mazesim's C++ headers, inherited ones
    too, read from the headers as g++ preprocesses them."""
    includes = "".join(f"#include <webots/{path.name}>\n" for path in sorted(HEADERS.glob("*.hpp")))
    text = subprocess.run(
        ["g++", "-E", "-P", "-x", "c++", "-I", str(CAPI / "include"), "-"],
        input=includes,
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    own: dict[str, set[str]] = {}
    bases: dict[str, str] = {}
    for found in re.finditer(r"\bclass\s+(\w+)\s*(?::\s*public\s+(\w+)\s*)?\{", text):
        depth, start, names = 1, found.end(), set()
        for index in range(found.end(), len(text)):
            char = text[index]
            if char in "{}":
                if depth == 1:
                    names.update(re.findall(r"(\w+)\s*\(", text[start:index]))
                depth += 1 if char == "{" else -1
                start = index + 1
                if depth == 0:
                    break
        own[found.group(1)] = names
        if found.group(2):
            bases[found.group(1)] = found.group(2)
    methods = {}
    for name in own:
        methods[name], base = set(own[name]), bases.get(name)
        while base:
            methods[name] |= own.get(base, set())
            base = bases.get(base)
    return methods


PAIRS = python_methods()


def test_python_methods_are_found_and_mapped_by_webots_rule() -> None:
    keys = {f"{name}.{method}" for name, method in PAIRS}
    assert {"Motor.enableTorqueFeedback", "GPS.getSpeed", "Camera.saveImage"} <= keys
    assert c_name("GPS", "getSpeedVector") == "wb_gps_get_speed_vector"
    assert c_name("Field", "setSFVec3f") == "wb_supervisor_field_set_sf_vec3f"
    assert c_name("Motor", "setControlPID") == "wb_motor_set_control_pid"
    assert c_name("Robot", "getCamera") == "wb_robot_get_device"
    assert c_name("Motor", "getMaxForce") == "wb_motor_get_max_force"
    # Every exception names a method the module has.
    assert set(PYTHON_ONLY) | set(C_NAMES) | set(CPP_NAMES) <= {f"{n}.{m}" for n, m in PAIRS} | {
        f"Robot.get{n}" for n in WITHOUT_FUNCTIONS
    }


def test_every_python_method_has_its_c_function_declared() -> None:
    declared = declared_c_functions()
    missing = [
        f"{n}.{m}: {c_name(n, m)}"
        for n, m in PAIRS
        if f"{n}.{m}" not in PYTHON_ONLY and c_name(n, m) not in declared
    ]
    assert missing == []
    stale = [
        key for key in PYTHON_ONLY if c_name(*key.split(".")) in declared - {"wb_robot_get_device"}
    ]
    assert stale == [], "these have a C function now: drop their exceptions"


@NEEDS_COMPILERS
@pytest.mark.skipif(shutil.which("nm") is None, reason="needs nm")
def test_every_declared_c_function_is_defined_in_the_library() -> None:
    defined = defined_c_functions()
    assert "wb_robot_step" in defined
    # <webots/radio.h> is declared only, on purpose: see its comment.
    radio = set(re.findall(r"\b(wb_radio_\w+)\s*\(", (HEADERS / "radio.h").read_text()))
    assert sorted(declared_c_functions() - defined - radio) == []


#: C functions without a Python method, and why.
C_ONLY = {
    "wb_robot_init": "C's start of a controller (Python's Robot() does it)",
    "wb_robot_cleanup": "C's end of a controller (Python's process exit does it)",
    "wb_robot_get_supervisor": "C's test of the robot's kind (Python's class says it)",
    "wb_device_get_type": "an older name of wb_device_get_node_type, whose Python name "
    "getType is a DistanceSensor's and a TouchSensor's sensor type",
    **{
        f"wb_{device}_get_lookup_table_size": "C reads the table's length apart from its rows"
        for device in ("accelerometer", "compass", "distance_sensor", "gyro", "light_sensor",
                       "touch_sensor")
    },
}  # fmt: skip


def test_every_c_function_has_its_python_method() -> None:
    # A C function without a Python method is a call a C controller makes that its Python
    # twin cannot (Webots 8's DifferentialWheels was once C only).
    radio = set(re.findall(r"\b(wb_radio_\w+)\s*\(", (HEADERS / "radio.h").read_text()))
    # A method of Webots' table the class does not define answers as not simulated, in C too.
    none = WebotsClass(frozenset(), {}, frozenset())
    # Every class with C functions, those that define no method of their own (Brake, Skin) too.
    named = {n for names in controller.SUBMODULE_CLASSES.values() for n in names}
    with_c = (named | {"DifferentialWheels"}) - set(WITHOUT_FUNCTIONS)
    answered = {(n, m) for n in with_c for m in webots_classes().get(n, none).methods}
    mapped = {c_name(name, method) for name, method in set(PAIRS) | answered}
    assert sorted(declared_c_functions() - mapped - radio - set(C_ONLY)) == []
    assert set(C_ONLY) <= declared_c_functions()


@NEEDS_COMPILERS
def test_every_python_method_has_its_cpp_method() -> None:
    methods = cpp_methods()
    assert "getValue" in methods["DistanceSensor"] and "getName" in methods["Motor"]
    missing = []
    for name, method in PAIRS:
        key = f"{name}.{method}"
        if key in PYTHON_ONLY:
            continue
        wanted = CPP_NAMES.get(key, method)
        if wanted not in methods.get(name, set()):
            missing.append(f"{name}::{wanted}")
    assert missing == []


@NEEDS_COMPILERS
@pytest.mark.usefixtures("own_cache")
def test_c_and_cpp_controllers_read_lens_torque_tables_and_robot_as_python_does(
    capfd: pytest.CaptureFixture[str],
) -> None:
    twins = (
        CONTROLLERS / "lens_torque_twin" / "lens_torque_twin.py",
        CONTROLLERS / "c_lens_torque" / "c_lens_torque.c",
        CONTROLLERS / "cpp_lens_torque" / "cpp_lens_torque.cpp",
    )
    runs, outputs = run_twins(capfd, *twins, seconds=0.5)
    assert [(run.exit_status, run.error) for run in runs] == [(0, ""), (0, ""), (0, "")]
    assert outputs[1] == outputs[0] and outputs[2] == outputs[0]
    # The e-puck's camera has neither zoom nor focus (Webots' messages say so on stderr), its
    # motors the E-puck PROTO's maximum torque and the available torque set (5), its encoders
    # no brake, its battery sensor no reading before its first period (the period set), and
    # the run no user and no robot window.
    assert outputs[0].splitlines() == [
        "fov 0.840000 0.840000 0.840000",
        "exposure 1.000000 near 0.005500",
        "focus 0.000000 0.000000 0.000000 0.000000",
        "torque 5.000000 10.000000",
        "force 5.000000 10.000000",
        "multiplier 1.000000 brake 0",
        "light table 2 1.000000 4095.000000 0.010000",
        "accelerometer table 2",
        "encoder type 0 brake 0",
        "dms 12°34'57.36\"",
        "battery none 32",
        'type 34 urdf <robot name="my_e-puck">',
        "window none",
        "feedback 0.000000 32",
    ]
