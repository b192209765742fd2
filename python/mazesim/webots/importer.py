"""Importing Webots ``.wbt`` worlds as mazesim worlds.

The reading and the conversion happen in the compiled core (``mazesim_core::wbt``): every
collision shape of the world that meets the e-puck's height becomes a wall; an object with physics
becomes a movable body when it is one box or disc at most 0.5 m wide and 1.5 kg heavy, otherwise a
static obstacle with a warning. The robot's pose becomes the start, its model picks
the robot profile, ``WorldInfo.basicTimeStep`` the time step. Floor image textures found beside
the world file (PNG or JPEG, decoded here with Pillow) become floor paint. The report says what
was imported and what was not (unknown PROTOs, meshes, tilted objects, missing textures), in
metres and radians, world frame, z up.
"""

from __future__ import annotations

import errno
import os
import re
import warnings
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any, Literal, TypedDict, TypeVar, Union, cast

import numpy as np
import numpy.typing as npt

from mazesim import _core
from mazesim._core import World
from mazesim._paths import open_input, read_input
from mazesim.errors import MazesimIOError
from mazesim.webots.recognition import RecognitionReport, read_recognition

if TYPE_CHECKING:
    from mazesim.webots.proto.resolver import Resolver

__all__ = [
    "BoxObstacle",
    "CircleObstacle",
    "ExtensionDevice",
    "FloorTexture",
    "WallTexture",
    "ImportReport",
    "RobotPose",
    "WorldRobot",
    "import_summary",
    "import_wbt",
    "import_wbt_text",
    "robot_warnings",
    "undownloaded_textures",
    "world_run_warnings",
]

#: Largest world file the PROTO engine reads (a larger one goes to the core, which refuses it).
MAX_WORLD_BYTES = 64 * 1024 * 1024

#: Robot node types that mazesim simulates as they are.
E_PUCK_MODELS = ("E-puck", "e-puck", "e-puck2", "E-puck2", "EPuck")


class BoxObstacle(TypedDict):
    """A box seen from above: centre [x, y], size [sx, sy] along its own axes, yaw; ``owners``,
    the lines of the world file's nodes that hold it (a supervisor moving one moves it),
    ``walls``, its first wall among the world's ``[[walls]]`` and how many it is, and
    ``reflectance``, the infra-red reflection factor its appearance gives it (docs/webots.md)."""

    kind: Literal["box"]
    center: list[float]
    size: list[float]
    yaw: float
    owners: list[int]
    walls: list[int]
    reflectance: float


class CircleObstacle(TypedDict):
    """An upright cylinder, capsule or sphere seen from above (a ring of walls in the world),
    with ``owners``, ``walls`` and ``reflectance`` as a :class:`BoxObstacle`'s."""

    kind: Literal["circle"]
    center: list[float]
    radius: float
    owners: list[int]
    walls: list[int]
    reflectance: float


class RobotPose(TypedDict):
    """The e-puck's start pose."""

    x: float
    y: float
    yaw: float


#: A device field's value: a number, numbers, lookup-table rows, text(s) or a flag.
DeviceFieldValue = Union[float, list[float], list[list[float]], str, list[str], bool]


class ExtensionDevice(TypedDict):
    """A device in the robot's ``turretSlot``, ``groundSensorsSlot`` or ``bodySlot``, or (slot
    ``children``) anywhere among a plain ``Robot`` e-puck's children that is not one of the
    e-puck's own devices.

    ``translation`` is in the robot's frame (x forward, y left, z up; metres, the slot's origin
    taken as the robot's), ``yaw`` the direction of the device's x axis in that frame, ``pitch``
    how far that axis points below the horizontal (pi/2: at the floor), and
    ``fields`` its other fields (``lookupTable`` as rows of three numbers).
    """

    type: str
    name: str
    slot: str
    translation: list[float]
    yaw: float
    pitch: float
    fields: dict[str, DeviceFieldValue]


