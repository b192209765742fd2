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
import configparser
import importlib.util
import os
import re
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TypeVar

from mazesim._paths import MAX_TEXT_CHARACTERS, read_input
from mazesim.webots.needed_imports import needed_guarded_imports
from mazesim.webots.stock_controllers import STOCK

_Value = TypeVar("_Value")

__all__ = [
    "LANGUAGES",
    "PreparedController",
    "imported_names",
    "missing_packages",
    "motor_limits",
    "prepare_controller",
    "scene_changes",
    "turn_in_place_speed",
    "unbuilt",
]

#: Controller languages by file suffix.
LANGUAGES = {
    ".py": "python",
    ".c": "c",
    ".cpp": "cpp",
    ".cc": "cpp",
    ".cxx": "cpp",
    ".bsg": "botstudio",
}
#: Most of a controller's own modules read for their imports.
MAX_OWN_MODULES = 200
#: The statement for a controller that opens Tk or OpenCV windows where there is no display.
NO_DISPLAY = (
    "a display for the controller's windows (Tk's: tkinter, turtle; OpenCV's: cv2.imshow, "
    "cv2.namedWindow; $DISPLAY is not set, and Xvfb, which would draw them on a virtual "
    "display, is not installed)"
)
#: What the run says of a controller whose Tk windows it draws on a virtual display.
VIRTUAL_DISPLAY_NOTE = (
    "its Tk windows (tkinter, turtle) are drawn on a virtual display (Xvfb) and not shown: "
    "$DISPLAY is not set"
)
#: Modules that open Tk windows.
TK_MODULES = {"tkinter", "turtle"}
#: OpenCV's window calls (HighGUI). OpenCV's wheels draw their windows with a Qt of their own
#: whose only platform is X11's (xcb): without a display the whole process stops (SIGABRT) at the
#: first window, and Qt's offscreen platform is not there to draw into memory.
_OPENCV_WINDOWS = re.compile(
    r"\b(?:cv2|cv)\s*\.\s*(imshow|namedWindow|startWindowThread|createTrackbar|selectROIs?|"
    r"setMouseCallback|moveWindow|resizeWindow|setWindowProperty|setWindowTitle)\s*\("
)
#: What the run says of a controller whose OpenCV windows it draws on a virtual display.
OPENCV_WINDOWS_NOTE = (
    "its OpenCV windows (cv2.imshow, cv2.namedWindow) are drawn on a virtual display (Xvfb) "
    "and not shown: $DISPLAY is not set"
)
#: Modules that open Qt windows.
QT_MODULES = {"PySide6", "PySide2", "PyQt6", "PyQt5"}
#: What the run says of a controller whose Qt windows it draws off screen.
QT_OFFSCREEN_NOTE = (
    "its Qt windows are drawn off screen (QT_QPA_PLATFORM=offscreen) and not shown: $DISPLAY "
    "is not set"
)
#: Calls that limit a motor's torque (Python and C API; Webots reference manual, Motor), which
#: mazesim does not model but for a torque of 0, which leaves the motor without control (a
#: motor's acceleration it does model: ``Motor.setAcceleration``).
_MOTOR_LIMITS = re.compile(
    r"\b(setAvailableTorque|setAvailableForce|"
    r"wb_motor_set_available_torque|wb_motor_set_available_force)"
    r"\s*\("
)
#: The statement for a controller that sets them.
MOTOR_LIMITS = (
    "motor torque limits ({calls}): mazesim's wheels reach their commanded speed as Webots' "
    "motors do at full torque (with none, 0, they do not drive, as in Webots); only the "
    "floor's friction limits how fast an imported E-puck's body starts"
)
#: Supervisor calls that add nodes to the running world or remove them (the Python and C++
#: names, then the C API's; Webots reference manual, Supervisor), which mazesim does in part; and
#: ``Node.remove()`` (``node->remove()`` in C++), a ``remove`` call without arguments.
_SCENE_CHANGES = re.compile(
    r"\b(importMFNodeFromString|importSFNodeFromString|importMFNode|importSFNode|removeMF|"
    r"removeSF|wb_supervisor_field_import_mf_node_from_string|"
    r"wb_supervisor_field_import_sf_node_from_string|wb_supervisor_field_import_mf_node|"
    r"wb_supervisor_field_import_sf_node|wb_supervisor_field_remove_mf|"
    r"wb_supervisor_field_remove_sf|wb_supervisor_node_remove)\s*\("
    r"|(?:\.|->)(remove)\s*\(\s*\)"
)
#: The statement for a controller that makes those calls.
SCENE_CHANGES = (
    "adding nodes to the running world or removing them ({calls}): mazesim imports nodes "
    "into children and empty endPoint fields and removes top-level and imported nodes, "
    "e-pucks and robots too in a run of the whole world (a robot that is not an e-puck is an "
    "obstacle); changes of other fields print an error and change nothing"
)
#: Wheel speed (rad/s) of a turn in place above which Webots' E-puck has been seen to turn
#: more slowly than its wheels' kinematics say. Controllers tuned in Webots agree with the
#: 0.05685 m wheel distance at 0.2 x 6.28 rad/s (a half turn timed in 111 steps of 32 ms),
#: but at 3.1-3.2 rad/s they find about 7.5 % less turn: 47 steps of 32 ms at 3.14 rad/s that
#: their author ends short of the half turn (176 degrees at 2.04 rad/s; the wheel distance gives
#: 190), 24 steps for a right angle (90 degrees; the wheel distance gives 97), and an
#: encoder-timed half turn at 3.2 rad/s that needs a 0.063 m wheel distance with 0.0205 m wheels.
FAST_TURN_IN_PLACE = 1.26
#: The statement for a Python controller that turns in place faster than that.
TURN_SLIP = (
    "Webots' wheel slip when an E-puck turns in place fast (the controller sets its wheels to "
    "-{speed:g} and {speed:g} rad/s): mazesim turns it at the rate its wheels give for a "
    "0.05685 m wheel distance, as Webots does at 1.26 rad/s; controllers tuned in Webots at "
    "3.1-3.2 rad/s find about 7.5 % less turn (47 steps of 32 ms at 3.14 rad/s for nearly a "
    "half turn, 24 for a right angle), so a turn timed in steps goes farther round here"
)
#: Source files of each language read for those calls, beside the controller's main file.
_SOURCES = {"python": (".py",), "c": (".c", ".h"), "cpp": (".cpp", ".cc", ".cxx", ".hpp", ".h")}
#: Source files, not headers, of a compiled controller.
_COMPILED_SOURCES = (".c", ".cpp", ".cc", ".cxx")
#: What the run says of a controller that draws on a Display.
DISPLAY_NOTE = (
    "its Display drawings are accepted and not drawn: mazesim has no view to show a display "
    "on (images keep their size only, saving one writes no file)"
)
#: A Python controller's drawing calls of Webots' Display (its first group names the call).
_DISPLAY_DRAWINGS = re.compile(
    r"\.\s*(fillRectangle|fillOval|fillPolygon|drawPixel|drawLine|drawRectangle|drawOval|"
    r"drawPolygon|drawText|imageNew|imageLoad|imageCopy|imagePaste|imageSave|attachCamera)\s*\("
)
#: The include of Webots' display header, in C or C++.
DISPLAY_INCLUDE = re.compile(r'#\s*include\s*[<"]webots/(display\.h|Display\.hpp)[>"]', re.I)
#: Source files of a compiled controller's folder.
SOURCE_SUFFIXES = (".c", ".cpp", ".cc", ".cxx", ".h", ".hpp", ".hh")
#: Headers of Windows' own API, which a build elsewhere does not find.
WINDOWS_HEADERS = {"windows.h", "winsock2.h", "conio.h", "direct.h", "io.h", "tchar.h"}
#: A compiled controller's own build files.
BUILD_FILES = ("CMakeLists.txt", "Makefile", "makefile")


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
        virtual_display: Whether its run draws its Tk windows on a virtual display
            (:mod:`mazesim.webots.virtual_display`): it opens some and ``$DISPLAY`` is not set.
        environment: Environment variables its run sets (Qt's windows drawn off screen).
        met_in_world_runs: The statements of ``missing`` that a run of the whole world meets
            (its supervisor's imports and removals), which such a run does not print.
    """

    file: str
    language: str
    missing: list[str] = field(default_factory=list)
    runnable: bool = True
    program: str | None = None
    notes: list[str] = field(default_factory=list)
    virtual_display: bool = False
    environment: dict[str, str] = field(default_factory=dict)
    met_in_world_runs: list[str] = field(default_factory=list)


def _guarded(tree: ast.AST) -> set[int]:
    """The ids of import statements inside a ``try`` (optional imports)."""
    guarded: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Try):
            for inner in node.body:
                guarded |= {id(n) for n in ast.walk(inner)}
    return guarded


def _syntax_tree(path: str) -> ast.Module | None:
    """The syntax tree of a Python controller file, or None when it cannot be read or parsed:
    a syntax error, or statements nested or chained deeper than Python's parser goes (a
    ``RecursionError``, as the controller would meet when run); the run then says why."""
    try:
        return ast.parse(read_input(path, MAX_TEXT_CHARACTERS, "the controller"))
    except (SyntaxError, ValueError, OSError, RecursionError, MemoryError):
        return None


def _imports(path: str) -> list[tuple[str, str]]:
    """The modules a file imports outside ``try``, and inside ``try`` when it needs them all
    the same (:mod:`mazesim.webots.needed_imports`): (the folder the name starts from, the
    dotted name); ``from a import b`` gives ``a.b`` (``b`` may be a submodule)."""
    tree = _syntax_tree(path)
    if tree is None:
        return []
    guarded = _guarded(tree) - {id(node) for node in needed_guarded_imports(tree)}
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


def _literal_path(node: ast.expr) -> str | None:
    """The text of a path written as a string, or as ``os.path.join`` of strings."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if (
        isinstance(node, ast.Call)
        and ast.unparse(node.func) in ("os.path.join", "path.join", "join")
        and node.args
        and all(isinstance(a, ast.Constant) and isinstance(a.value, str) for a in node.args)
    ):
        return os.path.join(*(str(a.value) for a in node.args if isinstance(a, ast.Constant)))
    return None


