"""mazesim: a fast, deterministic simulator of a small differential-drive robot in mazes.

The simulation runs in a compiled Rust core (:mod:`mazesim._core`); this package adds the world
loader, the report's controllers, plots and the ``mazesim`` command line.

Example:
    >>> import mazesim
    >>> world = mazesim.load_world("seed-maze")
    >>> sim = mazesim.Simulator(world, robot="e-puck", seed=0)
    >>> sim.step(3.14, 3.14)
    >>> sim.distance_sensors().shape
    (8,)
"""

from __future__ import annotations

import os
import sys

from mazesim import _checks, _core, _display, _pickling
from mazesim._core import (
    AvoidCollisionSettings,
    BatchSimulator,
    DrivePerturbation,
    EpisodeLimits,
    MazeLayout,
    RobotProfile,
    RunSettings,
    SensingPerturbation,
    Simulator,
    TabularSettings,
    World,
    __version__,
    builtin_world_names,
    default_codes,
    generate_maze,
    robot_profile_names,
    sharp_volts_to_cm,
    validate_codes,
)
from mazesim.errors import (
    InternalError,
    InvalidActionError,
    InvalidArgumentError,
    MazesimError,
    MazesimIOError,
    SimulatorBusyError,
    SnapshotError,
    UnknownNameError,
    WorldFormatError,
    WrongTypeError,
)

# Every public module imported from here on gets the argument check (mazesim._checks).
_checks.install()
_pickling.refuse_unpicklable(_core)
_display.install(World, Simulator)  # a notebook draws a world or a simulator, not its repr

__all__ = [
    "AvoidCollisionSettings",
    "BatchSimulator",
    "DrivePerturbation",
    "EpisodeLimits",
    "InternalError",
    "InvalidActionError",
    "InvalidArgumentError",
    "MazeLayout",
    "MazesimError",
    "MazesimIOError",
    "RobotProfile",
    "RunSettings",
    "SensingPerturbation",
    "Simulator",
    "SimulatorBusyError",
    "SnapshotError",
    "TabularSettings",
    "UnknownNameError",
    "World",
    "WorldFormatError",
    "WrongTypeError",
    "__version__",
    "builtin_world_names",
    "default_codes",
    "generate_maze",
    "load_world",
    "robot_profile_names",
    "sharp_volts_to_cm",
    "validate_codes",
]
__dir__ = _checks.listing(sys.modules[__name__])  # dir(mazesim), mazesim.<Tab>: the API


def load_world(name_or_path: str | os.PathLike[str]) -> World:
    """Loads a built-in world by name, or a world file by path.

    A string that names a built-in world (see :func:`builtin_world_names`) wins over a file of
    the same name in the current folder; anything else is read as a path to a ``.toml`` world file,
    or to a Webots ``.wbt`` world, which is imported (see :func:`mazesim.webots.import_wbt`). A
    world file without a ``name`` is named after the file (``my-maze`` for ``my-maze.toml``).

    Args:
        name_or_path: A built-in world name such as ``"seed-maze"``
            (``mazesim.builtin_world_names()`` or ``mazesim worlds`` lists them), or a path to a
            world file (``.toml`` or ``.wbt``).

    Returns:
        The loaded world.

    Raises:
        UnknownNameError: It is neither a built-in world nor an existing file; the message and the
            ``available`` attribute list the built-in names.
        WorldFormatError: The file is not a valid world (the message names file, line and field).
        MazesimIOError: The file exists but cannot be read.
        InvalidArgumentError: ``name_or_path`` is neither a str nor an ``os.PathLike``.
    """
    from mazesim._paths import fs_path

    if isinstance(name_or_path, str) and name_or_path in builtin_world_names():
        return World.builtin(name_or_path)
    path = fs_path(name_or_path, "name_or_path")  # as World.load takes it: bytes refused
    if os.path.isfile(path):
        if path.lower().endswith(".wbt"):
            from mazesim.webots.importer import import_wbt

            return import_wbt(path)[0]
        try:
            return World.load(path)
        except (WorldFormatError, MazesimIOError) as unreadable_world:
            advice = _not_a_world_advice(path, isinstance(unreadable_world, WorldFormatError))
            if not advice:
                raise
            if isinstance(unreadable_world, MazesimIOError):
                raise MazesimIOError(f"{unreadable_world}{advice}") from None
            raise WorldFormatError(
                f"{unreadable_world}{advice}",
                source=getattr(unreadable_world, "source", None),
                line=getattr(unreadable_world, "line", None),
                column=getattr(unreadable_world, "column", None),
                field=getattr(unreadable_world, "field", None),
            ) from None
    from mazesim._paths import unknown_name_or_file

    raise unknown_name_or_file(
        path,
        "world",
        sorted(builtin_world_names()),
        "a .toml or .wbt world file",
        (".toml", ".wbt"),
    )


