"""Webots controllers written in C, built with the system's compiler and driven in lockstep.

:func:`build` compiles a controller folder's ``.c`` files (as Webots' default Makefile does)
with mazesim's controller library (``capi/``: Webots' C API headers and their implementation,
written for mazesim) into a program kept in the build cache (``$XDG_CACHE_HOME/mazesim/
controllers``, by default ``~/.cache/mazesim/controllers``; ``MAZESIM_CACHE`` overrides it), so
a second run of the same sources starts at once. A controller that calls a Webots function the
library does not implement does not link; the build then names those functions as missing
Webots features instead of failing. :func:`drive` runs the program as a child process and
serves it over :mod:`mazesim.webots.native_link`.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Callable

from mazesim._atomic import atomic_file
from mazesim._paths import MAX_TEXT_CHARACTERS, read_input
from mazesim._paths import cache_folder as cache_folder_of
from mazesim.errors import ControllerBuildError, MazesimError, MissingDependencyError
from mazesim.webots import native_link
from mazesim.webots import simulation as simulations
from mazesim.webots.cmake_build import cmake_build, cmake_program
from mazesim.webots.controller_makefile import (
    LIBRARY_PACKAGES,
    MakefileSettings,
    defines_main,
    makefile,
    read_makefile,
)
from mazesim.webots.devices import MAX_SAMPLING_PERIOD_MS
from mazesim.webots.shipped_program import LIBRARY, shipped_program
from mazesim.webots.termination import GRACE_SECONDS

__all__ = ["CAPI", "Build", "build", "cache_folder", "drive", "native_robot"]

#: mazesim's controller library: ``include/webots/*.h`` and ``src/*.c``.
CAPI = Path(__file__).with_name("capi")
#: Seconds a build may take.
BUILD_TIMEOUT_S = 300
#: The compiler's options (besides include folders and files): optimised, without warnings, and
#: without ``assert`` checks, as Webots' ``Makefile.include`` builds a controller by default (its
#: release goal defines ``NDEBUG``), so that an assertion a controller fails unseen in Webots
#: (a course's Eigen matrix filled with fewer values than it holds) does not abort it here.
FLAGS = ("-O2", "-w", "-DNDEBUG")
#: The C compiler's own: a global that a header defines (``int count;``, not ``extern``) in
#: every file including it is one common symbol, as GCC made it before version 10 (the
#: compilers of Webots' Linux and Windows releases of those years), where GCC 10 on refuses
#: the link with "multiple definition".
C_FLAGS = ("-fcommon",)
#: Exit status of a controller killed by a signal, or that broke the link.
EXIT_CRASHED = 1

#: The devices of Webots' older C API, whose functions had no ``wb_`` before their names
#: (``robot_step``, ``distance_sensor_enable``, ``differential_wheels_set_speed``...): some old
#: controllers still call them, and the library implements none of them.
_OLD_API = (
    "robot|distance_sensor|differential_wheels|receiver|emitter|led|light_sensor|camera|"
    "supervisor|servo|touch_sensor|accelerometer|gps|compass"
)
_UNDEFINED = re.compile(rf"undefined reference to [`'‘]((?:wb|{_OLD_API})_\w+)['’]")
_NO_HEADER = re.compile(r"fatal error: (webots/[\w/.]+): No such file or directory")
#: A header of the project that is not in the controller's folder (a library the project's own
#: build, CMake or a Makefile, adds with its include folders).
_NO_PROJECT_HEADER = re.compile(r"fatal error: ((?!webots/)[\w/.+-]+): No such file or directory")
#: A method of Webots' C++ classes that the library's classes lack.
_NO_MEMBER = re.compile(
    r"error: ['‘](?:class |struct )?(webots::\w+)['’] has no member named ['‘](\w+)['’]"
)
#: A library the link does not find (``ld: cannot find -lgsl``).
_NO_LIBRARY = re.compile(r"cannot find -l([\w.+-]+)")
_INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.MULTILINE)
#: A file named in a linker's "multiple definition" or "first defined here" message.
_DEFINED_TWICE = re.compile(
    r"([\w.+-]+\.(?:c|cpp|cc|cxx)):\([^)]*\): (?:multiple definition of|first defined here)"
)
#: gcc's and g++'s notes naming the standard header that declares a name a source uses without
#: including it (``did you forget to '#include <memory>'?``, ``include '<string.h>' or provide a
#: declaration of 'memcpy'``): a header that other compilers' own headers include for it.
_FORGOTTEN_HEADER = re.compile(
    r"did you forget to [‘'`]#include <([\w./+-]+)>|include [‘'`]<([\w./+-]+)>[’'`] or provide"
)
#: g++'s errors for a name it does not know, where no note names a header; and for a class of
#: the standard library it knows only by the declaration another standard header makes of it
#: (``field 'names' has incomplete type 'std::array<...>'``: libstdc++'s <tuple> declares
#: ``std::array``, which its <tuple> before GCC 10 included whole).
_UNDECLARED = re.compile(
    r"error: [‘'`]\w+[’'`] (?:does not name a type|was not declared in this scope"
    r"|has not been declared|is not a member of [‘'`]std[’'`])"
    r"|error: [^\n]*incomplete type [‘'`](?:class |struct )?std::"
    r"|error: [^\n]*[‘'`](?:class |struct )?std::[^\n]*incomplete type"
)
#: Every header of the C++ standard library (libstdc++'s precompilable header), included first.
_EVERY_HEADER = ("cpp", ("-include", "bits/stdc++.h"))
#: A function of the sources whose name glibc's <stdlib.h> declares by default, as a BSD and
#: POSIX extension (its random number generator), with another type: Windows' C library has
#: no such function, so the name was free where the controller was written.
_REDEFINED_POSIX_NAME = re.compile(
    r"conflicting types for [‘'`](random|srandom|initstate|setstate)[’'`]"
)
#: The C steps' flag that builds them as X/Open C, without glibc's default BSD and POSIX
#: extensions (M_PI stays declared).
_POSIX_FREE = ("c", ("-D_XOPEN_SOURCE",))
#: The build's rules, part of its cache key: a change of how controllers are built (Windows'
#: own headers read as empty since 2) builds them anew rather than take an earlier result.
_BUILD_RULES = "rules 2"
#: Most builds with empty stand-ins for Windows' own headers, one more header each.
MAX_STAND_INS = 8
#: Most files read for their includes before a build.
MAX_SCANNED = 500


@dataclass
class Build:
    """A C controller's build.

    Attributes:
        program: The built program, or None when it could not be linked.
        missing: Webots API functions the controller calls that mazesim does not implement.
        headers: Webots API headers the controller includes that mazesim does not provide.
        note: What the build did, for the run's log (compiled, or taken from the cache).
        elsewhere: The project's own headers the controller includes that are not in its
            folder (a library its own build adds), which mazesim's build does not find.
        libraries: The libraries its Makefile links that are not installed, each with the
            Debian package that provides it when known (``gsl (Debian: libgsl-dev)``).
    """

    program: str | None
    missing: list[str] = field(default_factory=list)
    headers: list[str] = field(default_factory=list)
    note: str = ""
    elsewhere: list[str] = field(default_factory=list)
    libraries: list[str] = field(default_factory=list)


def cache_folder() -> Path:
    """The folder of built controllers: ``$MAZESIM_CACHE/controllers`` if set, else
    ``$XDG_CACHE_HOME/mazesim/controllers``, else ``~/.cache/mazesim/controllers``; a file where
    the folder or one above it should be is a ``MazesimIOError``."""
    return cache_folder_of("MAZESIM_CACHE", "controllers", under_variable=True)


#: Source suffixes by language, as Webots' default Makefile compiles them.
C_SUFFIXES = (".c",)
CPP_SUFFIXES = (".cpp", ".cc", ".cxx")
#: The compiler of each language, and the variable that names another one.
COMPILERS = {"c": ("CC", "gcc"), "cpp": ("CXX", "g++")}
LANGUAGE_NAMES = {"c": "C", "cpp": "C++"}


def language_name(source: str | os.PathLike[str]) -> str:
    """The language of the controller source ``source`` by its suffix: "C++" or "C"."""
    suffix = os.path.splitext(os.fspath(source))[1].lower()
    return LANGUAGE_NAMES["cpp" if suffix in CPP_SUFFIXES else "c"]


def _compiler(language: str) -> str:
    variable, default = COMPILERS[language]
    name = os.environ.get(variable) or default
    found = shutil.which(name)
    if found is None:
        raise MissingDependencyError(
            f"expected a {LANGUAGE_NAMES[language]} compiler ({name}, or the one ${variable} "
            f"names) on PATH to build the {LANGUAGE_NAMES[language]} controller, found none: "
            f"install {default} (Debian: apt-get install {default})"
        )
    return found


def _files(folder: Path, suffixes: tuple[str, ...], recursive: bool = False) -> list[Path]:
    found = folder.rglob("*") if recursive else folder.glob("*")
    return sorted(p for p in found if p.suffix.lower() in suffixes and p.is_file())


def _key(compilers: list[str], files: list[Path], options: tuple[str, ...] = ()) -> str:
    """The build's cache key: its compilers, its files and the options its Makefile adds."""
    digest = hashlib.sha256()
    digest.update(_BUILD_RULES.encode() + b"\0")
    if options:
        digest.update(b"options\0" + "\0".join(options).encode() + b"\0")
    for compiler in compilers:
        digest.update(compiler.encode() + b"\0" + " ".join(FLAGS + C_FLAGS).encode() + b"\0")
        version = subprocess.run([compiler, "--version"], capture_output=True, check=False)
        digest.update(version.stdout)
    for path in files:
        digest.update(str(path).encode() + b"\0" + _source(path) + b"\0")
    return digest.hexdigest()[:20]