class FloorTexture(TypedDict):
    """An image texture on the floor: where it lies, how it tiles (``repeat``: whether the image
    repeats along its x and y, the ``ImageTexture``'s ``repeatS`` and ``repeatT``; one that does
    not is laid once, its edge stretched to the floor's), which files were looked for."""

    urls: list[str]
    owner: str
    center: list[float]
    size: list[float]
    yaw: float
    tile: list[float]
    repeat: list[bool]
    candidates: list[str]


class WallTexture(TypedDict):
    """An image texture of a wall's appearance: the red and the ``colour`` the appearance gives
    a white texture, its roughness, and the files looked for (its image's mean colour sets the
    wall's infra-red reflection factor, by its red, and the colour a camera sees)."""

    urls: list[str]
    owner: str
    red: float
    colour: list[float]
    roughness: float
    candidates: list[str]


class WorldRobot(TypedDict):
    """A robot of the world file, as listed in the report's ``robots``: its start ``pose``,
    ``model``, the ``profile`` that simulates it (``None`` for a robot that is not an e-puck:
    its controller runs, its body does not move), its ``controller``, ``name`` and ``def_name``
    fields, the ``line`` of its node and whether its body is modelled Y-up (``y_up``: forward
    along its node's local -z, up its local y, as every robot of a file before R2022a, and a
    body built so and stood upright by its ``rotation`` in a later file), the type of its node
    once the project's PROTOs are expanded (``node_type``: ``E-puck``, ``Robot``...) and that
    node's own ``model`` field (``model_field``, None when it writes none)."""

    pose: list[float]
    model: str
    profile: str | None
    controller: str | None
    name: str | None
    def_name: str | None
    line: int
    y_up: bool
    node_type: str
    model_field: str | None


class ImportReport(TypedDict):
    """What ``mazesim import-wbt --json`` prints.

    ``robot_model`` is the robot as found (``"E-puck"``, ``"e-puck2"`` for ``version "2"``, the
    type name of another robot, ``None`` without one); ``robot_line`` the line of its node in
    the file (``None`` without one); ``robot_profile`` the mazesim profile
    that simulates it (``"e-puck"`` or ``"e-puck2"``); ``robots`` every robot of the file
    (see :class:`WorldRobot`); ``missing_devices`` the e-puck's own devices (``ps0``,
    ``gs0``, ``camera``...) the robot's node lacks, which Webots' ``getDevice`` does not find
    (a plain robot node's missing children; an E-puck's ground sensors without their module);
    ``floor_paint`` the number of paint rectangles the floor textures gave; ``floor_marks``
    the floor marks held by nodes (each its ``paint`` index and the ``owners``' lines: a
    supervisor that moves a node moves them); ``bodies`` the movable bodies (``kind``,
    ``center``, ``size`` and ``yaw`` or ``radius``, ``mass`` in kg, floor ``friction``,
    ``owners`` and ``reflectance`` as an obstacle's, the ``colour`` a camera sees, whether it
    is a ``sphere`` and its ``height`` in m); ``sensed_only`` the obstacles that only the
    infra-red sensors and the camera meet (``kind``, ``center``, ``size`` and ``yaw`` or
    ``radius``, and ``reflectance`` as an obstacle's: visual-only shapes, of no Solid with a
    ``boundingObject``, in the proximity sensors' rays, which Webots' infra-red rays see and
    nothing collides with); ``one_controller_warnings``
    those of ``warnings`` that concern a run of one controller only (the world's other e-pucks,
    which a run of the whole world simulates); ``recognition`` the cameras' Recognition nodes
    and the objects with ``recognitionColors`` (:mod:`mazesim.webots.recognition`; empty for a
    file the core reads itself).
    """

    obstacles: list[BoxObstacle | CircleObstacle]
    sensed_only: list[dict[str, object]]
    bodies: list[dict[str, object]]
    robot: RobotPose | None
    basic_time_step_ms: float
    warnings: list[str]
    one_controller_warnings: list[str]
    robot_model: str | None
    robot_line: int | None
    robot_profile: str
    robots: list[WorldRobot]
    extension_devices: list[ExtensionDevice]
    missing_devices: list[str]
    floor_textures: list[FloorTexture]
    wall_textures: list[WallTexture]
    floor_paint: int
    floor_marks: list[dict[str, object]]
    protos: ProtoReport
    recognition: RecognitionReport