def path_additions(path: str) -> list[str]:
    """The folders a controller file puts on ``sys.path`` by ``sys.path.append(...)`` or
    ``sys.path.insert(i, ...)`` of a written path (``".."``, ``os.path.join("..", "lib")``),
    relative to the controller's folder, from which Webots runs it, or of a path made from the
    file's own ``__file__`` (``Path(__file__).resolve().parent.parent``,
    ``os.path.dirname(os.path.abspath(__file__))``), directly or through names the file's
    top-level statements give them (:func:`_path_of`)."""
    tree = _syntax_tree(path)
    if tree is None:
        return []
    here = os.path.dirname(os.path.abspath(path))
    names = _module_names(tree, _path_of, {"__file__": os.path.abspath(path)})
    folders = []
    calls = [node for node in ast.walk(tree) if isinstance(node, ast.Call)]
    for node in sorted(calls, key=lambda call: (call.lineno, call.col_offset)):
        if (
            isinstance(node.func, ast.Attribute)
            and node.func.attr in ("append", "insert")
            and ast.unparse(node.func.value) == "sys.path"
            and node.args
        ):
            written = _literal_path(node.args[-1]) or _path_of(node.args[-1], names)
            if written is not None:
                folders.append(os.path.normpath(os.path.join(here, written)))
    return folders


