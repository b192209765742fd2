"""What a controller sees of a Webots world file beyond the import report.

The import report gives walls, the robot's pose and its extension devices; the controller module
also wants the DEF names (for ``Supervisor.getFromDef``), whether the robot is a supervisor,
the E-puck's camera fields and the world's north. They are read from the file's text here.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Any

from mazesim.webots.frames import nue_to_enu, rotation_matrix
from mazesim.webots.lights import Light, read_lights

__all__ = ["DEFAULT_LOOKUP_TABLE", "GROUPING_TYPES", "Row", "Scene", "SceneNode", "read_scene"]

#: A row of a ``lookupTable``: distance (m), value and relative noise.
Row = tuple[float, float, float]

_DEF = re.compile(r"\bDEF\s+([^\s{}\[\]]+)\s+([A-Za-z_][\w-]*)\s*\{")
_NAME = re.compile(r'\bname\s+"((?:[^"\\]|\\.)*)"')
_CUSTOM_DATA = re.compile(r'\bcustomData\s+"((?:[^"\\]|\\.)*)"')
_CONTROLLER_ARGS = re.compile(r'\bcontrollerArgs\s*(?:\[([^\]]*)\]|"((?:[^"\\]|\\.)*)")')
_STRING = re.compile(r'"((?:[^"\\]|\\.)*)"')
#: A string (kept: it may hold a ``#``) or a comment (removed).
_COMMENT_OR_STRING = re.compile(r'"(?:[^"\\\n]|\\.)*"|#[^\n]*')
_SUPERVISOR = re.compile(r"\bsupervisor\s+TRUE\b")
_NUMBER = r"([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)"
_CAMERA_WIDTH = re.compile(r"\bcamera_width\s+" + _NUMBER)
_CAMERA_HEIGHT = re.compile(r"\bcamera_height\s+" + _NUMBER)
_CAMERA_FOV = re.compile(r"\bcamera_fieldOfView\s+" + _NUMBER)
_CAMERA_ROTATION = re.compile(r"\bcamera_rotation" + r"\s+".join([""] + [_NUMBER] * 4))
_HEADER = re.compile(r"#VRML_SIM\s+(?:R(\d{4})([a-z])?|V?(\d+)\.)")
_NUE = re.compile(r'\bcoordinateSystem\s+"NUE"')
_NODE = re.compile(r"(?:\bDEF\s+([^\s{}\[\]]+)\s+)?(?<![\w-])([A-Za-z_][\w-]*)\s*\{")
_ROTATION = re.compile(r"\brotation" + r"\s+".join([""] + [_NUMBER] * 4))
_TRANSLATION = re.compile(r"\btranslation\s+" + _NUMBER + r"\s+" + _NUMBER + r"\s+" + _NUMBER)
#: Webots' ground sensors module of the E-puck (its gs0..gs2), in its groundSensorsSlot.
_GROUND_SENSORS_MODULE = re.compile(
    r"(?<![\w-])(?:E-puckGroundSensors|EPuck_GroundSensorsModule)\s*\{"
)
#: A wheel joint's position saved in a world file: ``hidden position_0_<joint> <rad>``.
_KINEMATIC = re.compile(r"\bkinematic\s+TRUE\b")
_VERSION_2 = re.compile(r'\bversion\s+"2"')
_HIDDEN_WHEEL = re.compile(r"\bhidden\s+position_0_([01])\s+" + _NUMBER)
_NORTH = re.compile(r"\bnorthDirection\s+" + _NUMBER + r"\s+" + _NUMBER + r"\s+" + _NUMBER)
#: Node types that are robots (``DifferentialWheels``: Webots 6-7's wheeled robot).
ROBOT_TYPES = {"E-puck", "Robot", "DifferentialWheels", "e-puck2", "Epuck", "EPuck", "E-puck2"}
#: The E-puck PROTOs, whose hidden joint positions are their wheels'.
#: The upward tilt of the E-puck PROTO's proximity sensor rays, radians: its
#: ``E-puckDistanceSensor`` holds its DistanceSensor at ``rotation 0 0 1 0.16``, about the axis
#: the mounts lay horizontal (Webots 8.6 to R2025a), so each ray rises 9.17 degrees.
EPUCK_IR_ELEVATION = 0.16
EPUCK_TYPES = {"E-puck", "E-puck2", "e-puck2", "Epuck", "EPuck"}
#: The base node of the common PROTOs (``Node.getBaseTypeName``); a built-in node is its own.
BASE_TYPES = {
    "E-puck": "Robot",
    "E-puck2": "Robot",
    "e-puck2": "Robot",
    "Epuck": "Robot",
    "EPuck": "Robot",
    "RectangleArena": "Solid",
    "CircleArena": "Solid",
    "Floor": "Solid",
    "Wall": "Solid",
    "WoodenBox": "Solid",
    "CardboardBox": "Solid",
    "SolidBox": "Solid",
    "LegoTallWall": "Solid",
    "LegoTallInterval": "Solid",
    "TexturedBackground": "Background",
    "TexturedBackgroundLight": "DirectionalLight",
}


#: The built-in nodes whose ``children`` field the scene keeps (they place their children).
GROUPING_TYPES = {"Solid", "Transform", "Pose", "Group"}


@dataclass(frozen=True)
class SceneNode:
    """A node at the top of the world file (a child of the scene tree's root), or a node of a
    grouping node's ``children`` field.

    Attributes:
        type_name: Its node type (``"WorldInfo"``, ``"RectangleArena"``, ``"E-puck"``...).
        def_name: Its DEF name, or "".
        translation: Its ``translation`` field in the world frame (ENU), if it has one.
        rotation: Its ``rotation`` field (axis x, y, z and angle, world frame), if it has one.
        name: Its ``name`` field, if it has one.
        robot: Whether it is the robot of the run.
        numbers: Its other fields of numbers (a PROTO instance's own fields too), as written.
        flags: Its fields of ``TRUE`` / ``FALSE``.
        strings: Its fields of one string.
        children: The nodes of its ``children`` field, for a grouping node
            (:data:`GROUPING_TYPES`); their ``translation`` and ``rotation`` are in its frame.
    """

    type_name: str
    def_name: str = ""
    translation: tuple[float, float, float] | None = None
    rotation: tuple[float, float, float, float] | None = None
    name: str | None = None
    robot: bool = False
    numbers: dict[str, tuple[float, ...]] = field(default_factory=dict)
    flags: dict[str, bool] = field(default_factory=dict)
    strings: dict[str, str] = field(default_factory=dict)
    children: list[SceneNode] = field(default_factory=list)

    @property
    def base_type(self) -> str:
        """The built-in node the type is, or derives from (``"Solid"`` for a ``Wall``)."""
        return BASE_TYPES.get(self.type_name, self.type_name)


@dataclass
class Scene:
    """DEF names, supervisor flag, camera fields and north of a world file.

    Attributes:
        defs: DEF name -> node type, in file order.
        robot_def: The robot node's DEF name, or None.
        supervisor: Whether the file says ``supervisor TRUE``.
        robot_name: The robot's ``name`` field (Webots' default for the E-puck, ``"e-puck"``).
        robot_custom_data: The robot's ``customData`` field.
        controller_args: The robot's ``controllerArgs`` (a list of strings since R2021a, one
            string split at spaces before), given to the controller as ``sys.argv[1:]``.
        camera_width: The E-puck's ``camera_width`` field, if set.
        camera_height: The E-puck's ``camera_height`` field, if set.
        camera_fov: The E-puck's ``camera_fieldOfView`` field, if set.
        camera_pitch: How far down (rad) the E-puck's ``camera_rotation`` tilts the camera
            (its part about the camera's y axis).
        north: ``WorldInfo.northDirection`` as x, y (world frame), if set.
        lights: The world's lights that are on (empty: the light sensors' default ambient).
        nodes: The nodes at the top of the file, in file order (the root's ``children``), each
            grouping node with its own ``children``.
        nue: Whether the file uses Webots' old NUE frame (y up): before R2022a, or
            ``coordinateSystem "NUE"``; a GPS then reads in that frame.
        ground_sensors_module: Whether the world's E-puck carries Webots' ground sensors
            module (``E-puckGroundSensors`` in its ``groundSensorsSlot``), without which
            Webots' e-puck has no ``gs0``..``gs2``; None for a robot that is no E-puck node.
        wheel_positions: The left and right wheel joints' positions (rad) a world saved after
            a run holds (the E-puck's ``hidden position_0_0`` and ``position_0_1``): where
            Webots restores them, so where its wheel sensors start; 0 otherwise.
        traction_version: The E-puck PROTO's ``version`` ("1" or "2") when the robot is one
            with physics (not ``kinematic TRUE``) on HingeJoint wheels (a file of R2018a or
            later; before, a DifferentialWheels robot): its body then starts and stops as its
            wheels' friction allows (:mod:`mazesim.webots.traction`); None otherwise.
        infrared_elevation: How far the robot's proximity sensor rays rise above the floor's
            plane, radians: :data:`EPUCK_IR_ELEVATION` for an ``E-puck`` PROTO node (its
            ``E-puckDistanceSensor`` turns each DistanceSensor 0.16 rad about the mount's z
            axis, since Webots 8 at least), 0 otherwise (level rays).
        y_up_devices: Whether the robot's PROTOs are Webots' Y-up ones (a file before
            R2022a): an accelerometer, gyro or compass then reads in the device frame x
            right, y up, z back.
        sensor_tables: The ``lookupTable`` of each ``DistanceSensor`` node the robot's node
            lists itself (a plain ``Robot`` or ``DifferentialWheels`` e-puck saved expanded, not
            an E-puck PROTO node), by its ``name``: rows of distance (m), value and relative
            noise, as written. Webots reads each such sensor through its own table; a sensor
            without a ``lookupTable`` field reads through the field's default,
            :data:`DEFAULT_LOOKUP_TABLE`; one whose table is not rows of 3 numbers is left out
            (see ``malformed_tables``).
        malformed_tables: The ``lookupTable`` fields of those ``DistanceSensor`` nodes that are
            not rows of 3 numbers, by sensor name: what was found, as written.
        sensor_poses: The pose of each of those ``DistanceSensor`` nodes that is a child of the
            robot node or of the ``Solid``, ``Transform``, ``Pose`` and ``Group`` nodes under it
            (whose poses it composes; an E-puck saved expanded holds each in a Solid; one in a
            joint's end point or another robot is left out), by sensor name:
            x, y (m), the heading of its ray (rad, counter-clockwise from forward) and how far
            the ray rises above the floor's plane (rad, negative down) in the robot's frame (x
            forward, y left, z up; an NUE file's converted as the importer converts it), from
            its ``translation`` and ``rotation`` (Webots' defaults where absent).
        sensor_heights: The height above the robot's origin (m) of each sensor of
            ``sensor_poses``, by sensor name.
        sensor_types: The ``type`` of each ``DistanceSensor`` node the robot's node lists itself
            (those of ``sensor_tables``), by its ``name``: ``"generic"`` (Webots' default where
            the node has no such field), ``"infra-red"``, ``"sonar"`` or ``"laser"``, as
            written.
    """

    defs: dict[str, str] = field(default_factory=dict)
    robot_def: str | None = None
    supervisor: bool = False
    robot_name: str = "e-puck"
    robot_custom_data: str = ""
    controller_args: list[str] = field(default_factory=list)
    camera_width: int | None = None
    camera_height: int | None = None
    camera_fov: float | None = None
    camera_pitch: float = 0.0
    north: tuple[float, float] | None = None
    nue: bool = False
    y_up_devices: bool = False
    wheel_positions: tuple[float, float] = (0.0, 0.0)
    traction_version: str | None = None
    infrared_elevation: float = 0.0
    ground_sensors_module: bool | None = None
    lights: list[Light] = field(default_factory=list)
    nodes: list[SceneNode] = field(default_factory=list)
    sensor_tables: dict[str, list[Row]] = field(default_factory=dict)
    malformed_tables: dict[str, str] = field(default_factory=dict)
    sensor_poses: dict[str, tuple[float, float, float, float]] = field(default_factory=dict)
    sensor_heights: dict[str, float] = field(default_factory=dict)
    sensor_types: dict[str, str] = field(default_factory=dict)


def _hinge_wheels(year: str | None) -> bool:
    """Whether an E-puck of a file of this release year turns its wheels on HingeJoints, moved
    by their friction: since R2018a (before, the PROTO was a DifferentialWheels robot)."""
    return year is not None and int(year) >= 2018


def read_scene(text: str, robot_model: str | None = None, robot_line: int | None = None) -> Scene:
    """Reads the scene facts of a world file's text (comments skipped).

    The robot's own facts (DEF and ``name``, ``customData``, ``supervisor``,
    ``controllerArgs``, camera fields) are read from its node alone, so that another robot of
    the world (a referee or supervisor ``Robot``) lends it none of its own.

    Args:
        text: The ``.wbt`` text.
        robot_model: The robot's node type from the import report, if any.
        robot_line: The line of the robot's node from the import report (``robot_line``), if
            any; without it the first robot node of the file is the robot.
    """
    text = text.lstrip("\ufeff")
    header = _HEADER.match(text.lstrip())
    scene = Scene()
    year = None
    if header is not None:
        year = header.group(1)
        scene.nue = int(year) < 2022 if year else header.group(3) is not None
        scene.y_up_devices = scene.nue
    text = _COMMENT_OR_STRING.sub(_without_comment, text)
    scene.nue = scene.nue or bool(_NUE.search(text))
    robot_types = ROBOT_TYPES | ({robot_model} if robot_model else set())
    robot = _robot_node(text, robot_types, robot_line)
    for match in _DEF.finditer(text):
        scene.defs.setdefault(match.group(1), match.group(2))
    scene.nodes = _top_nodes(text, robot, scene.nue)
    # Without a robot node, the whole file stands for it.
    own, body = text, text
    if robot is not None:
        scene.robot_def = robot.group(1)
        own, body = _own_text(text, robot.end()), _body_text(text, robot.end())
        if found := _NAME.search(own):
            scene.robot_name = found.group(1)
        if found := _CUSTOM_DATA.search(own):
            scene.robot_custom_data = found.group(1)
        saved = {int(j): float(v) for j, v in _HIDDEN_WHEEL.findall(own)}
        if robot.group(2) in EPUCK_TYPES:
            # The E-puck PROTO's first HingeJoint is its left wheel's, the second its right's.
            scene.wheel_positions = (saved.get(0, 0.0), saved.get(1, 0.0))
            scene.ground_sensors_module = bool(_GROUND_SENSORS_MODULE.search(body))
        if robot.group(2) not in EPUCK_TYPES:
            scene.sensor_tables, scene.malformed_tables = _sensor_tables(body)
            placed = _sensor_poses(body, scene.nue)
            scene.sensor_poses = {name: pose[:4] for name, pose in placed.items()}
            scene.sensor_heights = {name: pose[4] for name, pose in placed.items()}
            scene.sensor_types = _sensor_types(body)
        if robot.group(2) == "E-puck":
            scene.infrared_elevation = EPUCK_IR_ELEVATION
        if robot.group(2) == "E-puck" and _hinge_wheels(year) and not _KINEMATIC.search(own):
            scene.traction_version = "2" if _VERSION_2.search(own) else "1"
    scene.supervisor = bool(_SUPERVISOR.search(own))
    scene.lights = read_lights(text, scene.nue)
    if found := _CONTROLLER_ARGS.search(body):
        listed, single = found.groups()
        scene.controller_args = (
            _STRING.findall(listed) if listed is not None else (single or "").split()
        )
    if found := _CAMERA_WIDTH.search(own):
        scene.camera_width = max(1, int(float(found.group(1))))
    if found := _CAMERA_HEIGHT.search(own):
        scene.camera_height = max(1, int(float(found.group(1))))
    if found := _CAMERA_FOV.search(own):
        scene.camera_fov = float(found.group(1))
    if found := _CAMERA_ROTATION.search(own):
        ax, ay, az, angle = (float(v) for v in found.groups())
        norm = math.sqrt(ax * ax + ay * ay + az * az) or 1.0
        scene.camera_pitch = angle * ay / norm
    if found := _NORTH.search(text):
        x, y, z = (float(v) for v in found.groups())
        scene.north = nue_to_enu(x, y, z)[:2] if scene.nue else (x, y)
    elif scene.y_up_devices:
        # WorldInfo.northDirection's default before R2022a: x (1 0 0).
        scene.north = nue_to_enu(1.0, 0.0, 0.0)[:2]
    return scene


def _without_comment(match: re.Match[str]) -> str:
    """A string of the file as it is, a comment (``#`` to the end of its line) removed."""
    found = match.group(0)
    return "" if found.startswith("#") else found


_DISTANCE_SENSOR = re.compile(r"(?<![\w-])DistanceSensor\s*\{")
_LOOKUP_TABLE = re.compile(r"\blookupTable\s*\[([^\]]*)\]")
#: The ``lookupTable`` of a ``DistanceSensor`` node without the field (Webots' reference
#: manual, DistanceSensor: ``lookupTable [ 0 0 0, 0.1 1000 0 ]``): 0 touching, rising to 1000
#: at 0.1 m and beyond.
DEFAULT_LOOKUP_TABLE = [(0.0, 0.0, 0.0), (0.1, 1000.0, 0.0)]


def _sensor_tables(body: str) -> tuple[dict[str, list[Row]], dict[str, str]]:
    """The ``lookupTable`` of each named ``DistanceSensor`` node in a robot's body text (the
    default one where the node has no such field), and the fields that are not rows of 3
    numbers, as found."""
    tables: dict[str, list[Row]] = {}
    malformed: dict[str, str] = {}
    for node in _DISTANCE_SENSOR.finditer(body):
        found = _NAME.search(_own_text(body, node.end()))
        if found is None or found.group(1) in tables or found.group(1) in malformed:
            continue
        field_text = _own_lookup_table(_body_text(body, node.end()))
        if field_text is None:
            tables[found.group(1)] = list(DEFAULT_LOOKUP_TABLE)
        elif (table := _rows_of_three(field_text)) is not None:
            tables[found.group(1)] = table
        else:
            malformed[found.group(1)] = " ".join(field_text.split())
    return tables, malformed


_TYPE = re.compile(r'\btype\s+"((?:[^"\\]|\\.)*)"')
#: A ``DistanceSensor`` node's ``type`` without the field (Webots' reference manual).
DEFAULT_SENSOR_TYPE = "generic"


def _sensor_types(body: str) -> dict[str, str]:
    """The ``type`` of each named ``DistanceSensor`` node in a robot's body text (Webots'
    default, :data:`DEFAULT_SENSOR_TYPE`, where the node has no such field)."""
    types: dict[str, str] = {}
    for node in _DISTANCE_SENSOR.finditer(body):
        own = _own_text(body, node.end())
        found = _NAME.search(own)
        if found is None or found.group(1) in types:
            continue
        given = _TYPE.search(own)
        types[found.group(1)] = given.group(1) if given else DEFAULT_SENSOR_TYPE
    return types


#: An opening or closing brace or bracket, or a node's type and its opening brace.
_NESTING = re.compile(_NODE.pattern + r"|([{}\[\]])")


def _sensor_poses(body: str, nue: bool) -> dict[str, tuple[float, float, float, float, float]]:
    """The pose in the robot's frame (x, y, heading, rise, height) of each named
    ``DistanceSensor`` node of a robot's body text ``body`` that is a child of the robot node or
    of the grouping nodes (:data:`GROUPING_TYPES`: an E-puck saved expanded holds each in a
    Solid) under it, composed through their ``translation`` and ``rotation``."""
    poses: dict[str, tuple[float, float, float, float, float]] = {}
    # The open nodes (type, body start) and lists (None) from the robot's body inwards.
    open_nodes: list[tuple[str, int] | None] = []
    for match in _NESTING.finditer(body):
        bracket = match.group(3)
        if bracket in ("}", "]"):
            if open_nodes:
                open_nodes.pop()
            continue
        if bracket is not None:
            open_nodes.append(None)
            continue
        chain = [entry for entry in open_nodes if entry is not None]
        open_nodes.append((match.group(2), match.end()))
        if match.group(2) != "DistanceSensor" or any(t not in GROUPING_TYPES for t, _ in chain):
            continue
        own = _own_text(body, match.end())
        found = _NAME.search(own)
        if found is None or found.group(1) in poses:
            continue
        origin, axes = (0.0, 0.0, 0.0), _IDENTITY
        for _, start in [*chain, (match.group(2), match.end())]:
            origin, axes = _placed(origin, axes, _own_text(body, start))
        x, y, z = origin
        ray = (axes[0][0], axes[1][0], axes[2][0])
        if nue:
            (x, y, z), ray = nue_to_enu(x, y, z), nue_to_enu(*ray)
        rise = math.asin(max(-1.0, min(1.0, ray[2])))
        poses[found.group(1)] = (x, y, math.atan2(ray[1], ray[0]), rise, z)
    return poses


Matrix = tuple[tuple[float, float, float], ...]
_IDENTITY: Matrix = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))


def _placed(
    origin: tuple[float, float, float], axes: Matrix, own: str
) -> tuple[tuple[float, float, float], Matrix]:
    """The frame (origin, rotation matrix) of a node whose own fields are ``own`` inside the
    frame ``origin``, ``axes``: its ``translation`` and ``rotation`` (Webots' defaults, none,
    where absent)."""
    at = _TRANSLATION.search(own)
    offset = [float(v) for v in at.groups()] if at else [0.0, 0.0, 0.0]
    x, y, z = (origin[i] + sum(axes[i][k] * offset[k] for k in range(3)) for i in range(3))
    turned = _ROTATION.search(own)
    if turned is None:
        return (x, y, z), axes
    flat = rotation_matrix(*(float(v) for v in turned.groups()))
    rotation = (flat[0:3], flat[3:6], flat[6:9])
    rows = [[sum(a * rotation[k][j] for k, a in enumerate(row)) for j in range(3)] for row in axes]
    return (x, y, z), tuple((row[0], row[1], row[2]) for row in rows)


def _own_lookup_table(body: str) -> str | None:
    """The text between the brackets of a node's own ``lookupTable`` field (not a child's), or
    None without one."""
    for match in _LOOKUP_TABLE.finditer(body):
        if _nesting(body[: match.start()]) == 0:
            return match.group(1)
    return None


def _rows_of_three(field_text: str) -> list[Row] | None:
    """A ``lookupTable`` field's numbers as rows of 3, or None when they are not."""
    try:
        numbers = [float(v) for v in field_text.replace(",", " ").split()]
    except ValueError:
        return None
    if not numbers or len(numbers) % 3 != 0:
        return None
    return [(numbers[i], numbers[i + 1], numbers[i + 2]) for i in range(0, len(numbers), 3)]


def _robot_node(text: str, robot_types: set[str], line: int | None) -> re.Match[str] | None:
    """The robot's node (DEF name, type): the first robot node on ``line``, else the first node
    on ``line`` (a robot of a project's own PROTO, which the import report names by the robot it
    stands in for, ``E-puck`` for an ``epuck_custom``), or the first robot node of the file."""
    on_line = None
    for match in _NODE.finditer(text):
        here = line is not None and text.count("\n", 0, match.start(2)) + 1 == line
        if match.group(2) in robot_types and (line is None or here):
            return match
        if here and on_line is None:
            on_line = match
    return on_line


#: A node's opening, a ``children [`` field's, or another brace or bracket.
_TREE = re.compile(_NODE.pattern + r"|(?<![\w-])(children)\s*\[|([{}\[\]])")


def _top_nodes(text: str, robot: re.Match[str] | None, nue: bool) -> list[SceneNode]:
    """The nodes at the top of the file (comments removed), the robot's marked, each grouping
    node (:data:`GROUPING_TYPES`) with the nodes of its ``children`` field, in file order.

    One pass over the file: the text between two braces or brackets belongs to the innermost
    open one, so each kept node's own fields are gathered as the pass goes by them.
    """
    top: list[_NodeText] = []
    # From the file's top inwards: a kept node, a grouping node's ``children`` list (the
    # node), or another node, brace or bracket (None).
    open_entries: list[tuple[str, _NodeText | None]] = []
    scanned = 0
    for match in _TREE.finditer(text):
        if open_entries and open_entries[-1][0] == "node" and open_entries[-1][1] is not None:
            open_entries[-1][1].own.append(text[scanned : match.start()])
        scanned = match.end()
        bracket = match.group(4)
        if bracket in ("}", "]"):
            if open_entries:
                kind, closed = open_entries.pop()
                if kind == "node" and closed is not None:
                    closed.close(nue)
            continue
        if bracket is not None:
            open_entries.append(("other", None))
            continue
        kind, owner = open_entries[-1] if open_entries else ("top", None)
        if match.group(3) is not None:
            grouping = kind == "node" and owner is not None and owner.type_name in GROUPING_TYPES
            open_entries.append(("children", owner if grouping else None))
            continue
        kept: _NodeText | None = None
        if kind == "top" or (kind == "children" and owner is not None):
            is_robot = robot is not None and match.start() == robot.start()
            kept = _NodeText(match.group(1) or "", match.group(2), is_robot)
            (top if owner is None else owner.children).append(kept)
        open_entries.append(("node", kept))
    for kind, unclosed in reversed(open_entries):
        if kind == "node" and unclosed is not None:
            if scanned < len(text) and unclosed is open_entries[-1][1]:
                unclosed.own.append(text[scanned:])
            unclosed.close(nue)
    return [node.made for node in top if node.made is not None]


@dataclass
class _NodeText:
    """A node of the scene tree as the file is read: its own fields' text so far."""

    def_name: str
    type_name: str
    robot: bool
    own: list[str] = field(default_factory=list)
    children: list[_NodeText] = field(default_factory=list)
    made: SceneNode | None = None

    def close(self, nue: bool) -> None:
        """Makes the node's :class:`SceneNode` (its children's are made before)."""
        own = "".join(self.own)
        self.made = SceneNode(
            self.type_name,
            self.def_name,
            translation=_vector(_TRANSLATION.search(own), nue),
            rotation=_rotation(_ROTATION.search(own), nue),
            name=found.group(1) if (found := _NAME.search(own)) else None,
            robot=self.robot,
            children=[child.made for child in self.children if child.made is not None],
            **_own_fields(own),
        )


_OWN_NUMBERS = re.compile(r"(?<![\w-])([A-Za-z_]\w*)((?:\s+" + _NUMBER + r")+)(?![\w.])")
_OWN_FLAG = re.compile(r"(?<![\w-])([A-Za-z_]\w*)\s+(TRUE|FALSE)\b")
_OWN_STRING = re.compile(r'(?<![\w-])([A-Za-z_]\w*)\s+"((?:[^"\\]|\\.)*)"')
_HIDDEN = re.compile(r"\bhidden\s+\S+[^\n]*")
#: Fields read on their own (the frame) or not fields (``hidden`` engine state).
_NOT_OWN = {"translation", "rotation", "name", "hidden"}


def _own_fields(own: str) -> dict[str, dict[str, Any]]:
    """A node's own fields of numbers, flags and strings (for the supervisor's ``getField``)."""
    own = _HIDDEN.sub("", own)
    numbers = {
        m.group(1): tuple(float(v) for v in m.group(2).split())
        for m in _OWN_NUMBERS.finditer(own)
        if m.group(1) not in _NOT_OWN
    }
    flags = {
        m.group(1): m.group(2) == "TRUE"
        for m in _OWN_FLAG.finditer(own)
        if m.group(1) not in _NOT_OWN
    }
    strings = {
        m.group(1): m.group(2) for m in _OWN_STRING.finditer(own) if m.group(1) not in _NOT_OWN
    }
    return {"numbers": numbers, "flags": flags, "strings": strings}


def _vector(found: re.Match[str] | None, nue: bool) -> tuple[float, float, float] | None:
    """A found x y z in the world frame (ENU, converted from NUE)."""
    if found is None:
        return None
    x, y, z = (float(v) for v in found.groups())
    return nue_to_enu(x, y, z) if nue else (x, y, z)


def _rotation(found: re.Match[str] | None, nue: bool) -> tuple[float, float, float, float] | None:
    """A found axis-angle rotation in the world frame (its axis converted from NUE)."""
    if found is None:
        return None
    ax, ay, az, angle = (float(v) for v in found.groups())
    return (*nue_to_enu(ax, ay, az), angle) if nue else (ax, ay, az, angle)


def _nesting(text: str) -> int:
    """How much deeper (in braces and brackets) the end of ``text`` is than its start."""
    return text.count("{") + text.count("[") - text.count("}") - text.count("]")


def _body_text(text: str, body: int) -> str:
    """The text of the node whose body starts at ``body`` (after its ``{``), to its ``}``."""
    depth = 0
    for index in range(body, len(text)):
        if text[index] in "{[":
            depth += 1
        elif text[index] in "}]":
            depth -= 1
            if depth < 0:
                return text[body:index]
    return text[body:]


def _own_text(text: str, body: int) -> str:
    """The fields of the node whose body starts at ``body`` (after its ``{``), without its
    children's."""
    depth, own = 0, []
    for index in range(body, len(text)):
        char = text[index]
        if char in "{[":
            depth += 1
        elif char in "}]":
            depth -= 1
            if depth < 0:
                break
        elif depth == 0:
            own.append(char)
    return "".join(own)