#: The most characters of a file that is no world read to tell whether it is a drawn maze.
_MOST_MAP_CHARACTERS = 1 << 20

#: The first bytes of the picture files a maze may be drawn in, and their names.
_PICTURE_SIGNATURES = (
    (b"\x89PNG\r\n\x1a\n", "a PNG image"),
    (b"\xff\xd8\xff", "a JPEG image"),
    (b"GIF8", "a GIF image"),
    (b"BM", "a BMP image"),
    (b"%PDF", "a PDF document"),
)


def _not_a_world_advice(path: str, read_as_toml: bool) -> str:
    """What to add to the error of a file ``load_world`` could not read as a world: which kind
    of file it found, which files are worlds, and what to do with a maze drawn as a ``[grid]``
    map or in a picture; "" when there is nothing to add (a ``.toml`` world with a mistake)."""
    try:
        with open(path, "rb") as file:
            start = file.read(8)
    except OSError:
        return ""
    picture = next((kind for magic, kind in _PICTURE_SIGNATURES if start.startswith(magic)), None)
    if picture is not None:
        return (
            f" (found {picture}: mazesim reads .toml world files and .wbt Webots worlds, not "
            "pictures; draw the maze as a [grid] map of +--+ and | in a .toml world file, or "
            "generate one with mazesim.generate_maze: docs/own-maze.md shows both)"
        )
    suffix = os.path.splitext(path)[1]
    grid_map = _grid_map_advice(path)
    if suffix.lower() == ".toml" or not read_as_toml:
        return grid_map
    # Another kind of file read as TOML: say which files are worlds.
    return (
        " (mazesim reads .toml world files and .wbt Webots worlds; "
        + (f"found a {suffix} file)" if suffix else "found a file without an extension)")
        + grid_map
    )


def _grid_map_advice(path: str) -> str:
    """What to do with a file that is not a world but holds a maze drawn as a ``[grid]`` map (a
    hand-drawn ``.txt``, or a ``.toml`` holding the map alone): paste it into a world file; ""
    for any other file."""
    from mazesim.maze import looks_like_grid_map

    try:
        with open(path, encoding="utf-8") as file:
            text = file.read(_MOST_MAP_CHARACTERS)
    except (OSError, UnicodeDecodeError):
        return ""
    if not looks_like_grid_map(text):
        return ""
    return (
        "; it holds a maze drawn as a [grid] map: paste it into a .toml world file under "
        '[grid] map = """...""", after the lines format = "mazesim-world" and version = 1 '
        "(docs/own-maze.md shows such a file)"
    )


_checks.guard_module(_checks.sys.modules[__name__])

# gymnasium is optional (pip install "mazesim[gym]"): with it, mazesim/EPuckMaze-v0 and the task
# suite are registered once both mazesim and gymnasium are imported, in either order; importing
# mazesim alone does not import gymnasium (mazesim._gym_registration).
from mazesim import _gym_registration  # noqa: E402

_gym_registration.register_when_gymnasium_is_imported()
