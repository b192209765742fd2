"""What a controller sees of a Webots world file beyond the import report.

The import report gives walls, the robot's pose and its extension devices; the controller module
also wants the DEF names (for ``Supervisor.getFromDef``), whether the robot is a supervisor,
the E-puck's camera fields and the world's north. They are read from the file's node tree, as
:mod:`mazesim.webots.proto.syntax` parses it for the PROTO engine too.
"""

from __future__ import annotations

import io
import math
import os
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from mazesim._paths import open_input
from mazesim.webots.devices import device_side
from mazesim.webots.differential_drive import WheelsNode, wheels_node
from mazesim.webots.expansions import expanded_of
from mazesim.webots.frames import (
    WORLD_FRAME,
    camera_heading,
    nue_to_enu,
    placed,
    rotation_matrix,
)
from mazesim.webots.lights import Light, LightSource, light_sources, lit
from mazesim.webots.own_drive import OwnDrive, own_drive, resting_height
from mazesim.webots.proto.syntax import (
    Field,
    Node,
    first_value,
    line_numbers,
    nodes_in_order,
    parse_nodes,
    unix_line_ends,
    world_version,
)

__all__ = [
    "DEFAULT_LOOKUP_TABLE",
    "CHILDREN_TYPES",
    "GROUPING_TYPES",
    "Row",
    "BASE_NAMES",
    "Scene",
    "SceneNode",
    "body_y_up",
    "read_scene",
    "read_scenes",
    "read_world_text",
]

#: A row of a ``lookupTable``: distance (m), value and relative noise.
Row = tuple[float, float, float]


