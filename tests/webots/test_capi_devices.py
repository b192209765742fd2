"""Every device class of the Python ``controller`` module has its C header and its C++ class in
mazesim's controller library, so that a C or C++ controller can use what a Python one can."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from mazesim.webots import controller
from mazesim.webots.devices import Device
from mazesim.webots.importer import import_wbt
from mazesim.webots.native_controller import CAPI
from mazesim.webots.requirements import (
    RANGE_READINGS,
    motor_limits,
    prepare_controller,
    range_readings,
)
from native_controllers import NEEDS_COMPILERS, run_twins

CONTROLLERS = Path(__file__).resolve().parents[1] / "data" / "controllers"

HEADERS = CAPI / "include" / "webots"
#: Device classes of the Python module without a C or C++ side yet, all inert in Python (their
#: readings are Webots' values for a missing device, their commands are accepted and do
#: nothing): a C or C++ controller that includes one's header is named as needing it before it
#: is built.
WITHOUT_C = {
    "Altimeter",
    "Brake",
    "Connector",
    "Pen",
    "Radar",
    "RangeFinder",
    "Skin",
    "Speaker",
    "VacuumGripper",
}


def device_classes() -> list[tuple[str, str]]:
    """(submodule, class) of each device class of the Python module but Device itself."""
    return [
        (module, name)
        for module, names in controller.SUBMODULE_CLASSES.items()
        for name in names
        if name != "Device"
        and isinstance(getattr(controller, name), type)
        and issubclass(getattr(controller, name), Device)
    ]


def cpp_text() -> str:
    return "\n".join(path.read_text() for path in sorted(HEADERS.glob("*.hpp")))


@pytest.mark.parametrize(("module", "name"), device_classes())
def test_a_python_device_class_has_its_c_header_and_cpp_class(module: str, name: str) -> None:
    if name in WITHOUT_C:
        assert not (HEADERS / f"{module}.h").exists(), f"{name} is in C now: drop its exception"
        return
    assert (HEADERS / f"{module}.h").is_file(), f"<webots/{module}.h> for {name}"
    assert (HEADERS / f"{name}.hpp").is_file(), f"<webots/{name}.hpp> for {name}"
    text = cpp_text()
    assert re.search(rf"class {name}\b|MAZESIM_SENSOR\({name},", text), f"C++ class {name}"
    # Robot::getDevice makes the C++ class of each device it finds.
    assert f"new {name}(tag)" in (HEADERS / "Robot.hpp").read_text()


def test_the_exceptions_are_device_classes_of_the_python_module() -> None:
    assert WITHOUT_C <= {name for _, name in device_classes()}
    assert {"InertialUnit", "Lidar"} <= {name for _, name in device_classes()} - WITHOUT_C


@NEEDS_COMPILERS
@pytest.mark.usefixtures("own_cache")
def test_c_and_cpp_controllers_read_an_inertial_unit_and_a_lidar_as_python_does(
    capfd: pytest.CaptureFixture[str],
) -> None:
    path = CONTROLLERS / "worlds" / "inertial_lidar_arena.wbt"
    world, report = import_wbt(str(path))
    twins = (
        CONTROLLERS / "inertial_lidar_twin" / "inertial_lidar_twin.py",
        CONTROLLERS / "c_inertial_lidar" / "c_inertial_lidar.c",
        CONTROLLERS / "cpp_inertial_lidar" / "cpp_inertial_lidar.cpp",
    )
    runs, outputs = run_twins(capfd, *twins, world=world, seconds=1.0, report=report)
    assert [(run.exit_status, run.error) for run in runs] == [(0, ""), (0, ""), (0, "")]
    assert outputs[1] == outputs[0] and outputs[2] == outputs[0]
    lines = outputs[0].splitlines()
    yaws = [float(line.split()[3]) for line in lines if line.startswith("rpy ")]
    # The e-puck starts turned 0.5 rad and spins left on the spot.
    assert len(yaws) == 4 and yaws[0] > 0.5 and yaws == sorted(yaws)
    assert all(line.startswith("rpy 0.000000 0.000000 ") for line in lines[::4])
    # The lidar's range image is its node's 360 points of one layer (mazesim.webots.scanners);
    # it has no point cloud, which the run says at its start.
    assert lines[2] == "ranges 360 resolution 360 layers 1"
    assert lines[3] == "cloud none points 360 fov 6.280000 max 0.500000"
    assert runs[1].xs == runs[0].xs and runs[2].final_pose == runs[0].final_pose
    calls = (
        ["wb_lidar_get_point_cloud"],
        ["getPointCloud"],
    )
    for twin, read in zip(twins, (calls[1], calls[0], calls[1])):
        prepared = prepare_controller(str(twin))
        assert prepared.runnable
        assert prepared.missing == [RANGE_READINGS.format(calls=", ".join(read))]


def test_a_compiled_controllers_sources_below_its_folder_are_read_for_what_it_calls(
    tmp_path: Path,
) -> None:
    # A Makefile's src/*.cpp holds the calls; a copy of Webots' header declares, not calls.
    (tmp_path / "src").mkdir()
    (tmp_path / "webots").mkdir()
    (tmp_path / "main.cpp").write_text("int main() { return 0; }\n")
    (tmp_path / "src" / "walls.cpp").write_text("void f(L *l) { l->getPointCloud(); }\n")
    (tmp_path / "webots" / "motor.h").write_text("void wb_motor_set_acceleration(int, double);\n")
    assert range_readings(str(tmp_path / "main.cpp"), "cpp") == ["getPointCloud"]
    assert motor_limits(str(tmp_path / "main.cpp"), "cpp") == []
    # A Python controller's own packages are read for their imports, not for these calls.
    (tmp_path / "main.py").write_text("from controller import Robot\n")
    assert range_readings(str(tmp_path / "main.py"), "python") == []