#: Calls that give their argument's path back as it is, or in another type.
_SAME_PATH = frozenset(
    "str Path pathlib.Path PurePath pathlib.PurePath os.fspath os.path.abspath "
    "os.path.realpath os.path.normpath path.abspath path.realpath path.normpath".split()
)


def _path_of(node: ast.expr, names: dict[str, str]) -> str | None:
    """The path an expression makes from ``__file__`` and the paths in ``names`` (by the
    ``pathlib`` and ``os.path`` calls a controller uses to find its folder and its
    project's), or None when it makes none mazesim can tell without running it."""
    if isinstance(node, ast.Name):
        return names.get(node.id)
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if isinstance(node, ast.Attribute) and node.attr == "parent":
        inner = _path_of(node.value, names)
        return None if inner is None else os.path.dirname(inner)
    if (
        isinstance(node, ast.Subscript)
        and isinstance(node.value, ast.Attribute)
        and node.value.attr == "parents"
        and isinstance(node.slice, ast.Constant)
        and isinstance(node.slice.value, int)
    ):
        inner = _path_of(node.value.value, names)
        for _ in range(node.slice.value + 1):
            inner = None if inner is None else os.path.dirname(inner)
        return inner
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div):
        left, right = _path_of(node.left, names), _path_of(node.right, names)
        return None if left is None or right is None else os.path.join(left, right)
    if not isinstance(node, ast.Call):
        return None
    called = ast.unparse(node.func)
    if isinstance(node.func, ast.Attribute) and node.func.attr in ("resolve", "absolute"):
        return _path_of(node.func.value, names)
    parts = [_path_of(a, names) for a in node.args]
    if not parts or any(part is None for part in parts):
        return None
    paths = [str(part) for part in parts]
    if called in _SAME_PATH and len(paths) == 1:
        return os.path.normpath(paths[0])
    if called in ("os.path.dirname", "path.dirname") and len(paths) == 1:
        return os.path.dirname(paths[0])
    if called in ("os.path.join", "path.join"):
        return os.path.join(*paths)
    return None