class ProtoReport(TypedDict):
    """What the PROTO engine did: the PROTO types expanded (with the file or URL each was read
    from), those replaced by mazesim's stand-ins (with what the stand-in models), the URLs
    read from the download cache and those downloaded."""

    expanded: dict[str, str]
    stand_ins: dict[str, str]
    cache_hits: list[str]
    downloads: list[str]


#: Most pixels of a texture image read (8192 x 8192): a larger one is named in a warning and
#: left out, as one that cannot be decoded (a small file may declare a huge image).
MAX_TEXTURE_PIXELS = 8192 * 8192


@contextmanager
def _texture_image(path: str, what: str) -> Iterator[Any]:
    """The image of a texture file, opened, at most :data:`MAX_TEXTURE_PIXELS` pixels.

    Raises:
        OSError: The file cannot be read or decoded, or its image is larger.
    """
    from PIL import Image

    with open_input(path, what) as raw, warnings.catch_warnings():
        warnings.simplefilter("ignore", Image.DecompressionBombWarning)
        try:
            image = Image.open(raw)
        except Image.DecompressionBombError as error:
            raise OSError(f"too large an image: {error}") from None
        with image:
            width, height = image.size
            if width * height > MAX_TEXTURE_PIXELS:
                raise OSError(
                    f"an image of {width} x {height} pixels, more than the"
                    f" {MAX_TEXTURE_PIXELS} mazesim reads"
                )
            yield image


def grey_levels(path: str) -> npt.NDArray[np.float64]:
    """Reads an image file (PNG, JPEG, ...) as grey levels in [0, 1].

    Args:
        path: The image file.

    Returns:
        A C-contiguous ``(height, width)`` float64 array, the top row first.

    Raises:
        OSError: The file cannot be read or decoded, or its image has more than
            :data:`MAX_TEXTURE_PIXELS` pixels.
    """
    with _texture_image(path, "the floor texture") as image:
        grey = image.convert("L")
    return np.ascontiguousarray(np.asarray(grey, dtype=np.float64) / 255.0)


def mean_colour(path: str) -> tuple[float, float, float]:
    """The mean red, green and blue of an image file (PNG, JPEG, ...), each in [0, 1]: the one
    colour of a wall textured with it, which Webots' infra-red sensors read (by its red) and a
    camera sees, on average over its surface.

    Raises:
        OSError: The file cannot be read or decoded, or its image has more than
            :data:`MAX_TEXTURE_PIXELS` pixels.
    """
    from PIL import ImageStat

    with _texture_image(path, "the wall texture") as image:
        # The mean of each band from its histogram (exact sums), with no copy of the pixels.
        means = ImageStat.Stat(image.convert("RGB")).mean
    red, green, blue = (float(min(max(v / 255.0, 0.0), 1.0)) for v in means)
    return red, green, blue


#: What a texture that cannot be read leaves, by the kind of its owner.
_UNREAD = {
    "floor": "the floor is left bare",
    "wall": (
        "the wall reflects as white and a camera sees it in its appearance's own colour "
        "(grey without one)"
    ),
}

_Value = TypeVar("_Value")


def _texture_values(
    textures: list[dict[str, Any]],
    kind: str,
    read: Callable[[str], _Value],
    resolver: Resolver | None,
) -> tuple[dict[str, _Value], list[str]]:
    """What ``read`` makes of each texture's image (a floor's grey levels, a wall's mean red),
    by the candidate the core looks it up by: the first candidate file that exists, else the
    URL's file through ``resolver`` or the download cache (:func:`_downloaded`); and a warning
    for each image that cannot be had or decoded: the one place a missing texture of any kind
    is said, naming the files looked for. ``kind``: ``floor`` or ``wall``."""
    values: dict[str, _Value] = {}
    problems: list[str] = []
    for texture in textures:
        files = [(c, c) for c in texture["candidates"] if os.path.isfile(c)]
        if not files and texture["candidates"]:
            said = len(problems)
            files = _downloaded(texture, kind, problems, resolver)
            if not files and len(problems) == said:
                urls = texture["urls"]
                problems.append(
                    f'{texture["owner"]}: {kind} texture "{urls[0] if urls else ""}" not found '
                    f"(looked for {', '.join(texture['candidates'])}): {_UNREAD[kind]}"
                )
        for key, candidate in files[:1]:
            if key in values:
                continue
            try:
                values[key] = read(candidate)
            except OSError as error:
                problems.append(
                    f"{texture['owner']}: {kind} texture {candidate}: expected a PNG or JPEG "
                    f"image, cannot decode it ({error}); {_UNREAD[kind]}"
                )
    return values, problems


