"""Webots controllers written in C: built with gcc against mazesim's controller library, run as
a child process in lockstep, and compared step for step with the same logic in Python."""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path

import pytest

import mazesim
from mazesim.errors import ControllerBuildError, MissingDependencyError
from mazesim.webots import run_controller
from mazesim.webots.camera import Camera, CameraRecognitionObject
from mazesim.webots.keyboard import KeyScript
from mazesim.webots.native_controller import CAPI, build
from mazesim.webots.node_types import NODE_TYPES
from mazesim.webots.requirements import NO_DISPLAY, prepare_controller
from mazesim_process import mazesim_command
from native_controllers import NEEDS_COMPILERS, run_twins, write_source

CONTROLLERS = Path(__file__).resolve().parents[1] / "data" / "controllers"
AVOIDER = CONTROLLERS / "c_wall_avoider" / "c_wall_avoider.c"
CPP_AVOIDER = CONTROLLERS / "cpp_wall_avoider" / "cpp_wall_avoider.cpp"

pytestmark = [NEEDS_COMPILERS, pytest.mark.usefixtures("own_cache")]


def write_controller(folder: Path, name: str, body: str) -> Path:
    """A C controller ``folder/name/name.c`` whose ``main`` runs ``body``."""
    return write_source(
        folder,
        name,
        "#include <stdio.h>\n#include <webots/robot.h>\n#include <webots/motor.h>\n"
        "#include <webots/distance_sensor.h>\n#include <webots/utils/ansi_codes.h>\n"
        f"int main(void) {{\n  wb_robot_init();\n{body}\n  wb_robot_cleanup();\n  return 0;\n}}\n",
    )


def test_a_c_controller_drives_bit_for_bit_as_its_python_twin(
    capfd: pytest.CaptureFixture[str],
) -> None:
    twin = CONTROLLERS / "wall_avoider_twin.py"
    (in_c, in_python), (c_out, python_out) = run_twins(capfd, AVOIDER, twin, seconds=4.0, seed=3)
    assert (in_c.exit_status, in_c.error) == (0, "")
    assert in_python.exit_status == 0, in_python.error
    assert in_c.steps == in_python.steps > 100
    assert in_c.distance_m > 0.2
    # The same noisy readings, the same commands: the same trajectory, bit for bit.
    assert in_c.xs == in_python.xs
    assert in_c.ys == in_python.ys
    assert in_c.final_pose == in_python.final_pose
    assert c_out == python_out
    assert c_out.startswith("devices ") and " ps0 is a distance sensor\n" in c_out
    assert re.search(r"^t 0\.992 encoder -?\d+\.\d{4}$", c_out, re.MULTILINE)


def test_cameras_inertial_sensors_light_sensors_and_keys_read_as_in_python(
    capfd: pytest.CaptureFixture[str],
) -> None:
    keys = KeyScript.parse("0.2 A 0.1\n0.5 UP 0.05\n")
    twins = CONTROLLERS / "c_every_device/c_every_device.c", CONTROLLERS / "every_device_twin.py"
    runs, outputs = run_twins(capfd, *twins, seconds=1.0, keys=keys)
    assert [(r.exit_status, r.error) for r in runs] == [(0, ""), (0, "")]
    assert outputs[0] == outputs[1]
    lines = outputs[0].splitlines()
    assert lines[0] == "camera 52x39"
    assert "key 65 at 0.224" in lines and any(line.startswith("key 315 ") for line in lines)
    images = [line for line in lines if line.startswith("image ")]
    assert len(images) == 4 and all(int(line.split()[1]) > 0 for line in images)
    assert runs[0].xs == runs[1].xs and runs[0].final_pose == runs[1].final_pose


def test_a_build_is_cached_and_rebuilt_when_a_source_changes(tmp_path: Path) -> None:
    folder = tmp_path / "controllers" / "copy"
    shutil.copytree(AVOIDER.parent, folder)
    main = folder / "copy.c"
    (folder / "c_wall_avoider.c").rename(main)
    first = build(main)
    assert first.program is not None and "compiled with" in first.note
    second = build(main)
    assert second.program == first.program and "taken from the cache" in second.note
    (folder / "steering.h").write_text((folder / "steering.h").read_text() + "\n/* edited */\n")
    third = build(main)
    assert third.program != first.program and "compiled with" in third.note


