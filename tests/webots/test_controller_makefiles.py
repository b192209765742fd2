"""A C controller's Makefile settings (INCLUDE, CFLAGS, LIBRARIES, C_SOURCES, VPATH), as
Webots' Makefile.include takes them, are honoured by mazesim's build (#33)."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

import mazesim
from mazesim.webots import native_controller, run_controller
from mazesim.webots.controller_makefile import read_makefile
from mazesim.webots.native_controller import build
from mazesim.webots.requirements import prepare_controller
from native_controllers import NEEDS_COMPILERS, write_source

pytestmark = pytest.mark.usefixtures("own_cache")

PRINTER = (
    "#include <stdio.h>\n#include <webots/robot.h>\n{head}"
    'int main(void) {{\n  wb_robot_init();\n  printf("value %g\\n", {value});\n'
    "  wb_robot_cleanup();\n  return 0;\n}}\n"
)


def printer(folder: Path, name: str, head: str, value: str, makefile: str) -> Path:
    """A controller ``folder/name/name.c`` printing ``value`` once, built by ``makefile``."""
    source = write_source(folder, name, PRINTER.format(head=head, value=value))
    (source.parent / "Makefile").write_text(makefile)
    return source


def printed(capfd: pytest.CaptureFixture[str], source: Path) -> list[str]:
    run = run_controller(source, mazesim.load_world("arena"), seconds=0.1)
    assert (run.exit_status, run.error) == (0, "")
    return [line for line in capfd.readouterr().out.splitlines() if line.startswith("value")]


def test_the_makefile_is_read_with_its_continuations_references_and_webots_folders(
    tmp_path: Path,
) -> None:
    (tmp_path / "shared").mkdir()
    (tmp_path / "probe").mkdir()
    (tmp_path / "shared" / "gain.c").write_text("")
    (tmp_path / "mingw").mkdir()
    (tmp_path / "mingw" / "libgsl.dll.a").write_text("")
    settings = read_makefile(
        tmp_path / "probe",
        "SHARED := ../shared\nC_SOURCES = ../shared/gain.c \\\n  probe.c # left.c\n"
        'INCLUDE = -I"$(SHARED)" -I$(WEBOTS_HOME)/projects/default\n'
        "CFLAGS = -O3 -Wall -DGAIN=3 --std=c99 -fopenmp\nCFLAGS += -D SPEED=2\n"
        "LIBRARIES = -L../lib -lController -llibgsl $(shell x) \\\n"
        "  -L/usr/local/webots/lib/controller -L../mingw\n"
        "ifeq ($(OSTYPE),windows)\nLIBRARIES += -lws2_32\nendif\n"
        "null :=\nspace := $(null) $(null)\n"
        "WEBOTS_HOME_PATH=$(subst $(space),\\ ,$(strip $(subst \\,/,$(WEBOTS_HOME))))\n"
        "include $(WEBOTS_HOME_PATH)/resources/Makefile.include\n",
    )
    assert settings.sources == [(tmp_path / "shared" / "gain.c").resolve()]
    shared = (tmp_path / "shared").resolve()
    assert settings.compile_options == [f"-I{shared}", "-DGAIN=3", "-DSPEED=2"]
    assert settings.include_folders == [shared]
    assert settings.standards == ["-std=c99"]
    # OSTYPE, which make does not find set on Linux, is empty: -lws2_32 is Windows' only.
    assert settings.link_options == [f"-L{(tmp_path / 'lib').resolve()}", "-lgsl"]
    assert settings.ignored == [
        "$(shell x) in LIBRARIES",
        "-fopenmp in CFLAGS",
        "-L../mingw (libraries built for Windows)",
    ]


@NEEDS_COMPILERS
def test_include_folders_defines_and_exactly_the_listed_sources_are_built(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    common = tmp_path / "common"
    common.mkdir()
    (common / "gain.h").write_text("double gain(void);\n")
    (common / "gain.c").write_text('#include "gain.h"\ndouble gain(void) { return GAIN * 1.5; }\n')
    # A source listed by its file name alone, found by make in a folder of VPATH.
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "offset.c").write_text("double offset(void) { return 1.0; }\n")
    source = printer(
        tmp_path,
        "probe",
        "#include <gain.h>\ndouble offset(void);\n",
        "gain() + offset()",
        'INCLUDE = -I"../common"\nCFLAGS = -DGAIN=4 -std=gnu99\n'
        "C_SOURCES = probe.c ../common/gain.c offset.c\nVPATH = ../lib\n",
    )
    # A source of the folder the Makefile does not list: left out, as Webots leaves it out.
    (source.parent / "draft.c").write_text("this is not C\n")
    assert printed(capfd, source) == ["value 7"]


def test_conditionals_on_the_system_take_the_branch_make_takes_on_linux(tmp_path: Path) -> None:
    settings = read_makefile(
        tmp_path / "probe",
        "UNAME := $(shell uname)\nifeq ($(UNAME), Linux)\n  CFLAGS = -DGAIN=2\nelse\n"
        "  CFLAGS = -DGAIN=5\nendif\n"
        # OS is Windows_NT on Windows only; an unset variable is empty to make.
        "ifeq ($(OS),Windows_NT)\n  LIBRARIES = -lws2_32\nelse ifdef WEBOTS_HOME\n"
        "  CFLAGS += -DOFFSET=1\n  ifneq '$(UNAME)' 'Darwin'\n    LIBRARIES = -lgsl\n"
        "  endif\nendif\n"
        # A test this reader cannot make (another shell command): its settings are left out.
        "ifeq ($(shell uname -m),x86_64)\n  CFLAGS += -DWIDE=1\nendif\n",
    )
    assert settings.compile_options == ["-DGAIN=2", "-DOFFSET=1"]
    assert settings.link_options == ["-lgsl"]
    assert settings.ignored == ["CFLAGS set under a make conditional"]


@NEEDS_COMPILERS
def test_a_library_a_makefile_links_on_linux_only_is_linked(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    source = printer(
        tmp_path,
        "probe",
        "#include <math.h>\n",
        "round(GAIN * 2.6)",
        # Assignments indented by a tab before the first rule are read as make reads them;
        # after a rule, a line starting with a tab is a command of its recipe.
        "UNAME := $(shell uname)\nifeq ($(UNAME), Linux)\n\tLIBRARIES = -lm\n"
        "\tCFLAGS = -DGAIN=2\nelse\n\tCFLAGS = -DGAIN=5\nendif\n"
        "notes:\n\tCFLAGS = -DGAIN=9\n",
    )
    assert printed(capfd, source) == ["value 5"]


def test_sources_are_found_in_the_folders_of_vpath_and_the_vpath_directive(tmp_path: Path) -> None:
    for place in ("lib", "shared", "other", "probe"):
        (tmp_path / place).mkdir()
    (tmp_path / "lib" / "odometry.c").write_text("")
    (tmp_path / "shared" / "gain.cpp").write_text("")
    (tmp_path / "other" / "notes.c").write_text("")
    settings = read_makefile(
        tmp_path / "probe",
        "LIB = ../lib\nVPATH = $(LIB):../absent\nvpath %.cpp ../shared\nvpath %.h ../other\n"
        "C_SOURCES = odometry.c notes.c\nCXX_SOURCES = gain.cpp\n",
    )
    # make finds odometry.c through VPATH, gain.cpp through the vpath directive for .cpp
    # files; notes.c only lies in a folder searched for headers, so it is not found.
    assert settings.sources == [
        (tmp_path / "lib" / "odometry.c").resolve(),
        (tmp_path / "shared" / "gain.cpp").resolve(),
    ]


def test_the_wildcard_function_lists_the_sources_that_exist(tmp_path: Path) -> None:
    probe = tmp_path / "probe"
    (probe / "src").mkdir(parents=True)
    for name in ("timer.cpp", "plan.cpp", "notes.txt"):
        (probe / "src" / name).write_text("")
    (probe / "probe.cpp").write_text("")
    settings = read_makefile(probe, "CXX_SOURCES = $(wildcard src/*.cpp src/*.cc) probe.cpp\n")
    assert settings.sources == [
        (probe / "src" / "plan.cpp").resolve(),
        (probe / "src" / "timer.cpp").resolve(),
        (probe / "probe.cpp").resolve(),
    ]
    assert settings.ignored == []


@NEEDS_COMPILERS
def test_libraries_are_linked_from_folders_relative_to_the_controller(
    tmp_path: Path, capfd: pytest.CaptureFixture[str]
) -> None:
    lib = tmp_path / "lib"
    lib.mkdir()
    (lib / "scale.c").write_text("double scale(double x) { return 2 * x; }\n")
    gcc, ar = shutil.which("gcc"), shutil.which("ar")
    if ar is None or gcc is None:
        pytest.skip("needs ar")
    subprocess.run([gcc, "-c", "scale.c", "-o", "scale.o"], cwd=lib, check=True)
    subprocess.run([ar, "rcs", "libscale.a", "scale.o"], cwd=lib, check=True)
    (lib / "scale.c").unlink()
    source = printer(
        tmp_path,
        "scaler",
        "#include <math.h>\ndouble scale(double x);\n",
        "scale(cbrt(27.0))",
        "LIBRARIES = -L../lib -lscale -lm\n",
    )
    assert printed(capfd, source) == ["value 6"]


@NEEDS_COMPILERS
def test_a_library_that_is_not_installed_is_named_and_the_robot_stands_still(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    packages = {**native_controller.LIBRARY_PACKAGES, "gsl_absent": "libgsl-absent-dev"}
    monkeypatch.setattr(native_controller, "LIBRARY_PACKAGES", packages)
    source = printer(
        tmp_path, "linker", "", "1.0", "LIBRARIES = -lmazesim_absent_library -lgsl_absent\n"
    )
    built = build(source)
    assert built.program is None
    assert built.libraries == ["gsl_absent (Debian: libgsl-absent-dev)", "mazesim_absent_library"]
    prepared = prepare_controller(str(source))
    assert not prepared.runnable
    assert prepared.missing == [
        "librar(ies) its Makefile links that are not installed here: gsl_absent (Debian: "
        "libgsl-absent-dev), mazesim_absent_library"
    ]
    run = run_controller(source, mazesim.load_world("arena"), seconds=0.5, prepared=prepared)
    assert (run.steps, run.exit_status) == (0, 1)
