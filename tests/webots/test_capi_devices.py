"""Every device class of the Python ``controller`` module has its C header and its C++ class in
mazesim's controller library, so that a C or C++ controller can use what a Python one can."""

from __future__ import annotations

import math
import re
import wave
from pathlib import Path

import pytest

from mazesim.webots import controller
from mazesim.webots.devices import Device
from mazesim.webots.importer import import_wbt, import_wbt_text
from mazesim.webots.native_controller import CAPI
from mazesim.webots.requirements import motor_limits, prepare_controller
from native_controllers import NEEDS_COMPILERS, run_twins, write_source

CONTROLLERS = Path(__file__).resolve().parents[1] / "data" / "controllers"

HEADERS = CAPI / "include" / "webots"
#: Device classes of the Python module without a C or C++ side yet, all inert in Python (their
#: readings are Webots' values for a missing device, their commands are accepted and do
#: nothing): a C or C++ controller that includes one's header is named as needing it before it
#: is built.
WITHOUT_C: set[str] = set()


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
    assert all(line.startswith("rpy 0.000000 0.000000 ") for line in lines[::5])
    # The lidar's range image is its node's 360 points of one layer (mazesim.webots.scanners),
    # and its point cloud each range as a point in the lidar's frame, x ahead, y left, z up
    # (WbLidar::updatePointCloud), the nearest at its range, at the heading of its place in the
    # sweep (from fieldOfView / 2 to the left, 6.28 / 360 rad a point), timed from the reading.
    assert lines[2] == "ranges 360 resolution 360 layers 1"
    assert lines[3] == "cloud some points 360 fov 6.280000 max 0.500000"
    points = [line.split() for line in lines if line.startswith("point ")]
    assert len(points) == 4
    for block, point in enumerate(points):
        k, layer = int(point[1]), point[5]
        x, y, z, time, reach = (float(v) for v in (*point[2:5], point[6], point[8]))
        assert math.hypot(x, y) == pytest.approx(reach, abs=2e-4) and reach < 0.5
        heading = 3.14 - k * 6.28 / 360
        assert math.atan2(y, x) == pytest.approx(math.remainder(heading, 2 * math.pi), abs=1e-3)
        assert (z, layer) == (0.0, "0")
        assert time == pytest.approx(0.032 * 8 * (block + 1) - k * 0.032 / 360, abs=1e-4)
    assert runs[1].xs == runs[0].xs and runs[2].final_pose == runs[0].final_pose
    for twin in twins:
        prepared = prepare_controller(str(twin))
        assert prepared.runnable and prepared.missing == []


def test_a_compiled_controllers_sources_below_its_folder_are_read_for_what_it_calls(
    tmp_path: Path,
) -> None:
    # A Makefile's src/*.cpp holds the calls; a copy of Webots' header declares, not calls.
    (tmp_path / "src").mkdir()
    (tmp_path / "webots").mkdir()
    (tmp_path / "main.cpp").write_text("int main() { return 0; }\n")
    (tmp_path / "src" / "walls.cpp").write_text(
        "void f(int t) { wb_motor_set_available_torque(t, 0.5); }\n"
    )
    (tmp_path / "webots" / "motor.h").write_text(
        "void wb_motor_set_available_force(int, double);\n"
    )
    assert motor_limits(str(tmp_path / "main.cpp"), "cpp") == ["wb_motor_set_available_torque"]
    # A Python controller's own packages are read for their imports, not for these calls.
    (tmp_path / "main.py").write_text("from controller import Robot\n")
    assert motor_limits(str(tmp_path / "main.py"), "python") == []


def test_a_lidar_point_lies_along_its_ray_in_either_axis_convention() -> None:
    """``lidar_points``: a range of 4 m at 30 degrees to the left in the layer tilted up by 0.1
    rad lies at (4 cos 30 cos 0.1, 4 sin 30 cos 0.1, 4 sin 0.1) in the FLU frame of Webots
    R2022a on, at (-4 sin 30 cos 0.1, 4 sin 0.1, -4 cos 30 cos 0.1) in an NUE world's lidar
    frame; the second point of a sweep of two over a 0.1 s period is timed 0.05 s earlier."""
    from mazesim.webots.scanners import lidar_points

    a, e = math.radians(30), 0.1
    ranges = [1.0, 2.0, 3.0, 4.0]
    flu = lidar_points(ranges, [0.0, a], [0.0, e], (5.0, 0.1), nue=False)
    nue = lidar_points(ranges, [0.0, a], [0.0, e], (5.0, 0.1), nue=True)
    point = flu[3]
    assert (point.x, point.y, point.z) == pytest.approx(
        (4 * math.cos(a) * math.cos(e), 4 * math.sin(a) * math.cos(e), 4 * math.sin(e))
    )
    point = nue[3]
    assert (point.x, point.y, point.z) == pytest.approx(
        (-4 * math.sin(a) * math.cos(e), 4 * math.sin(e), -4 * math.cos(a) * math.cos(e))
    )
    assert [p.layer_id for p in flu] == [0, 0, 1, 1]
    assert [p.time for p in flu] == pytest.approx([5.0, 4.95, 5.0, 4.95])
    assert (flu[0].x, flu[0].y, flu[0].z) == (1.0, 0.0, 0.0), "straight ahead"