def test_a_compile_error_quotes_the_compiler(tmp_path: Path) -> None:
    source = write_controller(tmp_path, "broken", "  int x = ;")
    with pytest.raises(ControllerBuildError) as caught:
        prepare_controller(str(source))
    message = str(caught.value)
    assert "expected a C controller that compiles, found compiler errors" in message
    assert re.search(r"broken\.c:\d+:\d+: error: expected expression", message)


def test_a_cpp_controller_that_relies_on_another_compilers_transitive_headers_builds(
    tmp_path: Path,
) -> None:
    """Sources that use std::unique_ptr and memcpy without including <memory> and <cstring>
    (which the author's compiler brought in through <iomanip> and <string>) are built with the
    headers g++ names, and the build says so; a real error still stops the build."""
    source = tmp_path / "owner" / "owner.cpp"
    source.parent.mkdir()
    source.write_text(
        "#include <iomanip>\n#include <webots/robot.h>\n"
        "int main() {\n  wb_robot_init();\n  std::unique_ptr<int> kept(new int(4));\n"
        "  int copy = 0;\n  memcpy(&copy, kept.get(), sizeof copy);\n"
        "  wb_robot_cleanup();\n  return copy == 4 ? 0 : 1;\n}\n"
    )
    built = build(source)
    assert built.program is not None, built.note
    assert "<memory>, <cstring>" in built.note and "without including them" in built.note
    source.write_text(source.read_text().replace("int copy = 0;", "int copy = ;"))
    with pytest.raises(ControllerBuildError, match="expected a C\\+\\+ controller that compiles"):
        build(source)


def test_a_cpp_controller_using_a_standard_name_g_plus_plus_does_not_trace_builds(
    tmp_path: Path,
) -> None:
    """`function` after `using namespace std`, with only <memory> included (macOS' libc++
    brings <functional> in with it; g++ names no header for it): built with every standard
    header included first, and the build says so; a real error still stops the build."""
    source = tmp_path / "steer" / "steer.cpp"
    source.parent.mkdir()
    source.write_text(
        "#include <memory>\n#include <webots/robot.h>\nusing namespace std;\n"
        "struct steering {\n  steering(function<int(int)> pick) : pick_(pick) {}\n"
        "  function<int(int)> pick_;\n};\n"
        "int main() {\n  wb_robot_init();\n  steering left{[](int x) { return x - 4; }};\n"
        "  wb_robot_cleanup();\n  return left.pick_(4);\n}\n"
    )
    built = build(source)
    assert built.program is not None, built.note
    assert "every standard header included first" in built.note
    source.write_text(source.read_text().replace("return x - 4;", "return x - ;"))
    with pytest.raises(ControllerBuildError, match="expected a C\\+\\+ controller that compiles"):
        build(source)


def test_a_cpp_controller_using_a_standard_class_known_only_as_declared_builds(
    tmp_path: Path,
) -> None:
    """A std::array field with only <map> and <string> included (libstdc++'s <tuple>, which
    <map> includes, included <array> before GCC 10; today's declares std::array only, and g++
    says the field has an incomplete type, naming no header): built with every standard header
    included first, and the build says so; a real error still stops the build."""
    source = tmp_path / "plus" / "plus.cpp"
    source.parent.mkdir()
    source.write_text(
        "#include <map>\n#include <string>\n#include <webots/robot.h>\n"
        "struct arms {\n  std::array<std::string, 2> names;\n};\n"
        'int main() {\n  wb_robot_init();\n  arms maze{{"open", "closed"}};\n'
        "  wb_robot_cleanup();\n  return maze.names[1].size() == 6 ? 0 : 1;\n}\n"
    )
    built = build(source)
    assert built.program is not None, built.note
    assert "every standard header included first" in built.note
    assert "knows only as declared" in built.note
    source.write_text(source.read_text().replace("return maze", "return ; maze"))
    with pytest.raises(ControllerBuildError, match="expected a C\\+\\+ controller that compiles"):
        build(source)


