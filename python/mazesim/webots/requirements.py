"""What a Webots controller needs that mazesim lacks, known before the run starts.

:func:`prepare_controller` finds a controller's language, builds a C or C++ controller
(:mod:`mazesim.webots.native_controller`) and lists the Webots features and Python packages the
controller needs and this installation does not have: the run states them at its start and keeps
them in its ``summary.json`` (``missing_features``). A controller that cannot run at all (C or
C++ needing Webots headers or functions mazesim does not implement, or a Python controller
that opens Tk windows where there is no display) is not started; one that lacks a Python
package is, and fails as it would in Webots.
"""

from __future__ import annotations

import ast
import importlib.util
import os
import re
import sys
from dataclasses import dataclass, field

from mazesim._paths import MAX_TEXT_CHARACTERS, read_input

__all__ = [
    "LANGUAGES",
    "PreparedController",
    "imported_names",
    "missing_packages",
    "motor_limits",
    "prepare_controller",
]

#: Controller languages by file suffix.
LANGUAGES = {".py": "python", ".c": "c", ".cpp": "cpp", ".cc": "cpp", ".cxx": "cpp"}
#: Most of a controller's own modules read for their imports.
MAX_OWN_MODULES = 200
#: The statement for a controller that opens Tk windows where there is no display.
NO_DISPLAY = "a display for the controller's Tk windows (tkinter, turtle; $DISPLAY is not set)"
#: Modules that open Tk windows.
TK_MODULES = {"tkinter", "turtle"}
#: Calls that limit a motor's acceleration or torque (Python and C API; Webots reference manual,
#: Motor), which mazesim does not model.
_MOTOR_LIMITS = re.compile(
    r"\b(setAcceleration|setAvailableTorque|setAvailableForce|"
    r"wb_motor_set_acceleration|wb_motor_set_available_torque|wb_motor_set_available_force)"
    r"\s*\("
)
#: The statement for a controller that sets them.
MOTOR_LIMITS = (
    "motor acceleration and torque limits ({calls}): mazesim's wheels reach their commanded "
    "speed at once, as Webots' motors do by default; only the floor's friction limits how fast "
    "an imported E-puck's body starts"
)
#: Source files of each language read for those calls, beside the controller's main file.
_SOURCES = {"python": (".py",), "c": (".c", ".h"), "cpp": (".cpp", ".cc", ".cxx", ".hpp", ".h")}


@dataclass
class PreparedController:
    """A controller file ready to run.

    Attributes:
        file: The controller's main file.
        language: ``"python"``, ``"c"`` or ``"cpp"``.
        missing: What it needs that mazesim lacks, one statement each.
        runnable: Whether it can be started at all.
        program: A C controller's built program.
        notes: What was done to prepare it (a C build and where it is cached).
    """

    file: str
    language: str
    missing: list[str] = field(default_factory=list)
    runnable: bool = True
    program: str | None = None
    notes: list[str] = field(default_factory=list)


def _guarded(tree: ast.AST) -> set[int]:
    """The ids of import statements inside a ``try`` (optional imports)."""
    guarded: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Try):
            for inner in node.body:
                guarded |= {id(n) for n in ast.walk(inner)}
    return guarded