def _downloaded(
    texture: dict[str, Any], kind: str, problems: list[str], resolver: Resolver | None
) -> list[tuple[str, str]]:
    """A ``kind`` (floor or wall) texture given by an http(s) URL, through the PROTO engine's
    download cache, or by a ``webots://`` URL, found as the PROTO engine finds a ``webots://``
    PROTO (the Webots installation, the Webots tree the world lies in, else Webots' repository
    at the world's version through that cache): [(the candidate the core looks the image up by,
    the file)], or [] with a warning naming the URL."""
    from mazesim.webots.proto import ProtoUnavailableError, fetch_url

    for url in map(str, texture["urls"]):
        webots = url.startswith("webots://") and resolver is not None
        if not webots and not url.startswith(("http://", "https://")):
            continue
        try:
            found = resolver.webots_texture(url) if webots and resolver else fetch_url(url)
            return [(texture["candidates"][0], str(found))]
        except ProtoUnavailableError as error:
            problems.append(f"{texture['owner']}: {kind} texture: {error}; {_UNREAD[kind]}")
            return []
    return []


#: What a warning of :func:`_downloaded` holds between the owner and the download's failure.
_UNDOWNLOADED = re.compile(r": floor texture: (https?://\S+?): cannot be downloaded \(")


def undownloaded_textures(warnings: list[str]) -> list[str]:
    """What an import's ``warnings`` say the world needs from the network and did not get: one
    statement for each floor texture given by an http(s) URL that could neither be downloaded
    nor found in the download cache (the run says them at its start, with what the
    controller lacks)."""
    statements = []
    for warning in warnings:
        found = _UNDOWNLOADED.search(warning)
        if found is not None:
            statements.append(
                f"the floor texture {found.group(1)}, which cannot be downloaded here and is not "
                f"in the download cache (no network): the floor's paint is left out"
            )
    return statements


def _with_floor(
    imported: tuple[World, dict[str, Any]],
    again: Callable[
        [dict[str, npt.NDArray[np.float64]], dict[str, tuple[float, float, float]]],
        tuple[World, dict[str, Any]],
    ],
    resolver: Resolver | None = None,
) -> tuple[World, ImportReport]:
    """Imports again with the floor textures' images and the wall textures' mean colours
    (``webots://`` and http(s) ones through the world's ``resolver``) when any was found; each
    texture that cannot be had is warned of once, floor and wall alike."""
    world, report = imported
    images, problems = _texture_values(report["floor_textures"], "floor", grey_levels, resolver)
    textures = report.get("wall_textures") or []
    colours, unread = _texture_values(textures, "wall", mean_colour, resolver)
    if images or colours:
        world, report = again(images, colours)
    report["warnings"].extend(problems + unread)
    return world, cast(ImportReport, report)