def _source(path: Path) -> bytes:
    """The bytes of a source file of the build: a regular file (a FIFO would block the read for
    ever) of at most :data:`~mazesim._paths.MAX_TEXT_CHARACTERS` bytes.

    Raises:
        MazesimIOError: Not a regular file, or unreadable.
        ControllerBuildError: Longer than the bound.
    """
    data = read_input(path, MAX_TEXT_CHARACTERS, "a source of the controller")
    if len(data) > MAX_TEXT_CHARACTERS:
        raise ControllerBuildError(
            f"{path}: expected a source file of at most {MAX_TEXT_CHARACTERS} bytes, found more"
        )
    return data


def _compile(main: Path, command: list[str], cwd: str) -> subprocess.CompletedProcess[str]:
    try:
        return subprocess.run(
            command, cwd=cwd, capture_output=True, text=True, timeout=BUILD_TIMEOUT_S, check=False
        )
    except subprocess.TimeoutExpired:
        raise ControllerBuildError(
            f"{main}: expected the controller to build within {BUILD_TIMEOUT_S} s, found the "
            f"compiler still running"
        ) from None


def _provided_headers() -> dict[str, str]:
    """The library's Webots headers, by lower-case name (``webots/motor.hpp`` ->
    ``webots/Motor.hpp``)."""
    root = CAPI / "include"
    return {
        path.relative_to(root).as_posix().lower(): path.relative_to(root).as_posix()
        for path in root.rglob("*.h*")
    }