def _imports(path: str) -> list[tuple[str, str]]:
    """The modules a file imports outside ``try``: (the folder the name starts from, the dotted
    name); ``from a import b`` gives ``a.b`` (``b`` may be a submodule)."""
    try:
        source = read_input(path, MAX_TEXT_CHARACTERS, "the controller")
        tree = ast.parse(source)
    except (SyntaxError, ValueError, OSError):
        return []
    guarded = _guarded(tree)
    here = os.path.dirname(path)
    found: list[tuple[str, str]] = []
    for node in ast.walk(tree):
        if id(node) in guarded:
            continue
        if isinstance(node, ast.Import):
            found += [("", alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = ""
            if node.level:
                base = here
                for _ in range(node.level - 1):
                    base = os.path.dirname(base)
            module = node.module or ""
            for alias in node.names:
                tail = "" if alias.name == "*" else alias.name
                found.append((base, ".".join(p for p in (module, tail) if p)))
    return found


def _own_files(base: str, dotted: str) -> list[str] | None:
    """The controller's own files that ``dotted`` loads from ``base`` (packages' ``__init__.py``
    and the module), or None when its first part is not there."""
    parts = dotted.split(".")
    first = os.path.join(base, parts[0])
    if not (os.path.isdir(first) or os.path.isfile(first + ".py")):
        return None
    files: list[str] = []
    for part in parts:
        candidate = os.path.join(base, part)
        if os.path.isdir(candidate):
            init = os.path.join(candidate, "__init__.py")
            if os.path.isfile(init):
                files.append(init)
            base = candidate
        elif os.path.isfile(candidate + ".py"):
            files.append(candidate + ".py")
            break
        else:
            break
    return files


def imported_names(path: str) -> set[str]:
    """The top-level names of the modules a controller file imports (outside ``try``), and those
    its own modules and packages beside it import, but not its own modules' names."""
    folder = os.path.dirname(os.path.abspath(path))
    names: set[str] = set()
    files, seen = [os.path.abspath(path)], set[str]()
    while files and len(seen) < MAX_OWN_MODULES:
        file = files.pop()
        if file in seen:
            continue
        seen.add(file)
        for base, dotted in _imports(file):
            own = _own_files(base or folder, dotted)
            if own is None and not base:
                names.add(dotted.split(".")[0])
            else:
                files += own or []
    return names


def missing_packages(path: str) -> list[str]:
    """The Python packages a controller imports (see :func:`imported_names`) that are not
    installed; ``controller`` counts as present."""
    missing = []
    for name in sorted(imported_names(path)):
        if name in {"controller", "__future__"} or name in sys.builtin_module_names:
            continue
        try:
            found = importlib.util.find_spec(name) is not None
        except (ImportError, ValueError):
            found = False
        if not found:
            missing.append(name)
    return missing


def motor_limits(file: str, language: str) -> list[str]:
    """The motor acceleration and torque limit calls (see ``_MOTOR_LIMITS``) in the controller's
    source files: its main file and the files of its language beside it."""
    folder = os.path.dirname(os.path.abspath(file))
    try:
        names = sorted(os.listdir(folder))
    except OSError:
        names = []
    suffixes = _SOURCES.get(language, (".py",))
    paths = [os.path.join(folder, n) for n in names if n.lower().endswith(suffixes)]
    found: set[str] = set()
    for path in paths[:MAX_OWN_MODULES]:
        try:
            text = read_input(path, MAX_TEXT_CHARACTERS, "controller source")
        except OSError:
            continue
        found.update(_MOTOR_LIMITS.findall(text.decode("utf-8", "replace")))
    return sorted(found)


def prepare_controller(file: str) -> PreparedController:
    """Prepares the controller file ``file`` (see :func:`mazesim.webots.runner.controller_file`).

    Raises:
        MissingDependencyError: A C controller and no C compiler.
        ControllerBuildError: A C controller that does not compile.
    """
    language = LANGUAGES.get(os.path.splitext(file)[1].lower(), "python")
    prepared = PreparedController(file, language)
    if language in ("c", "cpp"):
        from mazesim.webots.native_controller import LANGUAGE_NAMES, build

        built = build(file)
        prepared.program = built.program
        kind = LANGUAGE_NAMES[language]
        prepared.notes.append(f"{kind} controller {os.path.basename(file)}: {built.note}")
        if built.headers:
            prepared.missing.append(
                f"Webots {kind} API header(s) mazesim does not provide: " + ", ".join(built.headers)
            )
        if built.missing:
            prepared.missing.append(
                f"Webots {kind} API function(s) mazesim does not implement: "
                + ", ".join(built.missing)
            )
        prepared.runnable = built.program is not None
    else:
        names = missing_packages(file)
        if names:
            prepared.missing.append(f"Python package(s) not installed: {', '.join(names)}")
        if TK_MODULES & imported_names(file) and not os.environ.get("DISPLAY"):
            # Tk raises at its first window; a controller that waits for the thread that
            # draws would never return, so it is not started.
            prepared.missing.append(NO_DISPLAY)
            prepared.runnable = False
    calls = motor_limits(file, language)
    if calls:
        prepared.missing.append(MOTOR_LIMITS.format(calls=", ".join(calls)))
    return prepared