def import_wbt(
    path: str | os.PathLike[str], controller: str | None = None, robot_line: int | None = None
) -> tuple[World, ImportReport]:
    """Imports a Webots world file.

    PROTO instances are first expanded by mazesim's PROTO engine (:mod:`mazesim.webots.proto`):
    the world's ``EXTERNPROTO`` files (relative paths, ``webots://`` and https URLs, through a
    download cache), the project's ``protos/`` folder and ``$WEBOTS_HOME``; stock objects that
    cannot be read get a stand-in, named in the warnings.

    Args:
        path: A ``.wbt`` file of any Webots version from V8.5 to R2025a (any line ends).
        controller: The name of the controller that will run (its file name without
            ``.py``): of several e-pucks, the first whose ``controller`` field names it is the
            robot, as Webots runs each robot's own controller; by default, the first e-puck.
        robot_line: The line of the robot that runs (an e-puck or not; the ``line`` of an
            entry of the report's ``robots``), instead of ``controller``'s.

    Returns:
        The mazesim world (named after the file) and the import report. Floor textures are
        read from beside the file (the url, then ``textures/`` and the url's file name).

    Raises:
        WorldFormatError: The file is not a readable Webots world, or one of its PROTOs is
            malformed; ``line`` and ``column`` say where.
        MazesimIOError: The file cannot be read; a ``ProtoUnavailableError`` when an
            ``EXTERNPROTO`` URL can be neither downloaded nor found in the cache.
    """
    file = os.fspath(path)
    text = _world_text(file)
    if text is None:  # not UTF-8 or not readable: the core says why, with the place
        world, report = _with_floor(
            _core.import_wbt(file, controller=controller, robot_line=robot_line),
            lambda images, colours: _core.import_wbt(
                file,
                floor_images=images,
                controller=controller,
                robot_line=robot_line,
                wall_colours=colours,
            ),
        )
        report["recognition"] = {"cameras": [], "objects": []}
        return world, report
    return import_wbt_text(text, file, controller=controller, robot_line=robot_line)


def _world_text(file: str) -> str | None:
    """The text of a world file, or None when the core should read it (and report why not)."""
    try:
        data = read_input(file, MAX_WORLD_BYTES, "the Webots world")
        if len(data) > MAX_WORLD_BYTES:
            return None
        return data.decode("utf-8")
    except MazesimIOError as unreadable:
        if unreadable.errno == errno.ENOENT:  # no such file: say where it was looked for
            raise
        return None
    except UnicodeDecodeError:
        return None


def _say_how_to_read(warnings: list[str], unreadable: Mapping[str, str]) -> None:
    """Before the first of the core's warnings that an instance of a type of Webots' own that
    could not be read (and has no stand-in) is not imported, one that says so and where to put
    its file: the core's alone ("an unknown PROTO", "not a device mazesim lists") read as if no
    file declared the type. A type the core knows itself (the Pi-puck board) has no such
    warning, and gets none."""
    for name, why in unreadable.items():
        about = re.compile(rf'(^|: ){re.escape(name)}( "[^"]*")?: ')
        lost = [
            i
            for i, warning in enumerate(warnings)
            if "not imported" in warning and about.search(warning)
        ]
        if lost:
            warnings.insert(
                lost[0],
                f"{name}: Webots' {name} PROTO cannot be read and mazesim has no stand-in for "
                f"it, so its {len(lost)} instance(s) below are not imported: {why}",
            )


def import_wbt_text(
    text: str,
    source: str = "<string>",
    controller: str | None = None,
    robot_line: int | None = None,
    *,
    imported_from: int | None = None,
) -> tuple[World, ImportReport]:
    """Imports the text of a Webots world file (its PROTOs expanded as in :func:`import_wbt`).

    Args:
        text: The file's text.
        source: A name for error messages (and for the world, from its file stem); floor
            textures, relative ``EXTERNPROTO`` paths and the project's ``protos/`` folder are
            looked for beside it.
        controller: As for :func:`import_wbt`.
        robot_line: As for :func:`import_wbt`.
        imported_from: For the running world's text after a supervisor imported nodes into
            it (:mod:`mazesim.webots.scene_edits`), the first line of those nodes: a robot
            there that is not an e-puck is warned of as an obstacle whose controller does not
            start, which is what a run makes of it.

    Returns:
        The mazesim world and the import report.

    Raises:
        WorldFormatError: The text is not a readable Webots world.
    """
    from mazesim.webots.expansions import remember
    from mazesim.webots.proto import expand_world, world_resolver

    expanded, protos = expand_world(text, source)
    remember(text, expanded, protos.interfaces)

    def imported(images: Any = None, colours: Any = None) -> tuple[World, dict[str, Any]]:
        return _core.import_wbt_text(
            expanded,
            source,
            floor_images=images,
            controller=controller,
            robot_line=robot_line,
            imported_from=imported_from,
            wall_colours=colours,
        )

    world, report = _with_floor(imported(), imported, world_resolver(text, source))
    report["warnings"][:0] = protos.warnings
    _say_how_to_read(report["warnings"], protos.unreadable)
    report["protos"] = {
        "expanded": protos.expanded,
        "stand_ins": protos.stand_ins,
        "cache_hits": protos.cache_hits,
        "downloads": protos.downloads,
    }
    report["recognition"] = read_recognition(expanded)
    return world, report