def _scan(files: list[Path]) -> tuple[list[str], dict[str, str], set[Path]]:
    """The Webots headers (``webots/...``) that ``files``, and the files they include by a
    relative path, include: those the controller library does not provide (all of them, where
    the compiler would stop at the first), and those it provides under another case
    (``webots/motor.hpp`` for ``webots/Motor.hpp``, which Windows and macOS, whose file names
    ignore case, find), mapped to the header they stand for; and every file read (those
    included from outside the controller's folder too, which a build depends on)."""
    provided = _provided_headers()
    absent: set[str] = set()
    other_case: dict[str, str] = {}
    queue, seen = list(files), set[Path]()
    while queue and len(seen) < MAX_SCANNED:
        path = queue.pop()
        if path in seen or not path.is_file():
            continue
        seen.add(path)
        text = _source(path).decode("utf-8", errors="replace")
        for quote, name in _INCLUDE.findall(text):
            local = (path.parent / name).resolve()
            if quote == '"' and local.is_file():
                queue.append(local)
            elif not name.startswith("webots/") or (path.parent / name).is_file():
                continue
            elif provided.get(name.lower()) == name:
                continue
            elif name.lower() in provided:
                other_case[name] = provided[name.lower()]
            else:
                absent.add(name)
    return sorted(absent), other_case, seen


def _write_case_aliases(folder: Path, aliases: dict[str, str]) -> None:
    """Headers in ``folder`` under the names a controller spells in another case, each
    including the library's header."""
    for name, header in aliases.items():
        alias = folder / name
        alias.parent.mkdir(parents=True, exist_ok=True)
        alias.write_text(f"#include <{header}>\n", encoding="utf-8")


def _compile_all(
    main: Path,
    language: str,
    compilers: list[str],
    c_sources: list[Path],
    cpp_sources: list[Path],
    aliases: dict[str, str],
    target: Path,
    settings: MakefileSettings,
    forced: tuple[str, tuple[str, ...]] = ("", ()),
) -> tuple[subprocess.CompletedProcess[str], list[str]]:
    """Compiles and links the controller into ``target``, with its Makefile's ``settings``; the
    last step's result and command.
    ``forced``: a language (``"c"`` or ``"cpp"``) and the flags its steps take before the
    sources (standard headers they include first, ``-include``, or a feature macro)."""
    folder = main.parent
    prefix = {forced[0]: list(forced[1])}
    c_compiler = compilers[0]
    library = _library(main, c_compiler)
    archived = [str(path) for path in library if path.suffix == ".a"]
    library = [path for path in library if path.suffix != ".a"]
    with tempfile.TemporaryDirectory(prefix="mazesim-build-") as work:
        _write_case_aliases(Path(work) / "aliases", aliases)
        includes = ["-I", str(folder), "-I", str(CAPI / "include"), "-I", f"{work}/aliases"]
        includes += settings.compile_options
        c_includes = [*C_FLAGS, *includes, *_standards(settings, "c"), *prefix.get("c", [])]
        linked = [*archived, "-o", str(target), *settings.link_options, "-lm"]
        if language == "c":
            steps = [[c_compiler, *FLAGS, *c_includes, *map(str, [*c_sources, *library])]]
            steps[0] += linked
        else:
            # The C parts (the library, the project's .c files) as C, then the C++ program.
            c_parts = [*c_sources, *library]
            objects = [os.path.join(work, f"{i}.o") for i in range(len(c_parts))]
            steps = [
                [c_compiler, *FLAGS, *c_includes, "-c", str(path), "-o", obj]
                for path, obj in zip(c_parts, objects)
            ]
            cpp_includes = [*includes, *_standards(settings, "cpp"), *prefix.get("cpp", [])]
            steps.append([compilers[1], *FLAGS, *cpp_includes, *map(str, cpp_sources), *objects])
            steps[-1] += linked
        for command in steps:
            done = _compile(main, command, work)
            if done.returncode != 0:
                break
    return done, command