#: The section of a controller folder's ``runtime.ini`` whose variables hold paths, which Webots
#: sets in the controller's environment (``:``-separated, relative to the controller's folder).
RUNTIME_PATHS_SECTION = "environment variables with paths"
_REFERENCE = re.compile(r"\$\((\w+)\)")


def runtime_python_paths(path: str) -> list[str]:
    """The folders the ``PYTHONPATH`` of the ``runtime.ini`` beside a controller file puts on
    the controller's module path, as Webots does: its ``[environment variables with paths]``
    section, ``:``-separated paths relative to the controller's folder, a ``$(NAME)`` replaced by
    the environment's variable (an entry naming one that is not set is left out)."""
    here = os.path.dirname(os.path.abspath(path))
    parser = configparser.ConfigParser(interpolation=None, strict=False)
    try:
        with open(os.path.join(here, "runtime.ini"), encoding="utf-8", errors="replace") as ini:
            parser.read_file(ini)
        written = parser.get(RUNTIME_PATHS_SECTION, "PYTHONPATH", fallback="")
    except (OSError, configparser.Error):
        return []
    folders = []
    for entry in written.split(":"):
        names = _REFERENCE.findall(entry)
        if not entry.strip() or any(name not in os.environ for name in names):
            continue
        for expanded in _REFERENCE.sub(lambda m: os.environ[m.group(1)], entry).split(":"):
            if expanded.strip():
                folders.append(os.path.normpath(os.path.join(here, expanded.strip())))
    return folders


def imported_names(path: str) -> set[str]:
    """The top-level names of the modules a controller file imports (outside ``try``, or inside
    it when it needs them all the same), and those
    its own modules and packages beside it (or in a folder it puts on ``sys.path``,
    :func:`path_additions`, or its ``runtime.ini`` on its module path,
    :func:`runtime_python_paths`) import, but not its own modules' names."""
    folder = os.path.dirname(os.path.abspath(path))
    roots = [folder, *runtime_python_paths(path), *path_additions(path)]
    names: set[str] = set()
    files, seen = [os.path.abspath(path)], set[str]()
    while files and len(seen) < MAX_OWN_MODULES:
        file = files.pop()
        if file in seen:
            continue
        seen.add(file)
        for base, dotted in _imports(file):
            own = _own_files(base, dotted) if base else _first_own(roots, dotted)
            if own is None and not base:
                names.add(dotted.split(".")[0])
            else:
                files += own or []
    return names


def _first_own(roots: list[str], dotted: str) -> list[str] | None:
    """The controller's own files ``dotted`` loads from the first of ``roots`` that holds it."""
    for root in roots:
        own = _own_files(root, dotted)
        if own is not None:
            return own
    return None


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


def _folder_texts(file: str, suffixes: tuple[str, ...], below: bool = False) -> list[str]:
    """The texts of the controller's source files with one of ``suffixes`` (lower case): its
    main file and those beside it (with ``below``, those in the folders below it too), at most
    ``MAX_OWN_MODULES`` of them; unreadable ones are left out."""
    folder = os.path.dirname(os.path.abspath(file))
    if below:
        found = (os.path.join(top, n) for top, _, names in os.walk(folder) for n in names)
        paths = sorted(p for p in found if p.lower().endswith(suffixes))
    else:
        try:
            names = sorted(os.listdir(folder))
        except OSError:
            return []
        paths = [os.path.join(folder, n) for n in names if n.lower().endswith(suffixes)]
    texts = []
    for path in paths[:MAX_OWN_MODULES]:
        if not os.path.isfile(path):
            continue
        try:
            texts.append(read_input(path, MAX_TEXT_CHARACTERS, "controller source"))
        except OSError:
            continue
    return [text.decode("utf-8", "replace") for text in texts]


