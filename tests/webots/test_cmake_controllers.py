"""A C controller that its project builds with its own CMakeLists.txt (a library of the project
outside the controller's folder), built with CMake against mazesim's controller library laid out
as a Webots installation (``mazesim.webots.cmake_build``; docs/webots.md)."""

from __future__ import annotations

from pathlib import Path

import pytest

import mazesim
from mazesim.webots.cmake_build import cmake_program
from mazesim.webots.native_controller import build
from mazesim.webots.runner import run_controller

pytestmark = pytest.mark.skipif(
    cmake_program() is None, reason="cmake is not installed (make test installs Debian's cmake)"
)

#: The controller's build, as Webots projects write it: Webots found through WEBOTS_HOME.
CMAKE_LISTS = """cmake_minimum_required(VERSION 3.16)
project(spinner C)
find_path(WEBOTS_C_INCLUDE webots/robot.h HINTS ENV WEBOTS_HOME PATH_SUFFIXES include/controller/c)
find_library(WEBOTS_CONTROLLER Controller HINTS ENV WEBOTS_HOME PATH_SUFFIXES lib/controller)
if(NOT WEBOTS_C_INCLUDE OR NOT WEBOTS_CONTROLLER)
  message(FATAL_ERROR "Webots not found: set WEBOTS_HOME")
endif()
add_executable(spinner spinner.c ../../lib/steer.c)
target_include_directories(spinner PRIVATE ${WEBOTS_C_INCLUDE} ../../lib)
target_link_libraries(spinner PRIVATE ${WEBOTS_CONTROLLER} m)
set_target_properties(spinner PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_CURRENT_LIST_DIR})
"""

CONTROLLER = """#include <webots/motor.h>
#include <webots/robot.h>
#include "steer.h"

int main(void) {
  wb_robot_init();
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  wb_motor_set_velocity(left, cruise_speed());
  wb_motor_set_velocity(right, cruise_speed());
  while (wb_robot_step(32) != -1) {
  }
  wb_robot_cleanup();
  return 0;
}
"""


def _project(root: Path) -> Path:
    (root / "lib").mkdir(parents=True)
    (root / "lib" / "steer.h").write_text("#include <math.h>\ndouble cruise_speed(void);\n")
    (root / "lib" / "steer.c").write_text(
        '#include "steer.h"\ndouble cruise_speed(void) { return 4.0; }\n'
    )
    folder = root / "controllers" / "spinner"
    folder.mkdir(parents=True)
    (folder / "CMakeLists.txt").write_text(CMAKE_LISTS)
    (folder / "spinner.c").write_text(CONTROLLER)
    return folder / "spinner.c"


def test_a_controller_of_a_cmake_project_is_built_by_its_cmake_lists_and_runs(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("MAZESIM_CACHE", str(tmp_path / "cache"))
    main = _project(tmp_path / "project")
    built = build(main)
    assert built.program == str(main.parent / "spinner")
    assert "CMakeLists.txt" in built.note and built.elsewhere == []
    run = run_controller(str(main), mazesim.load_world("arena"), seconds=1.0)
    assert run.exit_status == 0, run.error
    # 4 rad/s for 1 s on 0.02 m wheels: 0.08 m, give or take the first step.
    assert run.distance_m == pytest.approx(0.08, abs=0.005)
    # A second build is CMake's incremental one, and the same program.
    assert build(main).program == built.program


def test_without_cmake_the_run_names_the_project_s_headers(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("MAZESIM_CACHE", str(tmp_path / "cache"))
    monkeypatch.setattr("mazesim.webots.native_controller.cmake_program", lambda: None)
    built = build(_project(tmp_path / "project"))
    assert built.program is None and built.elsewhere == ["steer.h"]


def test_without_cmake_the_statement_says_it_would_build_the_controller(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from mazesim.webots.requirements import prepare_controller

    monkeypatch.setenv("MAZESIM_CACHE", str(tmp_path / "cache"))
    monkeypatch.setattr("mazesim.webots.native_controller.cmake_program", lambda: None)
    monkeypatch.setattr("mazesim.webots.cmake_build.cmake_program", lambda: None)
    prepared = prepare_controller(str(_project(tmp_path / "project")))
    assert not prepared.runnable
    assert prepared.missing == [
        "header(s) found neither in the controller's folder nor on this system: steer.h (the "
        "project builds the controller with its own CMakeLists.txt, which cmake, not installed "
        "here, would run)"
    ]


def test_a_windows_project_is_not_handed_to_its_cmake_lists_and_the_run_says_why(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from mazesim.webots.requirements import prepare_controller

    monkeypatch.setenv("MAZESIM_CACHE", str(tmp_path / "cache"))
    main = _project(tmp_path / "project")
    main.write_text("#include <windows.h>\n" + CONTROLLER)
    ran = []
    monkeypatch.setattr(
        "mazesim.webots.native_controller.cmake_build", lambda *a: ran.append(a) or (None, "")
    )
    for _ in range(2):  # the first build, then the cache's record of it
        prepared = prepare_controller(str(main))
        assert not prepared.runnable and ran == []
        assert prepared.missing[0] == (
            "Windows' own header(s), which only a Windows build finds (the controller is "
            "written for Windows): windows.h"
        )