def _standards(settings: MakefileSettings, language: str) -> list[str]:
    """The Makefile's ``-std=`` options of ``language``'s steps (``-std=c++17`` to C++,
    ``-std=c99`` to C), as each compiler takes only its own."""
    return [s for s in settings.standards if ("++" in s) == (language == "cpp")]


def _library(main: Path, c_compiler: str) -> list[Path]:
    """The controller library compiled once into an archive of the build cache
    (``capi-KEY/libmazesim_controller.a``), or its sources when no archiver (``ar``) is
    there or the archive cannot be made."""
    sources = sorted((CAPI / "src").glob("*.c"))
    archiver = shutil.which("ar")
    if archiver is None:
        return sources
    headers = [*(CAPI / "src").glob("*.h"), *(CAPI / "include").rglob("*.h")]
    key = _key([c_compiler], [*sources, *sorted(headers)])
    archive = cache_folder() / f"capi-{key}" / "libmazesim_controller.a"
    if archive.is_file():
        return [archive]
    archive.parent.mkdir(parents=True, exist_ok=True)
    temporary = archive.with_name(f".{archive.name}.{os.getpid()}")
    with tempfile.TemporaryDirectory(prefix="mazesim-build-") as work:
        objects = [os.path.join(work, f"{path.stem}.o") for path in sources]
        steps = [
            [c_compiler, *FLAGS, "-I", str(CAPI / "include"), "-c", str(path), "-o", obj]
            for path, obj in zip(sources, objects)
        ]
        steps.append([archiver, "rcs", str(temporary), *objects])
        for command in steps:
            if _compile(main, command, work).returncode != 0:
                temporary.unlink(missing_ok=True)
                return sources
    os.replace(temporary, archive)
    return [archive]


def _defined_twice(errors: str, main: Path) -> list[str]:
    """The controller's files (not its main file) that a link found defining a function another
    file defines too."""
    names = set(_DEFINED_TWICE.findall(errors))
    return sorted(name for name in names if name != main.name and (main.parent / name).is_file())


def _buildable(elsewhere: list[str]) -> bool:
    """Whether a controller whose headers ``elsewhere`` are found neither in its folder nor on
    the system may be built by its project's CMake: not when one is Windows' own (a project
    written for Windows does not build here, whatever its CMakeLists.txt says)."""
    from mazesim.webots.requirements import WINDOWS_HEADERS

    return bool(elsewhere) and not any(name.lower() in WINDOWS_HEADERS for name in elsewhere)


def _project_cmake(main: Path, c_compiler: str, elsewhere: list[str]) -> Build | None:
    """The controller built by its project's ``CMakeLists.txt`` beside it
    (:mod:`mazesim.webots.cmake_build`), or None when there is none, or no ``cmake`` or archiver
    to build it with. A CMake build that fails or makes no program is a build without a program
    that still lacks the project's headers ``elsewhere``, its note quoting CMake's complaint, so
    that the run says at its start what is missing instead of stopping."""
    if not (main.parent / "CMakeLists.txt").is_file() or cmake_program() is None:
        return None
    archive = [path for path in _library(main, c_compiler) if path.suffix == ".a"]
    if not archive:
        return None
    try:
        program, note = cmake_build(main.parent, cache_folder(), CAPI, archive[0])
    except ControllerBuildError as failed:
        complaint = str(failed).splitlines()[0][:300]
        return Build(
            None, note=f"its project's CMake build failed: {complaint}", elsewhere=elsewhere
        )
    return Build(program, note=note)