#: An E-puck with a Pen in its groundSensorsSlot (the e-puck's own speaker beside it).
PEN_WORLD = (
    "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\nRectangleArena { floorSize 1 1 }\n"
    'E-puck { controller "<extern>" groundSensorsSlot [ Pen { name "pen" } ] }\n'
)
PEN_SPEAKER_PY = """from controller import Robot, Speaker
robot = Robot()
pen, speaker = robot.getDevice("pen"), robot.getDevice("speaker")
pen.setInkColor(0xFF0000, 0.5)
pen.write(True)
print("language %d %s engine %s" % (speaker.setLanguage("fr-FR"), speaker.getLanguage(),
                                    speaker.getEngine()))
Speaker.playSound(speaker, speaker, "beep.wav", 1.0, 2.0, 0.0, False)
speaker.speak("bonjour", 1.0)
step = 0
while robot.step(32) != -1:
    step += 1
    print("%d %d %d %d" % (step, speaker.isSoundPlaying("beep.wav"), speaker.isSoundPlaying(""),
                           speaker.isSpeaking()))
"""
PEN_SPEAKER_C = """#include <stdio.h>
#include <webots/pen.h>
#include <webots/robot.h>
#include <webots/speaker.h>
int main(void) {
  wb_robot_init();
  WbDeviceTag pen = wb_robot_get_device("pen"), speaker = wb_robot_get_device("speaker");
  wb_pen_set_ink_color(pen, 0xFF0000, 0.5);
  wb_pen_write(pen, true);
  int set = wb_speaker_set_language(speaker, "fr-FR");
  printf("language %d %s engine %s\\n", set, wb_speaker_get_language(speaker),
         wb_speaker_get_engine(speaker));
  wb_speaker_play_sound(speaker, speaker, "beep.wav", 1.0, 2.0, 0.0, false);
  wb_speaker_speak(speaker, "bonjour", 1.0);
  int step = 0;
  while (wb_robot_step(32) != -1) {
    step++;
    printf("%d %d %d %d\\n", step, wb_speaker_is_sound_playing(speaker, "beep.wav"),
           wb_speaker_is_sound_playing(speaker, NULL), wb_speaker_is_speaking(speaker));
  }
  wb_robot_cleanup();
  return 0;
}
"""
PEN_SPEAKER_CPP = """#include <cstdio>
#include <webots/Pen.hpp>
#include <webots/Robot.hpp>
#include <webots/Speaker.hpp>
using namespace webots;
int main() {
  Robot robot;
  Pen *pen = robot.getPen("pen");
  Speaker *speaker = robot.getSpeaker("speaker");
  pen->setInkColor(0xFF0000, 0.5);
  pen->write(true);
  int set = speaker->setLanguage("fr-FR");
  std::printf("language %d %s engine %s\\n", set, speaker->getLanguage().c_str(),
              speaker->getEngine().c_str());
  Speaker::playSound(speaker, speaker, "beep.wav", 1.0, 2.0, 0.0, false);
  speaker->speak("bonjour", 1.0);
  int step = 0;
  while (robot.step(32) != -1) {
    step++;
    std::printf("%d %d %d %d\\n", step, speaker->isSoundPlaying("beep.wav"),
                speaker->isSoundPlaying(""), speaker->isSpeaking());
  }
  return 0;
}
"""


def _beep(folder: Path, seconds: float) -> None:
    """A silent WAV file ``beep.wav`` of ``seconds`` in ``folder``."""
    with wave.open(str(folder / "beep.wav"), "wb") as clip:
        clip.setnchannels(1)
        clip.setsampwidth(2)
        clip.setframerate(8000)
        clip.writeframes(bytes(2 * int(8000 * seconds)))


