"""C and C++ controllers that their project builds with its own ``CMakeLists.txt``.

Webots runs the program ``controllers/NAME/NAME``; a project whose controller needs the
project's own library (headers that are not in the controller's folder) builds it with CMake,
its ``CMakeLists.txt`` finding Webots' headers and libraries through ``$WEBOTS_HOME``
(``include/controller/c``, ``include/controller/cpp``, ``lib/controller/libController``,
``libCppController``). :func:`cmake_build` lays mazesim's controller library out so (``capi/``:
its headers, its C library as ``libController.a``; the C++ classes are in the headers, so
``libCppController.a`` is empty), runs CMake with ``$WEBOTS_HOME`` naming that layout, builds the
target named after the controller's folder (the whole project when it has no such target), and
returns the program: ``NAME`` in the controller's folder, where such a build puts it as Webots
expects, else the one the build folder holds. The build folder is kept in the build cache, so a
second build is CMake's own incremental one.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
from pathlib import Path

from mazesim.errors import ControllerBuildError

__all__ = ["CMAKE_TIMEOUT_S", "cmake_build", "cmake_program"]

#: Seconds a project's CMake build may take (a library of tens of C++ files on a loaded machine).
CMAKE_TIMEOUT_S = 1800


def cmake_program() -> str | None:
    """The ``cmake`` program on ``PATH``, or None."""
    return shutil.which("cmake")


def _webots_layout(cache: Path, capi: Path, archive: Path) -> Path:
    """mazesim's controller library laid out as a Webots installation, in the build cache."""
    key = hashlib.sha256(str(capi).encode() + archive.read_bytes()).hexdigest()[:20]
    home = cache / f"webots-home-{key}"
    if (home / "lib" / "controller" / "libCppController.a").is_file():
        return home
    staging = cache / f".webots-home-{key}.{os.getpid()}"
    shutil.rmtree(staging, ignore_errors=True)
    (staging / "include" / "controller").mkdir(parents=True)
    (staging / "lib" / "controller").mkdir(parents=True)
    for language in ("c", "cpp"):
        shutil.copytree(capi / "include", staging / "include" / "controller" / language)
    shutil.copyfile(archive, staging / "lib" / "controller" / "libController.a")
    # An archive with no member: the library's C++ classes are defined in its headers.
    (staging / "lib" / "controller" / "libCppController.a").write_bytes(b"!<arch>\n")
    if home.exists():
        shutil.rmtree(staging, ignore_errors=True)
    else:
        os.replace(staging, home)
    return home


def _run(command: list[str], environment: dict[str, str], what: str) -> None:
    try:
        done = subprocess.run(
            command,
            env=environment,
            capture_output=True,
            text=True,
            timeout=CMAKE_TIMEOUT_S,
            check=False,
        )
    except subprocess.TimeoutExpired:
        raise ControllerBuildError(
            f"expected the project's CMake {what} to finish within {CMAKE_TIMEOUT_S} s, found it "
            f"still running"
        ) from None
    if done.returncode != 0:
        tail = "\n".join((done.stdout + done.stderr).strip().splitlines()[-20:])
        raise ControllerBuildError(
            f"expected the project's CMake {what} to succeed, found exit status "
            f"{done.returncode}:\n{tail}"
        )


def _executable(path: Path) -> bool:
    return path.is_file() and os.access(path, os.X_OK)


def cmake_build(folder: Path, cache: Path, capi: Path, archive: Path) -> tuple[str, str]:
    """Builds the controller of ``folder`` with its project's ``CMakeLists.txt``.

    Args:
        folder: The controller's folder, holding ``CMakeLists.txt``.
        cache: The build cache (its build folder and the Webots layout go there).
        capi: mazesim's controller library (``include/``).
        archive: The library's C part compiled into an archive (``.a``).

    Returns:
        The program and what the build did, for the run's log.

    Raises:
        ControllerBuildError: CMake failed, took too long, or built no program.
        MissingDependencyError: No ``cmake`` on ``PATH``.
    """
    from mazesim.errors import MissingDependencyError

    cmake = cmake_program()
    if cmake is None:
        raise MissingDependencyError(
            "expected cmake on PATH to build a controller with its project's CMakeLists.txt, "
            "found none: install it (Debian: apt-get install cmake)"
        )
    home = _webots_layout(cache, capi, archive)
    build = cache / ("cmake-" + hashlib.sha256(f"{folder}\0{home}".encode()).hexdigest()[:20])
    environment = dict(os.environ, WEBOTS_HOME=str(home))
    configure = [cmake, "-S", str(folder), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release"]
    _run(configure, environment, "configuration")
    name = folder.name
    jobs = str(max(1, min(4, os.cpu_count() or 1)))
    targets = subprocess.run(
        [cmake, "--build", str(build), "--target", "help"],
        env=environment,
        capture_output=True,
        text=True,
        check=False,
    ).stdout
    chosen = ["--target", name] if f"... {name}" in targets else []
    _run([cmake, "--build", str(build), "-j", jobs, *chosen], environment, "build")
    program = folder / name
    if not _executable(program):
        found = sorted(p for p in build.rglob(name) if _executable(p))
        if not found:
            raise ControllerBuildError(
                f"expected the project's CMake build to make the program {name}, found none in "
                f"{folder} or {build}"
            )
        program = found[0]
    return str(program), f"built with the project's CMakeLists.txt by {cmake} in {build}"