def build(source: str | os.PathLike[str]) -> Build:
    """Builds the C or C++ controller whose main file is ``source`` (with its folder's other
    ``.c``, and for C++ ``.cpp``, ``.cc`` and ``.cxx``, files), or takes it from the cache. One
    that includes headers of its project found neither in its folder nor on the system is built
    by the project's ``CMakeLists.txt`` in its folder when there is one and ``cmake`` is
    installed (:mod:`mazesim.webots.cmake_build`). A C controller whose sources do not build
    here but whose folder holds the program Webots runs, built for Linux against Webots'
    ``libController.so``, runs that program with mazesim's library
    (:mod:`mazesim.webots.shipped_program`).

    Raises:
        MissingDependencyError: No compiler.
        ControllerBuildError: The sources do not compile (the message quotes the compiler), or
            one is longer than :data:`~mazesim._paths.MAX_TEXT_CHARACTERS` bytes.
        MazesimIOError: A source is not a regular file (a FIFO, a folder) or cannot be read.
    """
    main = Path(source).resolve()
    _source(main)  # a regular file of a bounded size, before anything waits on it
    found = makefile(main.parent)
    settings = (
        read_makefile(main.parent, _source(found).decode("utf-8", errors="replace"))
        if found is not None
        else MakefileSettings()
    )
    try:
        built = _build_sources(main, settings)
        built.note += settings.note()
    except ControllerBuildError as failed:
        errors = [line for line in str(failed).splitlines() if "error:" in line]
        shipped = _shipped(main, (errors or ["compiler errors"])[0])
        if shipped is None:
            raise
        return shipped
    if built.program is None and not built.missing:
        # Headers it lacks: the program its folder holds was built with them.
        return _shipped(main, built.note) or built
    return built


def _shipped(main: Path, why: str) -> Build | None:
    """The build of a C controller whose folder holds its program, built for Linux against
    Webots' ``libController.so``: that program, run with mazesim's library, as Webots runs it
    (None when the folder holds no such program)."""
    if main.suffix.lower() not in C_SUFFIXES:
        return None
    program = shipped_program(main, cache_folder(), CAPI, _compiler("c"))
    if program is None:
        return None
    note = (
        f"its sources do not build here ({why.strip()[:200]}): the program {main.parent.name} its "
        f"folder holds, which Webots runs, is run with mazesim's controller library as "
        f"{LIBRARY} (copied into the cache {Path(program).parent})"
    )
    return Build(program, note=note)