def test_without_a_compiler_the_error_says_what_to_install(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("CC", "no-such-cc-for-mazesim")
    with pytest.raises(MissingDependencyError, match=r"expected a C compiler \(no-such-cc"):
        build(AVOIDER)


def test_a_crashing_controller_is_reported_with_its_signal(tmp_path: Path) -> None:
    source = write_controller(
        tmp_path,
        "crasher",
        "  for (int i = 0; i < 3; i++) wb_robot_step(32);\n"
        "  volatile int *nowhere = 0;\n  *nowhere = 1;",
    )
    run = run_controller(source, mazesim.load_world("arena"), seconds=2.0)
    assert run.exit_status == 1
    assert run.error == "the C controller crashed: killed by SIGSEGV\n"
    assert run.steps == 3
    cpp = write_source(
        tmp_path,
        "cpp_crasher",
        "#include <webots/Robot.hpp>\nint main() {\n  webots::Robot robot;\n  robot.step(32);\n"
        "  volatile int *nowhere = nullptr;\n  *nowhere = 1;\n}\n",
        ".cpp",
    )
    run = run_controller(cpp, mazesim.load_world("arena"), seconds=2.0)
    assert run.error == "the C++ controller crashed: killed by SIGSEGV\n", "its own language"


def test_a_tag_of_another_kind_of_device_gets_webots_message(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    source = write_controller(
        tmp_path,
        "mixup",
        "  extern void wb_led_set(unsigned short, int);\n"
        '  WbDeviceTag motor = wb_robot_get_device("left wheel motor");\n'
        "  wb_led_set(motor, 1);\n  wb_distance_sensor_enable(motor, 32);\n"
        "  while (wb_robot_step(32) != -1) {}",
    )
    run = run_controller(source, mazesim.load_world("arena"), seconds=0.5)
    assert (run.exit_status, run.error) == (0, "")
    errors = capfd.readouterr().err.splitlines()
    assert "Error: wb_led_set(): invalid device tag." in errors
    assert "Error: wb_distance_sensor_enable(): invalid device tag." in errors


def test_a_controller_that_steps_on_after_the_end_ends_at_its_next_step(tmp_path: Path) -> None:
    # Webots' library exits (EXIT_SUCCESS) at the step after the one that returned -1: the run
    # does not have to stop it.
    source = write_controller(tmp_path, "forever", "  for (;;) wb_robot_step(32);")
    run = run_controller(source, mazesim.load_world("arena"), seconds=0.5)
    assert run.reached_end and not run.stopped
    assert run.exit_status == 0
    assert run.simulated_seconds == pytest.approx(0.512)


def test_a_controller_calling_on_after_its_cleanup_at_the_end_ends_quietly(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    # A student's step(): on -1 it calls wb_robot_cleanup() and returns, and the maze loop
    # around it sets the motors and steps again. Webots ends such a controller itself.
    source = write_controller(
        tmp_path,
        "after_cleanup",
        '  WbDeviceTag left = wb_robot_get_device("left wheel motor");\n'
        "  for (int i = 0; i < 100; i++) {\n"
        "    if (wb_robot_step(32) == -1) wb_robot_cleanup();\n"
        "    wb_motor_set_velocity(left, 1.0);\n  }",
    )
    run = run_controller(source, mazesim.load_world("arena"), seconds=0.5)
    assert run.reached_end
    assert (run.exit_status, run.error) == (0, "")
    assert "the link to mazesim is closed" not in capfd.readouterr().err


@pytest.mark.parametrize(
    ("body", "named"),
    [
        (
            "  extern void wb_microphone_enable(unsigned short, int);\n"
            "  extern const void *wb_microphone_get_sample_data(unsigned short);\n"
            "  wb_microphone_enable(1, 32);\n  wb_microphone_get_sample_data(1);",
            "wb_microphone_enable, wb_microphone_get_sample_data",
        ),
        # Webots' older C API named its functions without wb_.
        (
            "  extern int robot_step(int);\n"
            "  extern void distance_sensor_enable(unsigned short, int);\n"
            "  distance_sensor_enable(1, 64);\n  robot_step(64);",
            "distance_sensor_enable, robot_step",
        ),
    ],
)
def test_functions_the_library_lacks_are_named_and_the_controller_is_not_started(
    tmp_path: Path, body: str, named: str
) -> None:
    source = write_controller(tmp_path, "lacking", body)
    prepared = prepare_controller(str(source))
    assert not prepared.runnable
    assert prepared.missing == [f"Webots C API function(s) mazesim does not implement: {named}"]
    run = run_controller(source, mazesim.load_world("arena"), seconds=1.0, prepared=prepared)
    assert (run.steps, run.exit_status) == (0, 1)
    assert run.error.startswith("controller not run: Webots C API function(s)")


def test_every_header_the_library_lacks_is_named_before_building(tmp_path: Path) -> None:
    source = write_controller(tmp_path, "ranging", "")
    (source.parent / "ranging.h").write_text("#include <webots/microphone.h>\n")
    headers = '#include <webots/vehicle/driver.h>\n#include "ranging.h"\n'
    source.write_text(headers + source.read_text())
    prepared = prepare_controller(str(source))
    assert not prepared.runnable
    assert prepared.missing == [
        "Webots C API header(s) mazesim does not provide: webots/microphone.h, "
        "webots/vehicle/driver.h"
    ]


def test_a_controller_that_includes_the_radio_header_builds_and_one_calling_it_is_named(
    tmp_path: Path,
) -> None:
    # Webots' DIS course e-pucks include <webots/radio.h> and talk over Emitters only.
    talker = write_controller(tmp_path, "talker", '  printf("%d\\n", wb_robot_step(32));')
    talker.write_text("#include <webots/radio.h>\n" + talker.read_text())
    prepared = prepare_controller(str(talker))
    assert prepared.runnable and prepared.missing == []
    run = run_controller(talker, mazesim.load_world("arena"), seconds=0.5, prepared=prepared)
    assert (run.exit_status, run.error) == (0, "")
    call = '  wb_radio_enable(wb_robot_get_device("radio"), 32);'
    caller = write_controller(tmp_path, "caller", call)
    caller.write_text("#include <webots/radio.h>\n" + caller.read_text())
    assert prepare_controller(str(caller)).missing == [
        "Webots C API function(s) mazesim does not implement: wb_radio_enable"
    ]


def test_sources_a_makefile_lists_from_other_folders_are_built_as_webots_finds_them(
    tmp_path: Path,
) -> None:
    shared = tmp_path / "localization"
    shared.mkdir()
    (shared / "pose.h").write_text("double pose_x(void);\ndouble pose_scale(void);\n")
    (shared / "pose.c").write_text(
        '#include "pose.h"\ndouble pose_x(void) { return 2 * pose_scale(); }\n'
    )
    (shared / "scale.c").write_text("double pose_scale(void) { return 0.25; }\n")
    # A library of its own main, not listed: left out as Webots' Makefile leaves it.
    (shared / "localization.c").write_text("int main(void) { return 3; }\n")
    leader = write_controller(tmp_path, "leader", '  printf("%g\\n", pose_x());')
    leader.write_text('#include "../localization/pose.h"\n' + leader.read_text())
    # scale.c listed by a path that does not exist, found by make's vpath under its name in
    # another listed folder; continued over two lines; a comment and a variable left out.
    (leader.parent / "Makefile").write_text(
        "C_SOURCES = leader.c ../localization/pose.c \\\n  localization/scale.c $(EXTRA) # x.c\n"
        "include $(WEBOTS_HOME_PATH)/resources/Makefile.include\n"
    )
    built = build(leader)
    assert built.program is not None and built.missing == []
    run = run_controller(leader, mazesim.load_world("arena"), seconds=0.1)
    assert (run.exit_status, run.error) == (0, "")


def test_a_cpp_controller_drives_as_the_c_one_and_names_classes_it_lacks(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    (in_cpp, in_c), (cpp_out, c_out) = run_twins(capfd, CPP_AVOIDER, AVOIDER, seconds=2.0, seed=5)
    assert (in_cpp.exit_status, in_cpp.error) == (0, "")
    assert (in_cpp.xs, in_cpp.ys) == (in_c.xs, in_c.ys) and in_cpp.distance_m > 0.1
    assert cpp_out == c_out
    source = tmp_path / "bt" / "bt.cpp"
    source.parent.mkdir()
    source.write_text("#include <webots/Microphone.hpp>\nint main() { return 0; }\n")
    prepared = prepare_controller(str(source))
    assert (prepared.language, prepared.runnable) == ("cpp", False)
    assert prepared.missing == [
        "Webots C++ API header(s) mazesim does not provide: webots/Microphone.hpp"
    ]


def test_the_run_says_at_its_start_what_is_missing_and_keeps_it_in_its_summary(
    tmp_path: Path,
) -> None:
    folder = tmp_path / "controllers" / "fuzzy"
    folder.mkdir(parents=True)
    (folder / "helpers.py").write_text("import skfuzzy_not_installed_here\nGAIN = 2\n")
    (folder / "models").mkdir()
    (folder / "models" / "__init__.py").write_text("from .fit import *\n")
    (folder / "models" / "fit.py").write_text("import pandas_not_installed_here\n")
    (folder / "models" / "unused.py").write_text("import never_imported_package\n")
    (folder / "fuzzy.py").write_text(
        "import math\nimport helpers\nfrom models import fit\nfrom controller import Robot\n"
        "try:\n    import optional_package_for_mazesim_tests\nexcept ImportError:\n    pass\n"
    )
    result = mazesim_command(
        "webots", "run", str(folder), "--seconds", "1", "--out", "out", cwd=tmp_path
    )
    assert result.returncode == 1
    statement = (
        "mazesim: missing: Python package(s) not installed: pandas_not_installed_here, "
        "skfuzzy_not_installed_here"
    )
    lines = result.stderr.splitlines()
    assert lines[0] == statement
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["missing_features"] == [statement.removeprefix("mazesim: missing: ")]


def test_the_cli_runs_a_c_controller_folder_and_logs_its_build(tmp_path: Path) -> None:
    build(AVOIDER)  # built already by the twin test when the module runs whole
    result = mazesim_command(
        "webots", "run", str(AVOIDER.parent), "--seconds", "1", "--out", "out", cwd=tmp_path
    )
    assert result.returncode == 0, result.stderr
    assert result.stderr.splitlines()[0].startswith(
        "mazesim: C controller c_wall_avoider.c: built earlier, taken from the cache "
    )
    assert result.stdout.splitlines()[0].startswith("devices ")
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["missing_features"] == [] and summary["distance_m"] > 0.05


def test_the_node_type_header_numbers_the_types_as_the_python_module_does() -> None:
    text = (CAPI / "include" / "webots" / "nodes.h").read_text()
    numbers = dict(re.findall(r"WB_NODE_(\w+) = (\d+),", text))
    assert {name: int(numbers[name]) for name in NODE_TYPES} == {
        name: i for i, name in enumerate(NODE_TYPES)
    }


def test_a_tk_window_without_a_display_is_named_before_the_run(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.setattr("mazesim.webots.virtual_display.xvfb_program", lambda: None)
    (tmp_path / "view.py").write_text("from turtle import *\n")
    (tmp_path / "mouse.py").write_text("import view\nfrom controller import Robot\n")
    prepared = prepare_controller(str(tmp_path / "mouse.py"))
    assert NO_DISPLAY in prepared.missing and not prepared.runnable
    monkeypatch.setenv("DISPLAY", ":0")
    assert NO_DISPLAY not in prepare_controller(str(tmp_path / "mouse.py")).missing


def test_a_tk_controller_without_a_display_is_not_started(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Started, it would wait forever for the thread whose window Tk refuses.
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.setattr("mazesim.webots.virtual_display.xvfb_program", lambda: None)
    (tmp_path / "mouse.py").write_text(
        "import threading, turtle\nfrom controller import Robot\n"
        "ready = threading.Event()\n"
        "threading.Thread(target=lambda: (turtle.Turtle(), ready.set())).start()\n"
        "ready.wait()\nRobot().step(32)\n"
    )
    run = run_controller(str(tmp_path / "mouse.py"), mazesim.load_world("arena"), seconds=1.0)
    assert run.steps == 0 and run.exit_status != 0
    assert run.error.startswith("controller not run: ") and NO_DISPLAY in run.error


def test_a_controller_that_is_a_fifo_or_too_long_is_refused_before_it_is_read(
    tmp_path: Path,
) -> None:
    """A C controller that is a FIFO no process writes to is refused at once (its read would
    block for ever), and one longer than the text bound before it is read whole."""
    import os

    from mazesim._paths import MAX_TEXT_CHARACTERS

    (tmp_path / "fifo").mkdir()
    fifo = tmp_path / "fifo" / "fifo.c"
    os.mkfifo(fifo)
    with pytest.raises(mazesim.MazesimIOError, match="expected a regular file, found a FIFO"):
        build(fifo)
    (tmp_path / "long").mkdir()
    long = tmp_path / "long" / "long.c"
    with long.open("wb") as handle:
        handle.truncate(MAX_TEXT_CHARACTERS + 1)  # sparse: takes no room on the disk
    with pytest.raises(ControllerBuildError, match="at most 67108864 bytes"):
        build(long)


RECOGNITION_BODY = """
  WbDeviceTag camera = wb_robot_get_device("camera");
  wb_camera_recognition_enable(camera, 32);
  wb_robot_step(32);
  const WbCameraRecognitionObject *objects = wb_camera_recognition_get_objects(camera);
  printf("has %d period %d objects %d array %d same %d\\n", wb_camera_has_recognition(camera),
         wb_camera_recognition_get_sampling_period(camera),
         wb_camera_recognition_get_number_of_objects(camera), objects != NULL,
         objects == wb_camera_recognition_get_objects(camera));
"""


def test_a_c_controller_calls_camera_recognition_as_a_python_one_does(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    # The e-puck's camera has no Recognition node: Webots' error, and nothing recognised.
    source = write_controller(tmp_path, "recogniser", RECOGNITION_BODY)
    source.write_text("#include <webots/camera.h>\n" + source.read_text())
    assert prepare_controller(str(source)).missing == []
    run = run_controller(source, mazesim.load_world("arena"), seconds=0.5)
    assert (run.exit_status, run.error) == (0, "")
    out, err = capfd.readouterr()
    assert out.splitlines()[-1] == "has 0 period 0 objects 0 array 1 same 1"
    assert (
        "Error: wb_camera_recognition_enable() called on a Camera without Recognition node."
        in err.splitlines()
    )


def test_a_cpp_controller_reads_the_recognition_object_struct(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    source = write_source(
        tmp_path,
        "recogniser",
        "#include <cstdio>\n#include <webots/Camera.hpp>\n#include <webots/Robot.hpp>\n"
        "#include <webots/camera_recognition_object.h>\n"
        "int main() {\n  webots::Robot robot;\n"
        '  webots::Camera *camera = robot.getCamera("camera");\n'
        "  camera->recognitionEnable(32);\n  robot.step(32);\n"
        "  const webots::CameraRecognitionObject *objects = camera->getRecognitionObjects();\n"
        "  const WbCameraRecognitionObject *same = objects;\n"
        '  std::printf("objects %d %d\\n", camera->getRecognitionNumberOfObjects(),\n'
        "              same == camera->getRecognitionObjects());\n  return 0;\n}\n",
        suffix=".cpp",
    )
    assert prepare_controller(str(source)).missing == []
    run = run_controller(source, mazesim.load_world("arena"), seconds=0.5)
    assert (run.exit_status, run.error) == (0, "")
    assert capfd.readouterr().out.splitlines()[-1] == "objects 0 1"


def test_the_objects_python_recognises_reach_a_c_controller_field_by_field(
    tmp_path: Path, capfd: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    def recognised(camera: Camera) -> list[CameraRecognitionObject]:
        things = [CameraRecognitionObject(), CameraRecognitionObject()]
        things[0].id, things[0].model = 7, "target"
        things[0].position, things[0].orientation = [0.5, -0.25, 0.125], [0, 0, 1, 1.5]
        things[0].size, things[0].position_on_image = [0.1, 0.2], [3, 4]
        things[0].size_on_image = [5, 6]
        things[0].number_of_colors, things[0].colors = 2, [1, 0, 0, 0, 0.5, 1]
        things[1].id = 9
        return things

    monkeypatch.setattr(Camera, "getRecognitionObjects", recognised)
    body = (
        '  WbDeviceTag camera = wb_robot_get_device("camera");\n  wb_robot_step(32);\n'
        "  const WbCameraRecognitionObject *o = wb_camera_recognition_get_objects(camera);\n"
        '  printf("%d %s %g %g %g %g %g %g %d %d %d %d %d %g %g\\n", o[0].id, o[0].model,\n'
        "         o[0].position[0], o[0].position[1], o[0].position[2], o[0].orientation[3],\n"
        "         o[0].size[0], o[0].size[1], o[0].position_on_image[0],\n"
        "         o[0].position_on_image[1], o[0].size_on_image[1], o[0].number_of_colors,\n"
        "         o[1].id, o[0].colors[4], o[0].colors[5]);\n"
        '  printf("second [%s] %d\\n", o[1].model, o[1].number_of_colors);'
    )
    source = write_controller(tmp_path, "carrier", body)
    source.write_text("#include <webots/camera.h>\n" + source.read_text())
    run = run_controller(source, mazesim.load_world("arena"), seconds=0.5)
    assert (run.exit_status, run.error) == (0, "")
    assert capfd.readouterr().out.splitlines()[-2:] == [
        "7 target 0.5 -0.25 0.125 1.5 0.1 0.2 3 4 6 2 9 0.5 1",
        "second [] 0",
    ]


def test_a_c_controller_defining_its_own_random_builds_as_on_windows(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    # Windows' C library has no random(): controllers written there define their own.
    source = write_controller(
        tmp_path, "dice", '  wb_robot_step(32);\n  printf("%g %.4f\\n", random(2, 2), M_PI);'
    )
    source.write_text(
        "#include <stdlib.h>\n#include <math.h>\n"
        "double random(int min, int max) { return min + (max - min) * 0.5; }\n" + source.read_text()
    )
    built = build(source)
    assert built.note.endswith(
        "(C built without the C library's POSIX extensions, as on Windows, since it defines "
        "functions of their names: random)"
    )
    run = run_controller(source, mazesim.load_world("arena"), seconds=0.5)
    assert (run.exit_status, run.error) == (0, "")
    assert capfd.readouterr().out.splitlines()[-1] == "2 3.1416"


def test_a_second_threads_calls_wait_for_the_step_under_way_instead_of_garbling_the_link(
    capfd: pytest.CaptureFixture[str],
) -> None:
    # The library serves its threads one at a time: a call that another thread makes while the
    # main one is inside wb_robot_step waits for the step to end. Both used to write to the link
    # at once, and mazesim, reading garbage, closed it (the controller was killed by SIGPIPE).
    controller = CONTROLLERS / "c_two_threads" / "c_two_threads.c"
    run = run_controller(controller, mazesim.load_world("arena"), seconds=5.0)
    out, _ = capfd.readouterr()
    assert (run.exit_status, run.error) == (0, "")
    assert out.splitlines()[-1] == "read 1 wrong 0 steps 40 time 1.280"


def test_globals_a_shared_header_defines_link_as_before_gcc_10(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    # A header that defines (not declares) a global, included by two files of the controller:
    # GCC before 10, which Webots of those years built with, merged the two as one common
    # symbol; GCC 10's -fno-common refuses the link with "multiple definition".
    source = write_controller(
        tmp_path, "shared", '  count_step();\n  count_step();\n  printf("steps %d\\n", counter);'
    )
    (source.parent / "counter.h").write_text("int counter;\nvoid count_step(void);\n")
    (source.parent / "counter.c").write_text(
        '#include "counter.h"\nvoid count_step(void) { counter += 1; }\n'
    )
    source.write_text('#include "counter.h"\n' + source.read_text())
    run = run_controller(source, mazesim.load_world("arena"), seconds=0.2)
    assert (run.exit_status, run.error) == (0, "")
    assert capfd.readouterr().out.splitlines()[-1] == "steps 2"


#: Webots 8's DifferentialWheels e-puck: setSpeed in speed units (1500 is beyond its maxSpeed:
#: Webots' error, the speed kept as set), encoders in encoder units, set mid-run; a Python twin
#: of the C controller below.
DIFFERENTIAL_WHEELS_PY = """
from controller import DifferentialWheels

class EPuck(DifferentialWheels):
    pass

robot = EPuck()
robot.enableEncoders(32)
print("unit", robot.getSpeedUnit(), "max", robot.getMaxSpeed())
step = 0
while robot.step(32) != -1:
    step += 1
    robot.setSpeed(1500 if step < 20 else -300, 400)
    if step == 25:
        robot.setEncoders(10.0, -5.0)
    print("%d %.6f %.6f %.1f %.1f %d" % (step, robot.getLeftEncoder(), robot.getRightEncoder(),
          robot.getLeftSpeed(), robot.getRightSpeed(), robot.getEncodersSamplingPeriod()))
"""
DIFFERENTIAL_WHEELS_C = """#include <stdio.h>
#include <webots/robot.h>
#include <webots/differential_wheels.h>
int main(void) {
  wb_robot_init();
  wb_differential_wheels_enable_encoders(32);
  printf("unit %g max %g\\n", wb_differential_wheels_get_speed_unit(),
         wb_differential_wheels_get_max_speed());
  int step = 0;
  while (wb_robot_step(32) != -1) {
    step++;
    wb_differential_wheels_set_speed(step < 20 ? 1500 : -300, 400);
    if (step == 25)
      wb_differential_wheels_set_encoders(10.0, -5.0);
    printf("%d %.6f %.6f %.1f %.1f %d\\n", step, wb_differential_wheels_get_left_encoder(),
           wb_differential_wheels_get_right_encoder(), wb_differential_wheels_get_left_speed(),
           wb_differential_wheels_get_right_speed(),
           wb_differential_wheels_get_encoders_sampling_period());
  }
  wb_robot_cleanup();
  return 0;
}
"""


def test_webots_8_differential_wheels_drives_alike_in_python_and_c(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    c_source = write_source(tmp_path, "dw_c", DIFFERENTIAL_WHEELS_C)
    python_source = write_source(tmp_path, "dw_py", DIFFERENTIAL_WHEELS_PY, ".py")
    (in_c, in_python), (c_out, python_out) = run_twins(
        capfd, c_source, python_source, seconds=1.6, noise=False
    )
    assert (in_c.exit_status, in_python.exit_status) == (0, 0), in_python.error
    assert in_c.xs == in_python.xs and in_c.final_pose == in_python.final_pose
    assert c_out.splitlines()[1:] == python_out.splitlines()[1:]
    assert python_out.splitlines()[0] == "unit 0.00628 max 6.28"
    rows = [line.split() for line in python_out.splitlines()[1:]]
    assert rows[0][3:] == ["1500.0", "400.0", "32"], "the speed as set, as Webots keeps it"
    assert float(rows[18][1]) > float(rows[18][2]) > 0, "the left wheel turned faster"
    assert float(rows[24][1]) == pytest.approx(10.0) and float(rows[24][2]) == pytest.approx(-5.0)
    assert in_python.distance_m > 0.05


def test_a_failed_assert_does_not_abort_a_controller_as_webots_builds_it(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    # Webots' Makefile.include builds a controller with NDEBUG: an assert a course's
    # controller fails unseen in Webots aborted it here (SIGABRT).
    source = write_controller(
        tmp_path,
        "asserting",
        '  int cells = 2;\n  assert(cells == 3);\n  printf("after the assert\\n");\n'
        "  wb_robot_step(32);",
    )
    source.write_text("#include <assert.h>\n" + source.read_text())
    [run], [out] = run_twins(capfd, source, seconds=0.1)
    assert (run.exit_status, run.error) == (0, "")
    assert "after the assert" in out