def _calls(file: str, language: str, calls: re.Pattern[str]) -> list[str]:
    """The names of the functions ``calls`` finds (its first group that matched) in the
    controller's source files: its main file and the files of its language beside it, and for
    C and C++ the sources (not the headers) in the folders below it (a Makefile's ``src/``)."""
    found: set[str] = set()
    texts = _folder_texts(file, _SOURCES.get(language, (".py",)))
    if language in ("c", "cpp"):
        texts += _folder_texts(file, _COMPILED_SOURCES, below=True)
    for text in texts:
        found.update(next(g for g in m.groups() if g) for m in calls.finditer(text))
    return sorted(found)


def motor_limits(file: str, language: str) -> list[str]:
    """The motor torque limit calls (see ``_MOTOR_LIMITS``) in the controller's
    source files: its main file and the files of its language beside it."""
    return _calls(file, language, _MOTOR_LIMITS)


def scene_changes(file: str, language: str) -> list[str]:
    """The supervisor calls that add nodes to the running world or remove them (see
    ``_SCENE_CHANGES``; ``remove`` for ``Node.remove()``) in the controller's source files: its
    main file and the files of its language beside it."""
    return _calls(file, language, _SCENE_CHANGES)


def _constant(node: ast.AST, known: dict[str, float]) -> float | None:
    """The value of a constant expression of numbers and ``known`` names (+, -, *, /), or
    None."""
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
        return None if isinstance(node.value, bool) else float(node.value)
    if isinstance(node, ast.Name):
        return known.get(node.id)
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        inner = _constant(node.operand, known)
        return None if inner is None else (-inner if isinstance(node.op, ast.USub) else inner)
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub, ast.Mult, ast.Div)):
        left, right = _constant(node.left, known), _constant(node.right, known)
        if left is None or right is None:
            return None
        if isinstance(node.op, ast.Add):
            return left + right
        if isinstance(node.op, ast.Sub):
            return left - right
        if isinstance(node.op, ast.Mult):
            return left * right
        return left / right if right != 0.0 else None
    return None


def _velocity(statement: ast.stmt, known: dict[str, float]) -> float | None:
    """The wheel speed a ``motor.setVelocity(E)`` statement sets, when its constants give it."""
    if not isinstance(statement, ast.Expr) or not isinstance(statement.value, ast.Call):
        return None
    call = statement.value
    if not (isinstance(call.func, ast.Attribute) and call.func.attr == "setVelocity"):
        return None
    return _constant(call.args[0], known) if len(call.args) == 1 else None


def turn_in_place_speed(path: str) -> float | None:
    """The fastest turn in place a Python controller file commands: a wheel speed ``v`` that
    two ``setVelocity`` statements of one block set as ``-v`` and ``v``, as its module-level
    constants give them (rad/s); None when it commands none."""
    tree = _syntax_tree(path)
    if tree is None:
        return None
    known = _module_names(tree, _constant, {})
    fastest: float | None = None
    for node in ast.walk(tree):
        for block in (getattr(node, "body", None), getattr(node, "orelse", None)):
            if not isinstance(block, list):
                continue
            speeds = {_velocity(statement, known) for statement in block}
            turns = [v for v in speeds if v is not None and v > 0.0 and -v in speeds]
            if turns:
                fastest = max([*turns, *([fastest] if fastest is not None else [])])
    return fastest


def _project_build(file: str) -> str:
    """The build files of a compiled controller's folder (``CMakeLists.txt``, ``Makefile``)."""
    folder = os.path.dirname(os.path.abspath(file))
    found = [name for name in BUILD_FILES if os.path.isfile(os.path.join(folder, name))]
    said = "its own " + " and ".join(found) if found else "a build of its own"
    if "CMakeLists.txt" in found:
        from mazesim.webots.cmake_build import cmake_program

        if cmake_program() is None:
            said += ", which cmake, not installed here, would run"
    return said


def _includes_display(file: str) -> bool:
    """Whether a compiled controller's folder includes Webots' display header."""
    return any(DISPLAY_INCLUDE.search(text) for text in _folder_texts(file, SOURCE_SUFFIXES))