#: The ``name`` a base node type's Solid has when its node writes none (reference manual).
BASE_NAMES = {"Solid": "solid", "Robot": "robot"}
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
#: The other built-in nodes derived from Solid, whose ``children`` field a supervisor walks too:
#: a plain robot (an e-puck saved expanded) and the devices among its children (an Emitter
#: holding the Shape that shows its range).
SOLID_DERIVED_TYPES = {
    "Robot", "DifferentialWheels", "Accelerometer", "Altimeter", "Camera", "Compass",
    "Connector", "Display", "DistanceSensor", "Emitter", "GPS", "Gyro", "InertialUnit", "LED",
    "Lidar", "LightSensor", "Pen", "Radar", "RangeFinder", "Receiver", "Speaker",
    "TouchSensor", "VacuumGripper",
}  # fmt: skip
#: The nodes whose ``children`` field the scene keeps for a supervisor.
CHILDREN_TYPES = GROUPING_TYPES | SOLID_DERIVED_TYPES


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
        children: The nodes of its ``children`` field, for a grouping node, a plain robot or a
            device (:data:`CHILDREN_TYPES`); their ``translation`` and ``rotation`` are in its
            frame.
        slots: The nodes of each of its slot fields (an E-puck's ``turretSlot``,
            ``groundSensorsSlot`` and ``bodySlot``, a project PROTO's ``extensionSlot1``:
            :func:`_is_slot_field`), by field name, for a node
            that is not the run's robot; their poses are in the slot's frame.
        nodes: The node of each of its fields that holds one node (a Shape's ``geometry`` and
            ``appearance``, an Appearance's ``material``, a Solid's ``boundingObject``).
        lists: The values of each of its bracketed fields of values (an ImageTexture's ``url``,
            a sensor's ``lookupTable``), in order, as written (:mod:`mazesim.webots.list_fields`
            gives them their kind).
        line: The line of its node type in the file (the import report's ``owners`` name the
            obstacles and bodies a node holds by it); 0 when unknown.
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
    nodes: dict[str, SceneNode] = field(default_factory=dict)
    line: int = 0
    slots: dict[str, list[SceneNode]] = field(default_factory=dict)
    lists: dict[str, tuple[float | bool | str, ...]] = field(default_factory=dict)

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
        supervisor_refused: Whether Webots refuses the supervisor functions to the robot's
            controller: its node is one Webots' own types make a plain robot (``Robot``, an
            E-puck PROTO, ``DifferentialWheels``) and leaves ``supervisor`` FALSE
            (:mod:`mazesim.webots.supervisor_refusal`); False without a robot node.
        synchronization: The robot's ``synchronization`` field (Webots' default TRUE).
        robot_name: The robot's ``name`` field, or its node type's default (the E-puck's
            ``"e-puck"``, a plain Robot's ``"robot"``).
        robot_type: The robot node's type (``E-puck``, ``Robot``...); None without one.
        robot_custom_data: The robot's ``customData`` field.
        robot_battery: The robot's ``battery`` field: its energy (J), the most it holds (J)
            and its recharge speed (W); empty without a battery (Webots' default).
        robot_cpu_consumption: The robot's ``cpuConsumption`` field (W; Webots' default 10).
        robot_controller: The robot's ``controller`` field as the file writes it, or None when
            the file leaves it out (or has no robot node).
        controller_args: The robot's ``controllerArgs`` (a list of strings since R2021a, one
            string split at spaces before), given to the controller as ``sys.argv[1:]``.
        camera_width: The E-puck's ``camera_width`` field, if set.
        camera_height: The E-puck's ``camera_height`` field, if set.
        camera_fov: The E-puck's ``camera_fieldOfView`` field, if set.
        camera_pitch: How far down (rad) the E-puck's ``camera_rotation`` tilts the camera
            (in the frame of the file's E-puck PROTO: see ``y_up_devices``).
        camera_yaw: How far left (rad) the E-puck's ``camera_rotation`` turns the camera.
        north: ``WorldInfo.northDirection`` as x, y (world frame), if set.
        lights: The world's lights that are on; None when it has no light node (the light
            sensors' default ambient), empty when every one is off (darkness).
        light_sources: The world's light nodes as the file gives them, which :func:`lit`
            makes the lights of again once a supervisor sets a light's field.
        nodes: The nodes at the top of the file, in file order (the root's ``children``), each
            grouping node with its own ``children``.
        nue: Whether the file uses Webots' old NUE frame (y up): before R2022a, or
            ``coordinateSystem "NUE"``; a GPS then reads in that frame.
        wheel_positions: The left and right wheel joints' positions (rad) a world saved after
            a run holds (the E-puck's ``hidden position_0_0`` and ``position_0_1``): where
            Webots restores them, so where its wheel sensors start; 0 otherwise.
        wheels_node: The fields of the robot's node when it is a ``DifferentialWheels`` node
            (Webots' defaults where it writes none); None for another node.
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
        body_y_up: Whether the robot's inside is modelled Y-up (forward its node's local -z,
            up its local y): every robot of a file before R2022a, and one built so and stood
            upright by its ``rotation`` in a later file, as the import decides robot by robot
            (its report's ``y_up``); the positions of the devices its node writes are turned
            to the robot's Z-up frame.
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
        sensor_ray_counts: The ``numberOfRays`` of each ``DistanceSensor`` node the robot's node
            lists itself, by its ``name``, where it is above 1; of an E-puck PROTO whose
            ``distance_sensor_numberOfRays`` is above 1, that count for each of ps0..ps7.
        drive: The wheels, axle and body of a plain ``Robot`` node that is a two-wheeled robot
            of its own build, its wheels not the E-puck's
            (:func:`~mazesim.webots.own_drive.own_drive`); None for another robot.
        drive_refused: Why such a robot's own two wheels do not drive it (the e-puck's then
            do), None otherwise.
        origin_height: How high a plain ``Robot`` node's origin rests above the floor on its
            two wheels (m; :func:`~mazesim.webots.own_drive.resting_height`): a downward
            sensor's height above the floor is its own above the origin plus this; 0 for an
            E-puck, whose origin is on the floor.
    """

    defs: dict[str, str] = field(default_factory=dict)
    robot_def: str | None = None
    supervisor: bool = False
    supervisor_refused: bool = False
    synchronization: bool = True
    robot_name: str = "e-puck"
    robot_type: str | None = None
    robot_custom_data: str = ""
    robot_battery: tuple[float, ...] = ()
    robot_cpu_consumption: float = 10.0
    robot_controller: str | None = None
    controller_args: list[str] = field(default_factory=list)
    camera_width: int | None = None
    camera_height: int | None = None
    camera_fov: float | None = None
    camera_pitch: float = 0.0
    camera_yaw: float = 0.0
    north: tuple[float, float] | None = None
    nue: bool = False
    y_up_devices: bool = False
    body_y_up: bool = False
    wheel_positions: tuple[float, float] = (0.0, 0.0)
    wheels_node: WheelsNode | None = None
    traction_version: str | None = None
    infrared_elevation: float = 0.0
    lights: list[Light] | None = None
    light_sources: list[LightSource] | None = None
    nodes: list[SceneNode] = field(default_factory=list)
    sensor_tables: dict[str, list[Row]] = field(default_factory=dict)
    malformed_tables: dict[str, str] = field(default_factory=dict)
    sensor_poses: dict[str, tuple[float, float, float, float]] = field(default_factory=dict)
    sensor_heights: dict[str, float] = field(default_factory=dict)
    sensor_types: dict[str, str] = field(default_factory=dict)
    sensor_ray_counts: dict[str, int] = field(default_factory=dict)
    drive: OwnDrive | None = None
    drive_refused: str | None = None
    origin_height: float = 0.0


def _hinge_wheels(year: str | None) -> bool:
    """Whether an E-puck of a file of this release year turns its wheels on HingeJoints, moved
    by their friction: since R2018a (before, the PROTO was a DifferentialWheels robot)."""
    return year is not None and int(year) >= 2018


def read_world_text(path: str | os.PathLike[str]) -> str:
    """The text of a world file the import has read and checked already, read again for what
    the import report does not hold: line ends made ``\\n`` as the import counts lines, bytes
    that are not UTF-8 replaced.

    Raises:
        MazesimIOError: The file cannot be read (it changed since the import).
    """
    with io.TextIOWrapper(
        open_input(path, "the Webots world"), encoding="utf-8", errors="replace"
    ) as handle:
        return unix_line_ends(handle.read())


def read_scene(
    text: str,
    robot_model: str | None = None,
    robot_line: int | None = None,
    y_up: bool | None = None,
) -> Scene:
    """Reads the scene facts of a world file's text.

    The robot's own facts (DEF and ``name``, ``customData``, ``supervisor``,
    ``controllerArgs``, camera fields) are read from its node alone, so that another robot of
    the world (a referee or supervisor ``Robot``) lends it none of its own.

    Args:
        text: The ``.wbt`` text.
        robot_model: The robot's node type from the import report, if any.
        robot_line: The line of the robot's node from the import report (``robot_line``), if
            any; without it the first robot node of the file is the robot.
        y_up: Whether the robot's body is modelled Y-up, as the import report's robot says
            (its ``y_up``: :func:`body_y_up`); None takes the file's convention (Y-up before
            R2022a).

    Raises:
        WorldFormatError: The text is not a world's nodes (the import says so first).
    """
    return read_scenes(text, [(robot_model, robot_line)], [y_up])[0]


def read_scenes(
    text: str,
    robots: Sequence[tuple[str | None, int | None]],
    y_up: Sequence[bool | None] = (),
) -> list[Scene]:
    """The scene facts of a world file's text for each of its robots (its node type and line,
    as :func:`read_scene` takes them, and whether its body is modelled Y-up, ``y_up`` in the
    same order, None or left out for the file's convention), the text parsed once.

    Raises:
        WorldFormatError: The text is not a world's nodes (the import says so first).
    """
    expansion = _Expansion(expanded_of(text))
    text = text.lstrip("\ufeff")
    tree = parse_nodes(text, "<world>", max_depth=None)
    every = list(nodes_in_order(tree))
    bodies = [*y_up, *[None] * (len(robots) - len(y_up))]
    return [
        _scene(text, tree, every, model, line, body, expansion)
        for (model, line), body in zip(robots, bodies)
    ]


class _Expansion:
    """The expansion of the world text an import made (:mod:`mazesim.webots.expansions`),
    parsed when first asked for a robot's body."""

    def __init__(self, text: str | None) -> None:
        self.text = None if text is None else text.lstrip("\ufeff")
        self._read: tuple[list[Node], Callable[[int], int]] | None = None

    def body(self, line: int | None) -> Node | None:
        """The base robot node (``Robot``, ``E-puck``...) a PROTO instance on ``line``
        expands to; None without an expansion, a line, or such a node there."""
        if self.text is None or line is None:
            return None
        if self._read is None:
            every = list(nodes_in_order(parse_nodes(self.text, "<world>", max_depth=None)))
            self._read = every, line_numbers(self.text)
        every, line_of = self._read
        found = _robot_node(line_of, every, ROBOT_TYPES, line)
        return found if found is not None and found.type_name in ROBOT_TYPES else None


def body_y_up(robots: Sequence[Mapping[str, Any]], line: int | None) -> bool | None:
    """Whether the body of the robot of the import report's ``robots`` whose node is on
    ``line`` is modelled Y-up (its ``y_up``), or None when no robot of the list is there."""
    for robot in robots:
        if line is not None and robot.get("line") == line and "y_up" in robot:
            return bool(robot["y_up"])
    return None


def _scene(
    text: str,
    tree: list[Node],
    every: list[Node],
    robot_model: str | None,
    robot_line: int | None,
    y_up: bool | None,
    expansion: _Expansion,
) -> Scene:
    """The scene facts of a parsed world (``tree``, ``every`` node in file order) for a robot
    (``y_up``: whether its body is modelled Y-up, None for the file's convention); a robot
    that is an instance of a project's PROTO is read from the base node its PROTO builds, in
    the import's ``expansion`` of the text."""
    scene = Scene()
    version, scene.nue = world_version(text)
    scene.y_up_devices = scene.nue
    scene.body_y_up = scene.y_up_devices if y_up is None else y_up
    year = version[1:5] if version is not None and version.startswith("R") else None
    scene.nue = scene.nue or first_value(every, "coordinateSystem", Field.string) == "NUE"
    robot_types = ROBOT_TYPES | ({robot_model} if robot_model else set())
    line_of = line_numbers(text)
    robot = _robot_node(line_of, every, robot_types, robot_line)
    for node in every:
        if node.def_name is not None and node.use_name is None:
            scene.defs.setdefault(node.def_name, node.type_name)
    scene.nodes = _scene_nodes(tree, robot, scene.nue, _definitions(every), line_of)
    # Without a robot node, the whole file stands for it.
    own: list[Node] = every
    if robot is not None:
        scene.robot_def = robot.def_name
        built = None if robot.type_name in ROBOT_TYPES else expansion.body(robot_line)
        if built is not None and expansion.text is not None:
            # A project's robot PROTO: its fields, sensors and their tables are its body's.
            robot, text = built, expansion.text
        own = [robot]
        inside = list(nodes_in_order(f for item in robot.fields for f in item.nodes))
        scene.robot_type = robot.type_name
        named = first_value(own, "name", Field.string)
        scene.robot_name = named or BASE_NAMES.get(robot.type_name) or scene.robot_name
        scene.robot_custom_data = first_value(own, "customData", Field.string) or ""
        scene.robot_battery = first_value(own, "battery", _numbers) or ()
        cpu = first_value(own, "cpuConsumption", lambda f: f.numbers(1))
        scene.robot_cpu_consumption = cpu[0] if cpu else scene.robot_cpu_consumption
        scene.robot_controller = first_value(own, "controller", Field.string)
        if robot.type_name == "DifferentialWheels":
            written = {name: first_value(own, name, _leading(1)) for name in _WHEELS_FIELDS}
            fields = {name: value[0] for name, value in written.items() if value is not None}
            scene.wheels_node = wheels_node(fields, version)
        if robot.type_name in EPUCK_TYPES:
            # The E-puck PROTO's first HingeJoint is its left wheel's, the second its right's.
            scene.wheel_positions = (_saved_wheel(robot, 0), _saved_wheel(robot, 1))
            rays = first_value(own, "distance_sensor_numberOfRays", _leading(1))
            if rays is not None and rays[0] > 1:
                scene.sensor_ray_counts = {f"ps{i}": _ray_count(rays[0]) for i in range(8)}
        else:
            scene.sensor_tables, scene.malformed_tables = _sensor_tables(text, inside)
            placed = _sensor_poses(robot, scene.body_y_up)
            scene.sensor_poses = {name: pose[:4] for name, pose in placed.items()}
            scene.sensor_heights = {name: pose[4] for name, pose in placed.items()}
            scene.sensor_types = _sensor_types(inside)
            scene.sensor_ray_counts = _sensor_ray_counts(inside)
            if robot.type_name == "Robot" and robot_model is not None:
                # A plain Robot the import simulates: its own two wheels, where they are not
                # the E-puck's (an e-puck saved expanded keeps the profile's numbers).
                found = own_drive(robot, scene.body_y_up)
                scene.drive = found if isinstance(found, OwnDrive) else None
                scene.drive_refused = found if isinstance(found, str) else None
                scene.origin_height = resting_height(robot, scene.body_y_up)
        if robot.type_name == "E-puck":
            scene.infrared_elevation = EPUCK_IR_ELEVATION
        kinematic = first_value(own, "kinematic", Field.flag)
        if robot.type_name == "E-puck" and _hinge_wheels(year) and not kinematic:
            second = first_value(own, "version", Field.string) == "2"
            scene.traction_version = "2" if second else "1"
    scene.supervisor = bool(first_value(own, "supervisor", Field.flag))
    scene.supervisor_refused = (
        robot is not None and robot.type_name in ROBOT_TYPES and not scene.supervisor
    )
    scene.synchronization = first_value(own, "synchronization", Field.flag) is not False
    robot_lines = {
        node.start: line_of(node.type_start) for node in every if node.type_name in robot_types
    }
    scene.light_sources = light_sources(
        tree,
        scene.nue,
        lambda node: robot_lines.get(node.start),
        lambda node: line_of(node.type_start),
    )
    scene.lights = lit(scene.light_sources, scene.nue)
    if (arguments := first_value(own, "controllerArgs", _itself)) is not None:
        strings = [t.text[1:-1] for t in arguments.tokens if t.kind == "string"]
        bracketed = bool(arguments.tokens) and arguments.tokens[0].kind == "["
        scene.controller_args = strings if bracketed else " ".join(strings[:1]).split()
    if (width := first_value(own, "camera_width", _leading(1))) is not None:
        scene.camera_width = device_side(width[0], 1, "the E-puck's camera_width")
    if (height := first_value(own, "camera_height", _leading(1))) is not None:
        scene.camera_height = device_side(height[0], 1, "the E-puck's camera_height")
    if (fov := first_value(own, "camera_fieldOfView", _leading(1))) is not None:
        scene.camera_fov = fov[0]
    if (turn := first_value(own, "camera_rotation", _leading(4))) is not None:
        scene.camera_yaw, scene.camera_pitch = _camera_turn(turn, scene.y_up_devices)
    if (north := first_value(every, "northDirection", _leading(3))) is not None:
        x, y, z = north
        scene.north = nue_to_enu(x, y, z)[:2] if scene.nue else (x, y)
    elif scene.nue:
        # WorldInfo.northDirection's default before R2022a, and north in a later file of the
        # NUE convention (coordinateSystem "NUE": x north, y up, z east): the file's x.
        scene.north = nue_to_enu(1.0, 0.0, 0.0)[:2]
    return scene


def _camera_turn(rotation: Sequence[float], y_up: bool) -> tuple[float, float]:
    """The heading and tilt down (rad) of the E-puck's camera turned by its ``camera_rotation``
    (axis x, y, z and angle): the Camera of Webots' Z-up E-puck PROTO (R2022a on) looks along
    its x axis, z up, so a turn about y tilts it; that of the Y-up PROTO before looks along its
    -z axis, y up, x to the right, so there a turn about x tilts it (``1 0 0 -0.3`` looks 0.3
    rad down) and one about y turns it left."""
    m = rotation_matrix(*rotation[:4])
    if y_up:
        # -z of the turned camera, read in the robot's frame: forward -z, left -x, up y.
        return camera_heading((m[8], m[2], -m[5]))
    return camera_heading((m[0], m[3], m[6]))


#: The fields of a ``DifferentialWheels`` node its controller's side reads.
_WHEELS_FIELDS = ("speedUnit", "maxSpeed", "encoderResolution", "encoderNoise")


def _leading(count: int) -> Callable[[Field], tuple[float, ...] | None]:
    """Reads a field's first ``count`` values when they are numbers."""
    return lambda item: item.numbers(count)


def _itself(item: Field) -> Field:
    """Reads a field as it is."""
    return item


def _numbers(item: Field) -> tuple[float, ...] | None:
    """The numbers of a multiple field (``battery [50, 100, 2]``), or None when it holds
    anything else or nothing."""
    values = [t.text for t in item.tokens if t.text not in ("[", "]")]
    if item.nodes or not values:
        return None
    try:
        numbers = tuple(float(v) for v in values)
    except ValueError:
        return None
    return numbers if all(math.isfinite(n) for n in numbers) else None


def _sensor_name(node: Node) -> str | None:
    """The ``name`` of a ``DistanceSensor`` node; None for another node or one without."""
    return first_value([node], "name", Field.string) if node.type_name == "DistanceSensor" else None


def _saved_wheel(robot: Node, joint: int) -> float:
    """A wheel joint's position saved in a world file (``hidden position_0_<joint> <rad>``,
    the last one written), 0 without one."""
    saved = [
        values[0]
        for item in robot.fields
        if item.name == f"position_0_{joint}" and (values := item.numbers()) is not None
    ]
    return saved[-1] if saved else 0.0


#: The ``lookupTable`` of a ``DistanceSensor`` node without the field (Webots' reference
#: manual, DistanceSensor: ``lookupTable [ 0 0 0, 0.1 1000 0 ]``): 0 touching, rising to 1000
#: at 0.1 m and beyond.
DEFAULT_LOOKUP_TABLE = [(0.0, 0.0, 0.0), (0.1, 1000.0, 0.0)]
_COMMENT = re.compile(r"#[^\n\r]*")


def _sensor_tables(text: str, inside: list[Node]) -> tuple[dict[str, list[Row]], dict[str, str]]:
    """The ``lookupTable`` of each named ``DistanceSensor`` node among the nodes ``inside`` a
    robot's (the default one where the node has no such field), and the fields that are not
    rows of 3 numbers, as found."""
    tables: dict[str, list[Row]] = {}
    malformed: dict[str, str] = {}
    for node in inside:
        name = _sensor_name(node)
        if name is None or name in tables or name in malformed:
            continue
        table = first_value([node], "lookupTable", _itself)
        if table is None:
            tables[name] = list(DEFAULT_LOOKUP_TABLE)
            continue
        written = _COMMENT.sub("", text[table.value_start : table.value_end]).strip()
        written = written[1:-1] if written.startswith("[") and written.endswith("]") else written
        if (rows := _rows_of_three(table)) is not None:
            tables[name] = rows
        else:
            malformed[name] = " ".join(written.split())
    return tables, malformed


#: A ``DistanceSensor`` node's ``type`` without the field (Webots' reference manual).
DEFAULT_SENSOR_TYPE = "generic"


def _sensor_types(inside: list[Node]) -> dict[str, str]:
    """The ``type`` of each named ``DistanceSensor`` node among a robot's nodes ``inside``
    (Webots' default, :data:`DEFAULT_SENSOR_TYPE`, where the node has no such field)."""
    types: dict[str, str] = {}
    for node in inside:
        name = _sensor_name(node)
        if name is not None and name not in types:
            given = first_value([node], "type", Field.string)
            types[name] = given if given is not None else DEFAULT_SENSOR_TYPE
    return types


def _sensor_ray_counts(inside: list[Node]) -> dict[str, int]:
    """The ``numberOfRays`` of each named ``DistanceSensor`` node among a robot's nodes
    ``inside`` whose count is above 1."""
    rays: dict[str, int] = {}
    for node in inside:
        name = _sensor_name(node)
        count = first_value([node], "numberOfRays", _leading(1))
        if name is not None and name not in rays and count is not None and count[0] > 1:
            rays[name] = _ray_count(count[0])
    return rays


def _ray_count(value: float) -> int:
    """A ``numberOfRays`` as a whole count (a huge one held at 2**31 - 1, an SFInt32's most)."""
    return int(min(value, 2**31 - 1))


def _rows_of_three(table: Field) -> list[Row] | None:
    """A ``lookupTable`` field's numbers as rows of 3, or None when they are not."""
    inside = Field(table.name, table.start, table.end, table.nodes)
    inside.tokens = [t for t in table.tokens if t.kind not in ("[", "]")]
    if not inside.tokens:
        return []  # ``lookupTable []``: no table (Webots' DistanceSensor then reads 0)
    numbers = inside.numbers()
    if numbers is None or len(numbers) % 3 != 0:
        return None
    return [(numbers[i], numbers[i + 1], numbers[i + 2]) for i in range(0, len(numbers), 3)]


def _sensor_poses(robot: Node, y_up: bool) -> dict[str, tuple[float, float, float, float, float]]:
    """The pose in the robot's frame (x, y, heading, rise, height) of each named
    ``DistanceSensor`` node that is a child of the robot node or of the grouping nodes
    (:data:`GROUPING_TYPES`: an E-puck saved expanded holds each in a Solid) under it, composed
    through their ``translation`` and ``rotation``; a body modelled Y-up (``y_up``) is turned
    to the robot's Z-up frame."""
    poses: dict[str, tuple[float, float, float, float, float]] = {}
    # The nodes still to visit, each with the frame of the node that holds it.
    pending = [(node, WORLD_FRAME) for item in robot.fields for node in item.nodes]
    pending.reverse()
    while pending:
        node, holder = pending.pop()
        if node.use_name is not None:
            continue
        offset = first_value([node], "translation", _leading(3)) or (0.0, 0.0, 0.0)
        origin, axes = frame = placed(holder, offset, first_value([node], "rotation", _leading(4)))
        if node.type_name in GROUPING_TYPES:
            inner = [(n, frame) for item in node.fields for n in item.nodes]
            pending.extend(reversed(inner))
        name = _sensor_name(node)
        if name is None or name in poses:
            continue
        x, y, z = origin
        ray = (axes[0], axes[3], axes[6])
        if y_up:
            (x, y, z), ray = nue_to_enu(x, y, z), nue_to_enu(*ray)
        rise = math.asin(max(-1.0, min(1.0, ray[2])))
        poses[name] = (x, y, math.atan2(ray[1], ray[0]), rise, z)
    return poses


def _robot_node(
    line_of: Callable[[int], int], every: list[Node], robot_types: set[str], line: int | None
) -> Node | None:
    """The robot's node: the first robot node on ``line``, else the first node on ``line`` (a
    robot of a project's own PROTO, which the import report names by the robot it stands in
    for, ``E-puck`` for an ``epuck_custom``), or the first robot node of the file."""
    on_line = None
    for node in every:
        if node.use_name is not None:
            continue
        here = line is not None and line_of(node.type_start) == line
        if node.type_name in robot_types and (line is None or here):
            return node
        if here and on_line is None:
            on_line = node
    return on_line


def _definitions(every: list[Node]) -> dict[int, Node]:
    """The node each ``USE`` (by ``id``) stands for: the node of the last ``DEF`` of its name
    complete before it (``every`` is in file order), as Webots and the core read it."""
    defined: dict[str, list[Node]] = {}
    for node in every:
        if node.def_name is not None and node.use_name is None:
            defined.setdefault(node.def_name, []).append(node)
    used: dict[int, Node] = {}
    for node in every:
        earlier = [d for d in defined.get(node.use_name or "", []) if d.end <= node.start]
        if node.use_name is not None and earlier:
            used[id(node)] = max(earlier, key=lambda d: d.end)
    return used


def _scene_nodes(
    tree: list[Node],
    robot: Node | None,
    nue: bool,
    used: dict[int, Node],
    line_of: Callable[[int], int],
) -> list[SceneNode]:
    """The nodes at the top of the file, the robot's marked, each grouping node, plain robot and
    device (:data:`CHILDREN_TYPES`) with the nodes of its ``children`` field, in file order, and
    each node but the robot's with the node of each of its single-node fields
    (:func:`_single_nodes`); a
    ``USE`` among them is the very :class:`SceneNode` of the node it stands for (``used``), as
    a Webots supervisor sees it.

    The tree is walked with a stack, not recursion (a world may nest thousands deep): each
    node's :class:`SceneNode` is made once its children's are.
    """
    made: dict[int, SceneNode] = {}

    def scene_nodes(nodes: list[Node]) -> list[SceneNode]:
        top: list[SceneNode] = []
        # (node, the list its SceneNode goes into, its children's SceneNodes and its
        # single-node fields' once visited)
        Visited = tuple[list[SceneNode], list[tuple[str, SceneNode]], list[tuple[str, SceneNode]]]
        pending: list[tuple[Node, list[SceneNode] | _Named, Visited | None]] = [
            (node, top, None) for node in reversed(nodes)
        ]
        while pending:
            node, into, visited = pending.pop()
            if node.use_name is not None:
                if (defined := used.get(id(node))) is not None:
                    if id(defined) not in made:  # a DEF the scene does not list: made here
                        scene_nodes([defined])
                    into.append(made[id(defined)])
                continue
            if visited is None:
                inner: list[SceneNode] = []
                held: list[tuple[str, SceneNode]] = []
                slotted: list[tuple[str, SceneNode]] = []
                pending.append((node, into, (inner, held, slotted)))
                if node is not robot:
                    for name, single in reversed(_single_nodes(node)):
                        pending.append((single, _Named(held, name), None))
                    for name, held_node in reversed(_slot_nodes(node)):
                        pending.append((held_node, _Named(slotted, name), None))
                if node.type_name in CHILDREN_TYPES:
                    listed = [
                        n for item in node.fields if item.name == "children" for n in item.nodes
                    ]
                    pending.extend((n, inner, None) for n in reversed(listed))
                continue
            children, singles, slotted_nodes = visited
            line = line_of(node.type_start)
            made[id(node)] = _scene_node(node, node is robot, children, nue, line)
            made[id(node)].nodes.update(singles)
            for name, slotted_node in slotted_nodes:
                made[id(node)].slots.setdefault(name, []).append(slotted_node)
            into.append(made[id(node)])
        return top

    return scene_nodes(tree)


class _Named:
    """Where the SceneNode of a single-node field goes: its owner's list, under the field's
    name (an ``append`` as a list of children takes one)."""

    def __init__(self, held: list[tuple[str, SceneNode]], name: str) -> None:
        self._held = held
        self._name = name

    def append(self, scene_node: SceneNode) -> None:
        self._held.append((self._name, scene_node))


def _single_nodes(node: Node) -> list[tuple[str, Node]]:
    """The fields of a node that hold one node, without brackets (``geometry Box { ... }``,
    ``boundingObject USE BOX``), with their node, in file order."""
    return [
        (item.name, item.nodes[0])
        for item in node.own_fields()
        if item.name != "children" and len(item.nodes) == 1 and not item.tokens
    ]


def _is_slot_field(name: str) -> bool:
    """Whether a robot node's field is an extension slot: its name ends in ``Slot``, or in
    ``Slot`` and a number, as a project's own PROTO numbers the slots it adds
    (``extensionSlot1``); the core's import reads the same fields."""
    return name.rstrip("0123456789").endswith("Slot")


def _slot_nodes(node: Node) -> list[tuple[str, Node]]:
    """The nodes of a node's slot fields (:func:`_is_slot_field`), with the field's name, in file
    order."""
    return [
        (item.name, held)
        for item in node.own_fields()
        if _is_slot_field(item.name)
        for held in item.nodes
    ]


#: Fields read on their own (the frame) or not fields (``hidden`` engine state).
_NOT_OWN = {"translation", "rotation", "name", "hidden"}


def _scene_node(
    node: Node, robot: bool, children: list[SceneNode], nue: bool, line: int
) -> SceneNode:
    """The :class:`SceneNode` of a node of the tree (on ``line``), its ``children`` made
    already."""
    numbers, flags, strings, lists = {}, {}, {}, {}
    for item in node.own_fields():
        if item.name in _NOT_OWN:
            continue
        if item.tokens and item.tokens[0].kind == "[" and not item.nodes:
            listed = [token.value() for token in item.tokens if token.kind in ("string", "word")]
            lists[item.name] = tuple(v for v in listed if v is not None)
        if (values := item.numbers()) is not None:
            numbers[item.name] = values
        if (flag := item.flag()) is not None:
            flags[item.name] = flag
        if (string := item.string()) is not None:
            strings[item.name] = string
    translation, rotation = None, None
    if (at := first_value([node], "translation", _leading(3))) is not None:
        translation = nue_to_enu(*at) if nue else (at[0], at[1], at[2])
    if (turn := first_value([node], "rotation", _leading(4))) is not None:
        axis = nue_to_enu(*turn[:3]) if nue else (turn[0], turn[1], turn[2])
        rotation = (*axis, turn[3])
    return SceneNode(
        node.type_name,
        node.def_name or "",
        translation=translation,
        rotation=rotation,
        name=first_value([node], "name", Field.string),
        robot=robot,
        numbers=numbers,
        flags=flags,
        strings=strings,
        children=children,
        line=line,
        lists=lists,
    )