def _build_sources(main: Path, settings: MakefileSettings) -> Build:
    """:func:`build` from the controller's sources, as its Makefile's ``settings`` ask."""
    folder = main.parent
    language = "cpp" if main.suffix.lower() in CPP_SUFFIXES else "c"
    c_compiler = _compiler("c")
    compilers = [c_compiler] + ([_compiler("cpp")] if language == "cpp" else [])
    listed = settings.sources
    if listed is None:
        c_sources = _files(folder, C_SUFFIXES)
        cpp_sources = _files(folder, CPP_SUFFIXES) if language == "cpp" else []
    else:
        # The sources its Makefile lists, exactly those, as Webots' Makefile.include builds.
        c_sources = [path for path in listed if path.suffix.lower() in C_SUFFIXES]
        cpp_sources = [path for path in listed if path.suffix.lower() in CPP_SUFFIXES]
        cpp_sources = cpp_sources if language == "cpp" else []
    # Another file with a main of its own is another program (a tool, a test): left out. But
    # when the file named after the folder defines no main, the program's main is in another
    # of its files (Webots' Makefile links them all into the folder's one program): kept.
    apart = [p for p in [*c_sources, *cpp_sources] if p != main and defines_main(p)]
    if not defines_main(main):
        apart = []
    c_sources = [p for p in c_sources if p not in apart]
    cpp_sources = [p for p in cpp_sources if p not in apart]
    own = cpp_sources if language == "cpp" else c_sources
    if main not in own:
        own.append(main)
    headers = _files(folder, (".h", ".hpp", ".hh"), recursive=True)
    for place in settings.include_folders:
        headers += _files(place, (".h", ".hpp", ".hh"), recursive=True)[:MAX_SCANNED]
    library = sorted((CAPI / "src").glob("*.c"))
    library_headers = sorted((CAPI / "include").rglob("*.h*"))
    absent, aliases, read = _scan([*c_sources, *cpp_sources, *headers])
    if absent:
        return Build(None, [], absent, note="it includes Webots headers mazesim does not provide")
    # The files the build reads, those its sources include from outside their folder too.
    files = [*c_sources, *cpp_sources, *headers, *library, *(CAPI / "src").glob("*.h")]
    files += [path for path in [makefile(folder)] if path is not None]
    files += sorted(path for path in read if path not in set(files))
    options = (*settings.compile_options, *settings.standards, *settings.link_options)
    key = _key(compilers, [*files, *library_headers], options)
    target = cache_folder() / f"{main.stem}-{key}" / main.stem
    if target.is_file():
        return Build(str(target), note=f"built earlier, taken from the cache {target.parent}")
    # What a build that failed for lack of Webots features lacked, kept beside its program.
    lacking = target.with_name("missing.json")
    if lacking.is_file():
        known = json.loads(lacking.read_text(encoding="utf-8"))
        built = (
            _project_cmake(main, c_compiler, known["elsewhere"])
            if _buildable(known["elsewhere"])
            else None
        )
        if built is not None:
            return built
        note = f"built earlier without success, as the cache {target.parent} says"
        return Build(None, known["missing"], known["headers"], note, known["elsewhere"])
    target.parent.mkdir(parents=True, exist_ok=True)
    temporary = target.with_name(f".{target.name}.{os.getpid()}")

    def compiled(
        forced: tuple[str, tuple[str, ...]] = ("", ()),
    ) -> tuple[subprocess.CompletedProcess[str], list[str]]:
        """The build of the sources as they now stand, with ``forced`` flags."""
        return _compile_all(
            main, language, compilers, c_sources, cpp_sources, aliases, temporary, settings, forced
        )

    done, command = compiled()
    read_empty = _windows_headers(done.stderr) if done.returncode != 0 else []
    if read_empty:
        # Windows' own headers (<windows.h>) that a controller written for Windows includes
        # without using what they declare (left over from a Sleep since removed): built with
        # empty stand-ins, as it builds there. When it uses any of their names, that build
        # fails, and the failure said is the plain one: the headers are missing.
        # The compiler stops at the first missing header: each build names the next one.
        plain = settings
        for _ in range(MAX_STAND_INS):
            stand_ins = ["-I", str(_windows_stand_ins(read_empty))]
            settings = replace(plain, compile_options=[*plain.compile_options, *stand_ins])
            retried, again = compiled()
            more = _windows_headers(retried.stderr) if retried.returncode != 0 else []
            if not set(more) - set(read_empty):
                break
            read_empty = sorted(set(read_empty) | set(more))
        if retried.returncode == 0:
            done, command = retried, again
        else:
            settings, read_empty = plain, []
    twice = _defined_twice(done.stderr, main) if done.returncode != 0 else []
    if twice:
        # Files whose functions another file defines again (copies the main file took in):
        # the program is built without them, as it must have been.
        c_sources = [p for p in c_sources if p.name not in twice]
        cpp_sources = [p for p in cpp_sources if p.name not in twice]
        done, command = compiled()
    forgotten = _forgotten_headers(done.stderr) if done.returncode != 0 else ()
    if forgotten:
        # Standard headers the sources use without including them, which the compiler names:
        # the author's compiler included them through its other headers (g++ 12's <iomanip>
        # no longer brings <memory>), so the sources are built with them included first.
        step = "cpp" if language == "cpp" and command[0] == compilers[-1] else "c"
        included = tuple(part for header in forgotten for part in ("-include", header))
        done, command = compiled((step, included))
    whole_library = False
    if done.returncode != 0 and command[0] == compilers[-1] and _UNDECLARED.search(done.stderr):
        # A name of the C++ standard library that g++ does not trace to its header (`function`
        # after `using namespace std`), or a class it knows only as declared (`std::array`,
        # which <tuple> declares): another standard library (macOS' libc++, or libstdc++ before
        # GCC 10, whose <tuple> included <array>) brought it in through the headers the sources
        # include, so they are built with every standard header included first; when that fails
        # too, the first errors are the ones said.
        retried, again = compiled(_EVERY_HEADER)
        if retried.returncode == 0:
            done, command, whole_library = retried, again, True
    redefined = _posix_names_redefined(done.stderr) if done.returncode != 0 else ()
    if redefined and command[0] == c_compiler:
        # C functions named as the C library's POSIX extensions (a `double random(int, int)`),
        # which Windows' C library, the authors', does not declare: the C sources are built
        # without glibc's default extensions, as X/Open C, which leaves those names free.
        done, command = compiled(_POSIX_FREE)
    if done.returncode != 0:
        temporary.unlink(missing_ok=True)
        missing = sorted(set(_UNDEFINED.findall(done.stderr)))
        missing += sorted({f"{owner}::{name}" for owner, name in _NO_MEMBER.findall(done.stderr)})
        absent = sorted(set(_NO_HEADER.findall(done.stderr)))
        elsewhere = sorted(set(_NO_PROJECT_HEADER.findall(done.stderr)))
        libraries = sorted(set(_NO_LIBRARY.findall(done.stderr)))
        compiler = command[0]
        if libraries and not (missing or absent or elsewhere):
            # Not kept in the cache: the library may be installed before the next run.
            said = [
                f"{name} (Debian: {LIBRARY_PACKAGES[name]})" if name in LIBRARY_PACKAGES else name
                for name in libraries
            ]
            return Build(None, note=f"{compiler} cannot link it", libraries=said)
        built = (
            _project_cmake(main, c_compiler, elsewhere)
            if _buildable(elsewhere) and not missing
            else None
        )
        if built is not None:
            return built
        if missing or absent or elsewhere:
            known = {"missing": missing, "headers": absent, "elsewhere": elsewhere}
            with atomic_file(lacking) as handle:
                handle.write(json.dumps(known).encode("utf-8"))
            note = f"{compiler} cannot build it"
            return Build(None, missing, absent, note=note, elsewhere=elsewhere)
        message = done.stderr.strip().replace(f"{folder}{os.sep}", "")
        raise ControllerBuildError(
            f"{main}: expected a {LANGUAGE_NAMES[language]} controller that compiles, found "
            f"compiler errors ({os.path.basename(compiler)} {' '.join(FLAGS)}):\n{message}"
        )
    os.replace(temporary, target)
    names = " and ".join(compilers)
    note = f"compiled with {names} into the cache {target.parent}"
    if aliases:
        spelled = ", ".join(f"{name} as {header}" for name, header in sorted(aliases.items()))
        note += f" (headers in another case read as on Windows and macOS: {spelled})"
    if apart:
        names = ", ".join(path.name for path in apart)
        note += f" (left out, each a program with a main of its own: {names})"
    if twice:
        names = ", ".join(twice)
        note += f" (left out, their functions defined again by the controller's files: {names})"
    if redefined:
        names = ", ".join(redefined)
        note += (
            f" (C built without the C library's POSIX extensions, as on Windows, since it defines "
            f"functions of their names: {names})"
        )
    if read_empty:
        names = ", ".join(f"<{header}>" for header in read_empty)
        note += (
            f" (Windows' own headers it includes read as empty, as it uses nothing they "
            f"declare: {names})"
        )
    if whole_library:
        note += (
            " (C++ standard names its sources use without their headers, which g++ does not "
            "name or knows only as declared: built with every standard header included first, "
            "as other standard libraries' headers, and older ones of its own, include them)"
        )
    elif forgotten:
        names = ", ".join(f"<{header}>" for header in forgotten)
        note += (
            f" (standard headers its sources use without including them, included first as "
            f"other compilers' own headers include them: {names})"
        )
    return Build(str(target), note=note)


