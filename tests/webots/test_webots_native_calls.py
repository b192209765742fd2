"""The radio, display and supervisor of compiled Webots controllers: C and C++ twins of Python
controllers talk, and move robots, exactly as the Python ones do (mazesim.webots.native_calls
serves their calls with the Python objects)."""

from __future__ import annotations

import json
import re
import subprocess
from pathlib import Path

import pytest

import mazesim
from mazesim.errors import ControllerBuildError
from mazesim.webots import run_controller
from mazesim.webots.importer import import_wbt
from mazesim.webots.lockstep import run_world
from mazesim.webots.native_controller import build
from mazesim.webots.requirements import DISPLAY_NOTE, prepare_controller
from mazesim.webots.scene import read_scene
from native_controllers import NEEDS_COMPILERS, run_twins, write_source

DATA = Path(__file__).resolve().parents[1] / "data"
CONTROLLERS = DATA / "controllers"
SWARM = DATA / "webots-swarm"

pytestmark = [NEEDS_COMPILERS, pytest.mark.usefixtures("own_cache")]


def _logs(folder: Path) -> dict[str, object]:
    return {path.stem: json.loads(path.read_text()) for path in sorted(folder.glob("*.json"))}


def _twin_runs(
    world: Path, compiled: dict[str, str], tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> tuple[object, object, dict[str, object], dict[str, object]]:
    """The world run with its Python controllers, then with compiled ones for some robots; each
    run's robots write their logs into a folder of their own."""
    runs, logs = [], []
    for name, controllers in (("python", {}), ("compiled", compiled)):
        folder = tmp_path / name
        folder.mkdir()
        monkeypatch.setenv("SWARM_LOG", str(folder))
        runs.append(run_world(str(world), seconds=10.0, seed=3, controllers=controllers))
        logs.append(_logs(folder))
    return runs[0], runs[1], logs[0], logs[1]


def test_a_c_emitter_talks_to_c_receivers_as_python_ones_do(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    follower = str(CONTROLLERS / "c_follower" / "c_follower.c")
    compiled = {"leader": str(CONTROLLERS / "c_leader" / "c_leader.c")}
    compiled |= {"near": follower, "far": follower}
    world = SWARM / "worlds" / "leader_followers.wbt"
    in_python, in_c, python_logs, c_logs = _twin_runs(world, compiled, tmp_path, monkeypatch)
    robots = in_c.robots  # type: ignore[attr-defined]
    assert [(r.exit_status, r.error) for r in robots] == [(0, "")] * 3
    assert [Path(str(r.controller)).suffix for r in robots] == [".c"] * 3
    # The same packets, queues, channels, range, strength and direction: the same logs...
    assert set(c_logs) == {"leader", "near", "far"}
    assert c_logs == python_logs
    near = c_logs["near"]
    assert near["first_heard"] == 2 and near["orders"][:2] == ["go", "go"]  # type: ignore[index]
    assert c_logs["far"] == {"first_heard": None, "orders": [], "strengths": []}, "out of range"
    assert "near go" in c_logs["leader"]["acknowledgements"]  # type: ignore[index]
    # ... and the same trajectories, bit for bit.
    for python_robot, c_robot in zip(in_python.robots, robots):  # type: ignore[attr-defined]
        assert (c_robot.xs, c_robot.ys) == (python_robot.xs, python_robot.ys)
    assert robots[1].distance_m > 0.04, "the near follower obeyed the C leader"


def test_a_cpp_supervisor_moves_a_robot_as_the_python_one_does(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    compiled = {
        "shepherd": str(CONTROLLERS / "cpp_shepherd" / "cpp_shepherd.cpp"),
        "flock": str(CONTROLLERS / "c_follower" / "c_follower.c"),
    }
    world = SWARM / "worlds" / "shepherd.wbt"
    in_python, in_cpp, python_logs, cpp_logs = _twin_runs(world, compiled, tmp_path, monkeypatch)
    shepherd, stray, flock = in_cpp.robots  # type: ignore[attr-defined]
    assert (shepherd.exit_status, shepherd.error, flock.exit_status) == (0, "", 0)
    assert cpp_logs == python_logs and set(cpp_logs) == {"shepherd", "flock"}
    seen = cpp_logs["shepherd"]
    assert seen["stray"] == pytest.approx([-1.0, -1.0, 0.0], abs=1e-6)  # type: ignore[index]
    assert (seen["channel"], seen["range"]) == (1, -1)  # type: ignore[index]
    # The supervisor moved the stray e-puck home; the flock e-puck heard "go" and drove.
    assert stray.final_pose[:2] == pytest.approx((0.5, -0.5), abs=1e-6)
    assert flock.final_pose[0] > 1.03
    for python_robot, cpp_robot in zip(in_python.robots, in_cpp.robots):  # type: ignore[attr-defined]
        assert (cpp_robot.xs, cpp_robot.ys) == (python_robot.xs, python_robot.ys)


def test_a_c_supervisor_moves_its_own_robot_and_quits_as_the_python_one_does(
    capfd: pytest.CaptureFixture[str],
) -> None:
    path = CONTROLLERS / "worlds" / "gps_compass_arena.wbt"
    world, imported = import_wbt(str(path))
    report = {**imported, "path": str(path)}
    scene = read_scene(path.read_text(), report.get("robot_model"), report.get("robot_line"))
    twins = CONTROLLERS / "supervisor_teleport.py", CONTROLLERS / "c_teleport/c_teleport.c"
    runs, outputs = run_twins(capfd, *twins, world=world, seconds=3.0, report=report, scene=scene)
    in_python, in_c = runs
    assert (in_c.exit_status, in_c.error, in_c.quit_requested) == (3, "", True)
    assert in_python.exit_status == 3
    assert (in_c.xs, in_c.ys, in_c.steps) == (in_python.xs, in_python.ys, in_python.steps)
    printed = {line.split()[0]: line.split()[1:] for line in outputs[1].splitlines()}
    numbers = {key: [float(v) for v in values] for key, values in printed.items()}
    # Python prints its lists: "start [x, y, z] [ax, ay, az, angle]", "moved [...]"...
    python = {
        line.split(" ", 1)[0]: [json.loads(found) for found in re.findall(r"\[[^\]]*\]", line)]
        for line in outputs[0].splitlines()
    }
    assert [numbers["start"], numbers["rotation"]] == python["start"]
    assert [round(v, 3) for v in numbers["moved"]] == python["moved"][0] == [0.2, -0.1, 0.0]
    assert [round(v, 3) for v in numbers["velocity"]] == python["velocity"][0]


def test_wrong_tags_null_nodes_and_empty_queues_get_webots_messages(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    source = write_source(
        tmp_path,
        "mistakes",
        "#include <stdio.h>\n#include <webots/robot.h>\n#include <webots/emitter.h>\n"
        "#include <webots/receiver.h>\n#include <webots/supervisor.h>\n"
        "int main(void) {\n  wb_robot_init();\n"
        '  WbDeviceTag motor = wb_robot_get_device("left wheel motor");\n'
        '  WbDeviceTag receiver = wb_robot_get_device("receiver");\n'
        '  printf("sent %d\\n", wb_emitter_send(motor, "x", 1));\n'
        "  wb_receiver_enable(receiver, 32);\n  wb_robot_step(32);\n"
        '  printf("queue %d data %p\\n", wb_receiver_get_queue_length(receiver),\n'
        "         wb_receiver_get_data(receiver));\n"
        '  printf("field %p\\n", (void *)wb_supervisor_node_get_field(NULL, "name"));\n'
        "  WbNodeRef self = wb_supervisor_node_get_self();\n"
        '  printf("absent %p\\n", (void *)wb_supervisor_node_get_field(self, "no_field"));\n'
        '  printf("self %s\\n", wb_supervisor_node_get_type_name(self));\n'
        "  wb_robot_cleanup();\n  return 0;\n}\n",
    )
    run = run_controller(source, mazesim.load_world("arena"), seconds=1.0)
    assert (run.exit_status, run.error) == (0, "")
    out, err = capfd.readouterr()
    assert out.splitlines() == [
        "sent 0",
        "queue 0 data (nil)",
        "field (nil)",
        "absent (nil)",
        "self E-puck",
    ]
    errors = err.splitlines()
    assert "Error: wb_emitter_send(): invalid device tag." in errors
    assert "Error: wb_receiver_get_data(): the receiver queue is empty." in errors
    assert "Error: wb_supervisor_node_get_field() called with a NULL 'node' argument." in errors
    assert (
        "Error: wb_supervisor_node_get_field(): field 'no_field' does not exist in node 'E-puck'."
        in errors
    )


def test_a_display_draws_nothing_and_the_run_says_so_at_its_start(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    source = write_source(
        tmp_path,
        "plotter",
        "#include <stdio.h>\n#include <webots/robot.h>\n#include <webots/display.h>\n"
        "int main(void) {\n  wb_robot_init();\n"
        '  WbDeviceTag display = wb_robot_get_device("display");\n'
        "  wb_display_set_color(display, 0xff0000);\n"
        "  wb_display_draw_line(display, 0, 0, 10, 10);\n"
        '  wb_display_draw_text(display, "fitness", 2, 2);\n'
        "  WbImageRef image = wb_display_image_copy(display, 0, 0, 8, 8);\n"
        "  wb_display_image_paste(display, image, 0, 0, false);\n"
        "  wb_display_image_delete(display, image);\n"
        '  printf("%d %d\\n", wb_display_get_width(display), wb_display_get_height(display));\n'
        "  wb_robot_step(32);\n  wb_robot_cleanup();\n  return 0;\n}\n",
    )
    prepared = prepare_controller(str(source))
    assert prepared.runnable and prepared.missing == []
    assert f"C controller plotter.c: {DISPLAY_NOTE}" in prepared.notes
    run = run_controller(source, mazesim.load_world("arena"), seconds=1.0, prepared=prepared)
    assert (run.exit_status, run.error, run.steps) == (0, "", 1)
    out, err = capfd.readouterr()
    # The e-puck has no display: Webots' message for each call on the absent device.
    assert out == "0 0\n"
    assert "Error: wb_display_draw_line(): invalid device tag." in err


def test_headers_spelled_in_another_case_build_as_on_windows(tmp_path: Path) -> None:
    source = write_source(
        tmp_path,
        "flocking",
        "#include <webots/supervisor.hpp>\n#include <webots/motor.hpp>\n"
        "#include <webots/Emitter.hpp>\n"
        "int main() { webots::Supervisor robot; return robot.getSelf() ? 0 : 1; }\n",
        ".cpp",
    )
    built = build(source)
    assert built.program is not None and built.headers == []
    assert built.note.endswith(
        "(headers in another case read as on Windows and macOS: webots/motor.hpp as "
        "webots/Motor.hpp, webots/supervisor.hpp as webots/Supervisor.hpp)"
    )
    run = run_controller(source, mazesim.load_world("arena"), seconds=0.5)
    assert (run.exit_status, run.error) == (0, "")


def test_missing_cpp_methods_and_headers_of_a_project_library_are_named(tmp_path: Path) -> None:
    source = write_source(
        tmp_path,
        "recorder",
        "#include <webots/Supervisor.hpp>\n"
        'int main() { webots::Supervisor s; s.animationStartRecording("run.html"); return 0; }\n',
        ".cpp",
    )
    prepared = prepare_controller(str(source))
    assert not prepared.runnable
    assert prepared.missing == [
        "Webots C++ API function(s) mazesim does not implement: "
        "webots::Supervisor::animationStartRecording"
    ]
    library = write_source(
        tmp_path,
        "planner",
        '#include <webots/Robot.hpp>\n#include "bt/blackboard.hpp"\nint main() { return 0; }\n',
        ".cpp",
    )
    (library.parent / "CMakeLists.txt").write_text("project(planner)\n")
    missing = prepare_controller(str(library)).missing
    assert len(missing) == 1 and re.fullmatch(
        r"header\(s\) found neither in the controller's folder nor on this system: "
        r"bt/blackboard.hpp \(the project builds the controller with its own CMakeLists.txt\)",
        missing[0],
    )


def test_windows_headers_are_named_as_windows_ones(tmp_path: Path) -> None:
    # It calls Sleep, which <windows.h> declares: it does not build here.
    source = write_source(
        tmp_path,
        "visualizer",
        "#include <windows.h>\n#include <webots/robot.h>\n"
        "int main(void) { Sleep(10); return 0; }\n",
    )
    prepared = prepare_controller(str(source))
    assert not prepared.runnable
    assert prepared.missing == [
        "Windows' own header(s), which only a Windows build finds (the controller is written "
        "for Windows): windows.h"
    ]
    # The cache keeps what a failed build lacked: the next run says it without compiling.
    again = prepare_controller(str(source))
    assert again.missing == prepared.missing and not again.runnable
    assert "built earlier without success" in again.notes[0]


@pytest.mark.parametrize("suffix", [".c", ".cpp"])
def test_windows_headers_a_controller_uses_nothing_of_are_read_as_empty(
    tmp_path: Path, suffix: str
) -> None:
    # Written on Windows, <Windows.h> and <conio.h> included for a Sleep and a getch since
    # removed: it builds there, and here too.
    source = write_source(
        tmp_path,
        "walker",
        "#include <Windows.h>\n#include <conio.h>\n#include <webots/robot.h>\n"
        "int main(void) { wb_robot_init(); wb_robot_step(32); wb_robot_cleanup(); return 0; }\n",
        suffix,
    )
    prepared = prepare_controller(str(source))
    assert prepared.runnable and prepared.missing == [], prepared.missing
    said = "Windows' own headers it includes read as empty, as it uses nothing they declare"
    assert f"({said}: <Windows.h>, <conio.h>)" in prepared.notes[0], prepared.notes


def test_a_header_included_from_outside_the_folder_is_part_of_the_build(tmp_path: Path) -> None:
    common = tmp_path / "common" / "speed.h"
    common.parent.mkdir()
    common.write_text("#define SPEED 1.0\n")
    source = write_source(
        tmp_path,
        "mover",
        '#include "../common/speed.h"\n#include <webots/robot.h>\nint main(void) { return 0; }\n',
    )
    first = build(source)
    assert first.program is not None and build(source).program == first.program
    common.write_text("#define SPEED 2.0\n")
    again = build(source)
    assert again.program != first.program and "compiled with" in again.note


def test_other_programs_and_files_a_controller_copied_are_left_out_of_its_build(
    tmp_path: Path,
) -> None:
    source = write_source(
        tmp_path,
        "swarm",
        "#include <webots/robot.h>\ndouble half(double x) { return x / 2; }\n"
        "int main(void) { wb_robot_init(); wb_robot_step(32); wb_robot_cleanup(); "
        "return half(0.0); }\n",
    )
    # A tool with a main of its own, and the file the controller copied half() from.
    (source.parent / "kmeans.c").write_text("int main(void) { return 1; }\n")
    (source.parent / "maths.c").write_text("double half(double x) { return 0.5 * x; }\n")
    built = build(source)
    assert built.program is not None
    assert built.note.endswith(
        "(left out, each a program with a main of its own: kmeans.c) "
        "(left out, their functions defined again by the controller's files: maths.c)"
    )
    run = run_controller(source, mazesim.load_world("arena"), seconds=0.5)
    assert (run.exit_status, run.error, run.steps) == (0, "", 1)


def test_a_controller_whose_main_is_in_another_of_its_files_builds_with_it(
    tmp_path: Path,
) -> None:
    # The file named after the folder holds the controller's functions; its main is in pso.cpp,
    # and Webots' Makefile links the folder's files into one program.
    source = write_source(
        tmp_path,
        "supervisor",
        "#include <webots/robot.h>\nint steps() { return wb_robot_step(32) == -1 ? 0 : 1; }\n",
        suffix=".cpp",
    )
    (source.parent / "pso.cpp").write_text(
        "#include <webots/robot.h>\nint steps();\n"
        "int main(int, char const **) { wb_robot_init(); int n = steps(); wb_robot_cleanup(); "
        "return n - 1; }\n"
    )
    built = build(source)
    assert built.program is not None and "main of its own" not in built.note
    run = run_controller(source, mazesim.load_world("arena"), seconds=0.5)
    assert (run.exit_status, run.error, run.steps) == (0, "", 1)


def test_a_controller_reads_its_own_path_in_its_folder_as_in_webots(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    # Webots starts controllers/NAME/NAME, so argv[0] leads to the files beside the sources
    # (a supervisor that loads its saved settings from there), not to mazesim's build cache.
    source = write_source(
        tmp_path,
        "replayer",
        "#include <stdio.h>\n#include <webots/robot.h>\n"
        'int main(int argc, char **argv) { wb_robot_init(); printf("argv0=%s\\n", argv[0]); '
        "wb_robot_cleanup(); return 0; }\n",
    )
    run = run_controller(source, mazesim.load_world("arena"), seconds=0.5)
    assert (run.exit_status, run.error) == (0, "")
    assert f"argv0={source.parent / 'replayer'}\n" in capfd.readouterr().out


def test_a_c_controller_whose_folder_ships_its_linux_program_runs_it_when_its_sources_fail(
    tmp_path: Path,
) -> None:
    # Webots runs controllers/NAME/NAME when the folder holds it, whatever its sources: here
    # a program built against libController.so beside sources that no longer compile.
    from mazesim.webots.native_controller import CAPI
    from mazesim.webots.shipped_program import LIBRARY

    webots = tmp_path / "webots-lib"
    webots.mkdir()
    capi = [str(path) for path in sorted((CAPI / "src").glob("*.c"))]
    include = ["-I", str(CAPI / "include")]
    shared = ["gcc", "-shared", "-fPIC", "-w", *include, *capi, "-o", str(webots / LIBRARY)]
    assert subprocess.run([*shared, "-lm"], check=False).returncode == 0
    source = write_source(
        tmp_path, "walker", "#include <webots/robot.h>\nint main(void) { return undeclared; }\n"
    )
    program = source.parent / "walker.built.c"
    program.write_text(
        "#include <webots/robot.h>\n#include <webots/motor.h>\n"
        "int main(void) { wb_robot_init();\n"
        '  WbDeviceTag left = wb_robot_get_device("left wheel motor");\n'
        '  WbDeviceTag right = wb_robot_get_device("right wheel motor");\n'
        "  wb_motor_set_position(left, 1.0 / 0.0); wb_motor_set_position(right, 1.0 / 0.0);\n"
        "  wb_motor_set_velocity(left, 4.0); wb_motor_set_velocity(right, 4.0);\n"
        "  while (wb_robot_step(32) != -1) {}\n  wb_robot_cleanup(); return 0; }\n"
    )
    link = ["gcc", "-w", *include, str(program), "-L", str(webots), "-lController"]
    assert subprocess.run([*link, "-o", str(source.parent / "walker")], check=False).returncode == 0
    program.unlink()
    built = build(source)
    assert built.program is not None and "the program walker its folder holds" in built.note
    run = run_controller(source, mazesim.load_world("arena"), seconds=1.0)
    assert (run.exit_status, run.error) == (0, "") and run.distance_m > 0.05
    # A program for another system (a macOS build) is not run: the sources' errors stand.
    (source.parent / "walker").write_bytes(b"\xcf\xfa\xed\xfe" + bytes(64))
    with pytest.raises(ControllerBuildError):
        build(source)