def prepare_controller(file: str) -> PreparedController:
    """Prepares the controller file ``file`` (see :func:`mazesim.webots.runner.controller_file`).

    Raises:
        MissingDependencyError: A C controller and no C compiler.
        ControllerBuildError: A C controller that does not compile.
    """
    language = LANGUAGES.get(os.path.splitext(file)[1].lower(), "python")
    prepared = PreparedController(file, language)
    if language == "botstudio":
        # An automaton of BotStudio's states and transitions: it imports and builds nothing.
        return prepared
    if os.path.abspath(file) in {os.path.abspath(stock) for stock in STOCK.values()}:
        # mazesim's own stock controller uses nothing mazesim lacks; the files beside it are
        # mazesim's modules, not the controller's.
        return prepared
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
        if built.libraries:
            prepared.missing.append(
                "librar(ies) its Makefile links that are not installed here: "
                + ", ".join(built.libraries)
            )
        windows = [name for name in built.elsewhere if name.lower() in WINDOWS_HEADERS]
        others = [name for name in built.elsewhere if name not in windows]
        if windows:
            prepared.missing.append(
                "Windows' own header(s), which only a Windows build finds (the controller is "
                "written for Windows): " + ", ".join(windows)
            )
        if others:
            prepared.missing.append(
                "header(s) found neither in the controller's folder nor on this system: "
                + ", ".join(others)
                + f" (the project builds the controller with {_project_build(file)})"
            )
        if built.program is not None and _includes_display(file):
            prepared.notes.append(f"{kind} controller {os.path.basename(file)}: {DISPLAY_NOTE}")
        prepared.runnable = built.program is not None
    else:
        names = missing_packages(file)
        if names:
            prepared.missing.append(f"Python package(s) not installed: {', '.join(names)}")
        imported = imported_names(file)
        if QT_MODULES & imported and not os.environ.get("DISPLAY"):
            if "QT_QPA_PLATFORM" not in os.environ:
                prepared.notes.append(QT_OFFSCREEN_NOTE)
                prepared.environment["QT_QPA_PLATFORM"] = "offscreen"
        tk = bool(TK_MODULES & imported)
        opencv = "cv2" in imported and bool(_calls(file, language, _OPENCV_WINDOWS))
        if (tk or opencv) and not os.environ.get("DISPLAY"):
            from mazesim.webots import virtual_display

            if virtual_display.xvfb_program() is not None:
                prepared.notes += [VIRTUAL_DISPLAY_NOTE] * tk + [OPENCV_WINDOWS_NOTE] * opencv
                prepared.virtual_display = True
            else:
                # Tk raises at its first window; a controller that waits for the thread that
                # draws would never return, and OpenCV's Qt stops the process: neither is
                # started.
                prepared.missing.append(NO_DISPLAY)
                prepared.runnable = False
        if _calls(file, language, _DISPLAY_DRAWINGS):
            prepared.notes.append(f"Python controller {os.path.basename(file)}: {DISPLAY_NOTE}")
        speed = turn_in_place_speed(file)
        if speed is not None and speed > FAST_TURN_IN_PLACE:
            prepared.missing.append(TURN_SLIP.format(speed=round(speed, 4)))
    calls = motor_limits(file, language)
    if calls:
        prepared.missing.append(MOTOR_LIMITS.format(calls=", ".join(calls)))
    calls = scene_changes(file, language)
    if calls:
        statement = SCENE_CHANGES.format(calls=", ".join(calls))
        prepared.missing.append(statement)
        prepared.met_in_world_runs.append(statement)
    return prepared


def unbuilt(file: str, failure: Exception) -> PreparedController:
    """A C or C++ controller of a world's robot that does not compile, prepared not to run: in a
    world of several robots its robot stands still, as one whose controller Webots cannot build
    does, while the others run. Its statement quotes the compiler's first error."""
    from mazesim.webots.native_controller import LANGUAGE_NAMES

    language = LANGUAGES.get(os.path.splitext(file)[1].lower(), "c")
    lines = str(failure).splitlines()
    first = next((line.strip() for line in lines if "error:" in line), lines[0] if lines else "")
    kind = LANGUAGE_NAMES.get(language, "C")
    statement = f"its {kind} controller {os.path.basename(file)} does not compile here: {first}"
    return PreparedController(file, language, missing=[statement], runnable=False)


def _module_names(
    tree: ast.Module,
    value_of: Callable[[ast.expr, dict[str, _Value]], _Value | None],
    names: dict[str, _Value],
) -> dict[str, _Value]:
    """``names`` with the module's top-level ``NAME = value`` assignments whose value
    ``value_of`` works out (from the names known so far), in source order."""
    for statement in tree.body:
        if isinstance(statement, ast.Assign) and len(statement.targets) == 1:
            target = statement.targets[0]
            value = value_of(statement.value, names)
            if isinstance(target, ast.Name) and value is not None:
                names[target.id] = value
    return names