def _windows_headers(stderr: str) -> list[str]:
    """Windows' own headers (:data:`~mazesim.webots.requirements.WINDOWS_HEADERS`, any case)
    that the compiler's errors say it cannot find."""
    from mazesim.webots.requirements import WINDOWS_HEADERS

    found = sorted(set(_NO_PROJECT_HEADER.findall(stderr)))
    return [name for name in found if name.lower() in WINDOWS_HEADERS]


def _windows_stand_ins(headers: list[str]) -> Path:
    """The cache's folder of empty stand-ins for Windows' own ``headers`` and no others (a build
    finds out which it includes), made as needed."""
    named = hashlib.sha256("\0".join(sorted(headers)).encode()).hexdigest()[:16]
    folder = cache_folder() / "windows-stand-ins" / f"set-{named}"
    folder.mkdir(parents=True, exist_ok=True)
    for name in headers:
        stand_in = folder / name
        if not stand_in.is_file():
            with atomic_file(stand_in) as handle:
                handle.write(
                    f"/* mazesim: an empty stand-in for Windows' <{name}>, for a controller "
                    "that includes it and uses nothing it declares. */\n".encode()
                )
    return folder


def _posix_names_redefined(stderr: str) -> tuple[str, ...]:
    """The C library's POSIX extensions the sources define again with other types, as the
    compiler's errors name them."""
    return tuple(dict.fromkeys(_REDEFINED_POSIX_NAME.findall(stderr)))


def _forgotten_headers(stderr: str) -> tuple[str, ...]:
    """The standard headers the compiler's notes say the sources forgot to include, in the order
    the notes first name them."""
    named = [cpp or c for cpp, c in _FORGOTTEN_HEADER.findall(stderr)]
    return tuple(dict.fromkeys(named))


def native_robot() -> Any:
    """The robot a compiled controller drives, on the prepared simulation: a
    :class:`~mazesim.webots.supervisor.Supervisor`, whose powers the supervisor functions use;
    the robot counts as a supervisor when the world says so, or from the controller's first
    supervisor function on (as a Python controller's does from its ``Supervisor()``)."""
    from mazesim.webots.supervisor import Supervisor

    simulation = simulations.current()
    said = simulation.supervisor
    robot = Supervisor()
    simulation.supervisor = said
    return robot


def _signal_name(status: int) -> str:
    try:
        return signal.Signals(-status).name
    except ValueError:
        return f"signal {-status}"


def crash_error(language: str, status: int) -> str:
    """The error of a ``language`` controller whose process was killed by signal ``-status``
    (a negative exit status, as :mod:`subprocess` gives it)."""
    return f"the {language} controller crashed: killed by {_signal_name(status)}\n"