@NEEDS_COMPILERS
@pytest.mark.usefixtures("own_cache")
def test_c_and_cpp_controllers_use_a_pen_and_the_speaker_as_python_does(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    # Their headers refused the build before: a controller that includes <webots/pen.h> without
    # calling it (a course's supervisor) did not run.
    world, report = import_wbt_text(PEN_WORLD, "pen.wbt")
    twins = [
        write_source(tmp_path, "pen_py", PEN_SPEAKER_PY, ".py"),
        write_source(tmp_path, "pen_c", PEN_SPEAKER_C),
        write_source(tmp_path, "pen_cpp", PEN_SPEAKER_CPP, ".cpp"),
    ]
    for twin in twins:
        _beep(twin.parent, 0.2)
    runs, outputs = run_twins(capfd, *twins, world=world, report=report, seconds=0.32)
    assert [(run.exit_status, run.error) for run in runs] == [(0, ""), (0, ""), (0, "")]
    assert outputs[1] == outputs[0] and outputs[2] == outputs[0]
    lines = outputs[0].splitlines()
    assert lines[0] == "language 1 fr-FR engine pico"
    # 0.2 s of sound at pitch 2 plays 0.1 s: through step 3 (0.096 s), over at step 4.
    assert [line.split()[1] for line in lines[1:]] == ["1", "1", "1"] + ["0"] * 7
    assert all(line.split()[2] == line.split()[1] and line.endswith(" 0") for line in lines[1:])


#: An E-puck 0.2 m from the arena's +x wall, a RangeFinder of 8 x 2 pixels in its turretSlot.
RANGE_WORLD = (
    "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 32 }\nRectangleArena { floorSize 1 1 }\n"
    'E-puck { translation 0.3 0 0 controller "<extern>" turretSlot [ RangeFinder { '
    'name "depth" width 8 height 2 fieldOfView 1 maxRange 2 } ] }\n'
)
RANGE_PY = """from controller import RangeFinder, Robot
robot = Robot()
finder = robot.getDevice("depth")
finder.enable(32)
print("size %d %d fov %.4f range %.4f %.4f" % (finder.getWidth(), finder.getHeight(),
      finder.getFov(), finder.getMinRange(), finder.getMaxRange()))
robot.step(32)
image = finder.getRangeImage()
print(" ".join("%.5f" % RangeFinder.rangeImageGetDepth(image, 8, x, 1) for x in range(8)))
"""
RANGE_C = """#include <stdio.h>
#include <webots/range_finder.h>
#include <webots/robot.h>
int main(void) {
  wb_robot_init();
  WbDeviceTag finder = wb_robot_get_device("depth");
  wb_range_finder_enable(finder, 32);
  printf("size %d %d fov %.4f range %.4f %.4f\\n", wb_range_finder_get_width(finder),
         wb_range_finder_get_height(finder), wb_range_finder_get_fov(finder),
         wb_range_finder_get_min_range(finder), wb_range_finder_get_max_range(finder));
  wb_robot_step(32);
  const float *image = wb_range_finder_get_range_image(finder);
  for (int x = 0; x < 8; x++)
    printf(x ? " %.5f" : "%.5f", wb_range_finder_image_get_depth(image, 8, x, 1));
  printf("\\n");
  wb_robot_cleanup();
  return 0;
}
"""
RANGE_CPP = """#include <cstdio>
#include <webots/RangeFinder.hpp>
#include <webots/Robot.hpp>
using namespace webots;
int main() {
  Robot robot;
  RangeFinder *finder = robot.getRangeFinder("depth");
  finder->enable(32);
  std::printf("size %d %d fov %.4f range %.4f %.4f\\n", finder->getWidth(), finder->getHeight(),
              finder->getFov(), finder->getMinRange(), finder->getMaxRange());
  robot.step(32);
  const float *image = finder->getRangeImage();
  for (int x = 0; x < 8; x++)
    std::printf(x ? " %.5f" : "%.5f", RangeFinder::rangeImageGetDepth(image, 8, x, 1));
  std::printf("\\n");
  return 0;
}
"""


@NEEDS_COMPILERS
@pytest.mark.usefixtures("own_cache")
def test_c_and_cpp_controllers_read_a_range_finder_as_python_does(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    world, report = import_wbt_text(RANGE_WORLD, "range.wbt")
    twins = [
        write_source(tmp_path, "range_py", RANGE_PY, ".py"),
        write_source(tmp_path, "range_c", RANGE_C),
        write_source(tmp_path, "range_cpp", RANGE_CPP, ".cpp"),
    ]
    runs, outputs = run_twins(capfd, *twins, world=world, report=report, seconds=0.1)
    assert [(run.exit_status, run.error) for run in runs] == [(0, ""), (0, ""), (0, "")]
    assert outputs[1] == outputs[0] and outputs[2] == outputs[0]
    size, depths = outputs[0].splitlines()
    assert size == "size 8 2 fov 1.0000 range 0.0100 2.0000"
    # The wall about 0.2 m ahead: each column's depth along the axis is the same (a flat wall).
    values = [float(v) for v in depths.split()]
    assert max(values) - min(values) < 1e-3 and 0.18 < values[0] < 0.23


ABSENT_C = """#include <stdio.h>
#include <webots/brake.h>
#include <webots/connector.h>
#include <webots/radar.h>
#include <webots/robot.h>
#include <webots/skin.h>
#include <webots/vacuum_gripper.h>
int main(void) {
  wb_robot_init();
  WbDeviceTag radar = wb_robot_get_device("radar");
  printf("radar %d targets %d locked %d\\n", radar, wb_radar_get_number_of_targets(radar),
         wb_connector_is_locked(wb_robot_get_device("connector")));
  wb_robot_step(32);
  wb_robot_cleanup();
  return 0;
}
"""


@NEEDS_COMPILERS
@pytest.mark.usefixtures("own_cache")
def test_a_c_controller_including_headers_of_devices_mazesim_never_builds_runs(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    # Their headers refused the build before; the robot has no such device, as in Python
    # (getDevice gives None): Webots' messages, and the values Webots gives for none.
    source = write_source(tmp_path, "absent", ABSENT_C)
    assert prepare_controller(str(source)).runnable
    [run], [out] = run_twins(capfd, source, seconds=0.1)
    assert (run.exit_status, run.error) == (0, "")
    assert out.splitlines()[0] == "radar 0 targets 0 locked 0"


INPUTS_PY = """from controller import Robot
robot = Robot()
mouse, joystick = robot.getMouse(), robot.getJoystick()
mouse.enable(32)
mouse.enable3dPosition()
joystick.enable(64)
robot.step(32)
state = mouse.getState()
print("mouse %d %d %d %d %s %s" % (mouse.getSamplingPeriod(), mouse.is3dPositionEnabled(),
      state.left, state.right, state.u, state.z))
print("joystick %d %d [%s] %d %d %d" % (joystick.getSamplingPeriod(), joystick.isConnected(),
      joystick.getModel(), joystick.getNumberOfAxes(), joystick.getAxisValue(0),
      joystick.getPressedButton()))
"""
INPUTS_C = """#include <stdio.h>
#include <webots/joystick.h>
#include <webots/mouse.h>
#include <webots/robot.h>
int main(void) {
  wb_robot_init();
  wb_mouse_enable(32);
  wb_mouse_enable_3d_position();
  wb_joystick_enable(64);
  wb_robot_step(32);
  WbMouseState state = wb_mouse_get_state();
  printf("mouse %d %d %d %d %s %s\\n", wb_mouse_get_sampling_period(),
         wb_mouse_is_3d_position_enabled(), state.left, state.right,
         state.u != state.u ? "nan" : "?", state.z != state.z ? "nan" : "?");
  printf("joystick %d %d [%s] %d %d %d\\n", wb_joystick_get_sampling_period(),
         wb_joystick_is_connected(), wb_joystick_get_model(), wb_joystick_get_number_of_axes(),
         wb_joystick_get_axis_value(0), wb_joystick_get_pressed_button());
  wb_robot_cleanup();
  return 0;
}
"""


@NEEDS_COMPILERS
@pytest.mark.usefixtures("own_cache")
def test_a_c_controller_finds_the_mouse_and_no_joystick_as_python_does(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    twins = [
        write_source(tmp_path, "inputs_py", INPUTS_PY, ".py"),
        write_source(tmp_path, "inputs_c", INPUTS_C),
    ]
    runs, outputs = run_twins(capfd, *twins, seconds=0.1)
    assert [(run.exit_status, run.error) for run in runs] == [(0, ""), (0, "")]
    assert outputs[1] == outputs[0]
    assert outputs[0].splitlines() == ["mouse 32 1 0 0 nan nan", "joystick 64 0 [] 0 0 -1"]
