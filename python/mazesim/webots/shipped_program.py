"""C controllers whose folder holds the program Webots runs, built by their author for Linux.

Webots starts the executable ``controllers/NAME/NAME`` when the folder holds one; it does not
build the sources beside it, so a project that committed its built program runs that program in
Webots, even when its sources no longer compile (a header left out of the repository, a name
renamed in one file only). Such a program is linked against Webots' ``libController.so``, whose
functions, ``wb_robot_step``..., it calls by name. :func:`shipped_program` gives it mazesim's
controller library under that name (``capi/``, built once into the build cache as
``libController.so`` beside a copy of the program), so it runs as a controller mazesim built,
when its sources do not build here: a program for this machine's processor (an ELF executable of
its architecture), that needs ``libController.so`` and not Webots' C++ library.
"""

from __future__ import annotations

import hashlib
import os
import platform
import shutil
import struct
import subprocess
import tempfile
from pathlib import Path

__all__ = ["LIBRARY", "shipped_program"]

#: The name of Webots' C controller library, which such a program needs.
LIBRARY = "libController.so"
#: ELF's machine numbers of the processors mazesim runs on.
_MACHINES = {"x86_64": 62, "amd64": 62, "aarch64": 183, "arm64": 183}
#: Bytes read from a file to tell whether it is such a program (its dynamic section's names).
_MAX_PROGRAM_BYTES = 64 * 1024 * 1024
#: Seconds the library's build may take.
_BUILD_TIMEOUT_S = 300


def _runs_here(data: bytes) -> bool:
    """Whether ``data`` is an ELF executable for this machine's processor (64-bit, little-endian)
    that needs Webots' C controller library and not its C++ one."""
    if len(data) < 20 or data[:4] != b"\x7fELF" or data[4] != 2 or data[5] != 1:
        return False
    machine = struct.unpack_from("<H", data, 18)[0]
    if machine != _MACHINES.get(platform.machine().lower()):
        return False
    return LIBRARY.encode() + b"\0" in data and b"libCppController" not in data


def _library(folder: Path, capi: Path, compiler: str) -> bool:
    """Builds mazesim's controller library as ``folder/libController.so``; whether it did."""
    sources = sorted(str(path) for path in (capi / "src").glob("*.c"))
    with tempfile.TemporaryDirectory(prefix="mazesim-build-") as work:
        temporary = os.path.join(work, LIBRARY)
        command = [compiler, "-O2", "-w", "-shared", "-fPIC", "-I", str(capi / "include")]
        command += [*sources, "-o", temporary, "-lm"]
        try:
            done = subprocess.run(
                command, cwd=work, capture_output=True, timeout=_BUILD_TIMEOUT_S, check=False
            )
        except (OSError, subprocess.TimeoutExpired):
            return False
        if done.returncode != 0:
            return False
        shutil.move(temporary, folder / LIBRARY)
    return True


def shipped_program(main: Path, cache: Path, capi: Path, compiler: str) -> str | None:
    """The program ``NAME`` that the folder of the controller ``main`` holds, copied into the
    build cache beside mazesim's controller library built as ``libController.so``, or None when
    the folder holds no such program for this machine (or the library does not build)."""
    program = main.parent / main.parent.name
    if not program.is_file() or program.stat().st_size > _MAX_PROGRAM_BYTES:
        return None
    data = program.read_bytes()
    if not _runs_here(data):
        return None
    digest = hashlib.sha256(data)
    for path in sorted([*(capi / "src").glob("*"), *(capi / "include").rglob("*.h")]):
        digest.update(path.name.encode() + b"\0" + path.read_bytes())
    folder = cache / f"{program.name}-shipped-{digest.hexdigest()[:20]}"
    copy = folder / program.name
    if copy.is_file() and (folder / LIBRARY).is_file():
        return str(copy)
    folder.mkdir(parents=True, exist_ok=True)
    if not (folder / LIBRARY).is_file() and not _library(folder, capi, compiler):
        return None
    temporary = folder / f".{program.name}.{os.getpid()}"
    temporary.write_bytes(data)
    temporary.chmod(0o755)
    os.replace(temporary, copy)
    return str(copy)