def own_build(report: Mapping[str, Any]) -> bool:
    """Whether the run's robot is a two-wheeled robot of its own build: the import simulates it
    (its ``robots`` entry has a profile) though its model is no e-puck's (a plain ``Robot``
    whose two motors turn its wheels: :mod:`mazesim.webots.own_drive`)."""
    model = report.get("robot_model")
    line = report.get("robot_line")
    own = next((r for r in report.get("robots") or [] if r.get("line") == line), None)
    return bool(model) and model not in E_PUCK_MODELS and bool(own and own.get("profile"))


def robot_warnings(report: Mapping[str, Any]) -> list[str]:
    """Warnings about the world's robot that the report does not already give.

    Args:
        report: An import report; its ``robot_model`` (when present) names the robot's type.

    Returns:
        A warning when the robot is not an e-puck (it then runs as the report's
        ``robot_profile``, by default the e-puck), unless a report warning already names it.
    """
    model = report.get("robot_model")
    if not model or model in E_PUCK_MODELS or own_build(report):
        return []
    if any(str(model) in str(warning) for warning in report.get("warnings", [])):
        return []
    profile = report.get("robot_profile") or "e-puck"
    return [f"the world's robot is a {model}, not an e-puck: mazesim runs it as the {profile}"]


def world_run_warnings(report: Mapping[str, Any]) -> list[str]:
    """The import's warnings that a run of the whole world shares: all of them but those that
    concern a run of one controller only (``one_controller_warnings``)."""
    alone = set(report.get("one_controller_warnings") or [])
    return [warning for warning in report.get("warnings") or [] if warning not in alone]


def import_summary(
    spec: str, report: Mapping[str, Any], warnings: list[str], robots: int = 1
) -> dict[str, Any]:
    """The one summary of a world's import that a run starts with (and keeps in summary.json):
    the robot recognised (or, for a run of ``robots`` > 1, how many run), the visual-only objects
    kept for the infra-red sensors and the camera (``sensed_only``, a count), the PROTOs expanded
    and stood in for, and how many things were not imported as Webots simulates them (each is
    one warning line)."""
    protos = report.get("protos") or {}
    expanded = sorted(protos.get("expanded") or {})
    stand_ins = protos.get("stand_ins") or {}
    model = report.get("robot_model")
    if robots > 1:
        robot = f"{robots} robots, each run by its own controller"
    elif model and own_build(report):
        robot = f"robot: {model}, a two-wheeled robot of its own build, rolled on its own wheels"
    elif model:
        robot = f"robot: {model}, simulated as the {report.get('robot_profile') or 'e-puck'}"
    else:
        robot = "no robot: the e-puck starts at (0, 0)"
    parts = [f"{os.path.basename(spec)}: {robot}"]
    sensed = len(report.get("sensed_only") or [])
    if sensed:
        parts.append(
            f"{sensed} visual-only object(s) seen by the infra-red sensors, the camera and a "
            "lidar, met by nothing else"
        )
    if expanded:
        parts.append(f"PROTOs expanded: {', '.join(expanded)}")
    if stand_ins:
        parts.append(f"stood in for by mazesim's stand-ins: {', '.join(sorted(stand_ins))}")
    parts.append(
        f"{len(warnings)} thing(s) not imported as in Webots, listed below"
        if warnings
        else "everything imported"
    )
    return {
        "sentence": "; ".join(parts),
        "robot_model": model,
        "sensed_only": sensed,
        "protos_expanded": expanded,
        "stand_ins": stand_ins,
        "not_imported": list(warnings),
    }