def drive(
    program: str,
    robot: Any,
    arguments: list[str],
    facts: tuple[str, str, str],
    folder: str,
    language: str = "C",
) -> tuple[int, str, bool]:
    """Runs a built controller as a child process and serves its steps until it exits.

    Args:
        program: The built controller.
        robot: The :class:`~mazesim.webots.robot.Robot` it drives.
        arguments: The controller's arguments (the world's ``controllerArgs``).
        facts: Controller name, project path and world path, for the API's getters.
        folder: The controller's folder, where it runs (as in Webots), and where its
            ``argv[0]`` says it is.
        language: The controller's language as a crash names it ("C" or "C++").

    Returns:
        The exit status, the error (a crash, or "" ), and whether the controller was stopped
        because it went on after the run's end.
    """
    ours, theirs = socket.socketpair()
    environment = dict(os.environ, MAZESIM_CONTROLLER_FD=str(theirs.fileno()))
    beside = os.path.dirname(program)
    if os.path.isfile(os.path.join(beside, LIBRARY)):
        # A program built against Webots' libController.so finds mazesim's beside it.
        found = environment.get("LD_LIBRARY_PATH")
        environment["LD_LIBRARY_PATH"] = beside + (os.pathsep + found if found else "")
    sys.stdout.flush()
    sys.stderr.flush()
    # The program's own name (argv[0]) is where Webots starts it, the executable named after
    # its folder in that folder, as a controller that finds its files beside itself reads it.
    process = subprocess.Popen(
        [os.path.join(folder, facts[0]), *arguments],
        executable=program,
        cwd=folder,
        env=environment,
        pass_fds=(theirs.fileno(),),
        stdin=subprocess.DEVNULL,
        preexec_fn=_ends_with_its_parent(),
    )
    theirs.close()
    link = native_link.RobotLink(ours, robot, facts)
    stopped, failure = False, ""
    saved_cwd = os.getcwd()
    try:
        # The calls it makes are served in its folder, as a Python controller's run there: a
        # relative path it passes (a sound, a saved image) names a file beside it.
        os.chdir(folder)
        stopped = _serve(link, robot)
    except native_link.LinkClosed:
        pass
    except MazesimError as error:
        # A malformed message, or a refusal the library does not answer as Webots: the run's error.
        process.kill()
        failure = f"{type(error).__name__}: {error}\n"
    except BaseException:
        process.kill()
        process.wait()
        raise
    finally:
        os.chdir(saved_cwd)
        ours.close()
    try:
        status = process.wait(timeout=GRACE_SECONDS)
    except subprocess.TimeoutExpired:
        process.kill()
        status = process.wait()
        stopped = True
    if failure:
        return EXIT_CRASHED, failure, False
    if stopped:
        return 0, "", True
    if status < 0:
        return EXIT_CRASHED, crash_error(language, status), False
    return status, "", False


#: Linux's ``prctl`` option that sends a process a signal when its parent ends.
_PR_SET_PDEATHSIG = 1


def _ends_with_its_parent() -> Callable[[], None] | None:
    """What the controller's process runs before it starts, so that it is killed when the
    process that serves it ends, however that one ends (a world run's controller process killed
    at Ctrl-C): a controller that never steps does not run on after mazesim, holding the
    terminal's output open. Without Linux's ``prctl``, None.

    Linux's ``prctl`` is looked up here, in the serving process: after the fork, with other
    threads about, the child only calls it (no import, no library loading)."""
    import ctypes

    try:
        prctl = ctypes.CDLL(None, use_errno=True).prctl
    except (OSError, AttributeError):
        return None
    prctl.argtypes = [ctypes.c_int, ctypes.c_ulong]
    death_signal = int(signal.SIGKILL)

    def in_the_child() -> None:
        prctl(_PR_SET_PDEATHSIG, death_signal)

    return in_the_child


def _step(robot: Any, duration: int) -> int:
    """Runs a compiled controller's ``wb_robot_step(duration)``. Webots' library sends the
    duration as an unsigned 32-bit count of ms, so a negative one asks for 2**32 - |duration|
    ms: no message, and the controller waits in that step until the run's end (-1), as in
    Webots it waits for weeks of simulated time."""
    left = duration % 2**32
    while True:
        part = min(left, MAX_SAMPLING_PERIOD_MS)
        result = robot.step(part)
        left -= part
        if result != 0 or left <= 0:
            return int(result)


def _serve(link: native_link.RobotLink, robot: Any) -> bool:
    """Serves the controller's messages; True when it was stopped for going on after the end."""
    simulation = robot._simulation
    ended_at: float | None = None
    while True:
        if ended_at is not None:
            left = GRACE_SECONDS - (time.monotonic() - ended_at)
            if left <= 0:
                simulation.stopped = True
                return True
            link.channel.settimeout(left)
        try:
            kind = link.receive_kind()
        except TimeoutError:
            simulation.stopped = True
            return True
        if kind == native_link.HELLO:
            link.receive_hello()
        elif kind == native_link.STEP:
            duration, commands = link.receive_step()
            if simulation.ended:
                link.answer_step(-1)
                continue
            link.apply(commands)
            result = _step(robot, duration)
            if result == -1:
                ended_at = time.monotonic()
            link.answer_step(result)
        elif kind == native_link.CALL:
            link.receive_call()
        elif kind == native_link.CLEANUP:
            return False
        else:
            raise native_link.LinkClosed
