"""Webots' ``Supervisor`` and ``Node`` for the robot of a run (a node's ``Field``:
:mod:`mazesim.webots.field`).

The supervisor sees the scene tree's root, whose ``children`` are the world file's top-level
nodes (their type, DEF name and, read from the file, their ``translation``, ``rotation`` and
``name``; setting the pose of a node that holds walls or movable bodies moves them in the
simulation, and a movable body's node reads its live pose: :mod:`mazesim.webots.solids`;
other nodes' are snapshots that move nothing), the ``children`` of
the plain Solid, Transform, Pose and Group nodes among them, and theirs (snapshots too), the
robot's node among them (``getSelf``, ``getFromDef`` of its DEF name) and the file's other DEF
nodes (their type). It imports nodes into a ``children`` field (the root's or a static
node's) or an empty ``endPoint`` field and removes top-level and imported nodes while the
world runs (:mod:`mazesim.webots.scene_edits`); a change mazesim does not make (the robot's own
node, another field) prints Webots' kind of error and changes nothing, so the controller goes
on as Webots' would.
It reads and sets the robot's ``translation`` and ``rotation`` (moving the robot in the
simulation), and in a world with several robots those of every other robot too, reads its
position, orientation and velocity, sets a movable body's velocity, resets the simulation
(every robot, moved wall and movable body back where the file has them) or the motion of the
robot and the bodies, and quits it with a status (``mazesim webots run`` exits with it).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from mazesim._atomic import atomic_file
from mazesim.errors import MazesimError, _shortened
from mazesim.webots import simulation as _simulations
from mazesim.webots.devices import _print_error
from mazesim.webots.field import (
    Field,
    _file_frame,
    _in,
    _out,
    _refuse_scene_change,
    _yaw_of_rotation,
    field_value,
)
from mazesim.webots.frames import (
    WORLD_FRAME,
    axis_angle,
    body_turn,
    enu_to_nue_matrix,
    heading_of,
    placed,
    rotation_matrix,
    turned,
)
from mazesim.webots.importer import E_PUCK_MODELS, own_build
from mazesim.webots.inert import ContactPoint
from mazesim.webots.lights import LIGHT_TYPES
from mazesim.webots.list_fields import LIST_TYPES, list_items, list_kind
from mazesim.webots.movie import MovieRecorder
from mazesim.webots.name_clash import default_name, unique_names
from mazesim.webots.node_types import NODE_TYPES
from mazesim.webots.proto_fields import DeclaredFields, declared_fields, default_controller
from mazesim.webots.radio_devices import E_PUCK_CHANNEL
from mazesim.webots.robot import Robot
from mazesim.webots.scene import CHILDREN_TYPES, EPUCK_TYPES, GROUPING_TYPES, SceneNode
from mazesim.webots.scene_edits import Change, scene_edits
from mazesim.webots.solids import (
    Held,
    Pose2,
    as_given,
    composed,
    held_by_line,
    relative,
    world_objects,
)
from mazesim.webots.supervisor_refusal import _refuse_supervisor
from mazesim.webots.webots_api import NotSimulated
from mazesim.webots.world_save import with_fields

__all__ = ["Field", "Node", "Supervisor"]


#: Webots' built-in nodes a world file places at its top (the others are PROTOs).
_BUILT_IN_TYPES = {
    "Robot",
    "Solid",
    "Group",
    "Transform",
    "Pose",
    "WorldInfo",
    "Viewpoint",
    "Background",
    "DirectionalLight",
    "PointLight",
    "SpotLight",
    "Fog",
    "Shape",
    "Charger",
}
#: Base nodes with an ``endPoint`` field, which places its node in their parent's frame.
_END_POINT_TYPES = {"Slot", "HingeJoint", "Hinge2Joint", "SliderJoint", "BallJoint"}
#: Base nodes with ``translation`` and ``rotation`` fields.
_POSED_TYPES = {"Robot", "Solid", "Pose", "Transform", "Charger"}


class Node(NotSimulated):
    """A node of the world: the root, the robot (with fields and a live pose) or another node
    of the world file (a snapshot of its fields)."""

    def __init__(
        self,
        type_name: str,
        def_name: str = "",
        node_id: int = 0,
        robot: bool = False,
        translation: tuple[float, float, float] | None = None,
        rotation: tuple[float, float, float, float] | None = None,
        base_type: str | None = None,
        name: str | None = None,
    ) -> None:
        """A node.

        Args:
            type_name: The node's type (``"E-puck"``, ``"Solid"``...).
            def_name: Its DEF name.
            node_id: Its unique id.
            robot: Whether it is the robot of the run (its pose is the simulation's).
            translation: The ``translation`` of another node, read from the world file.
            rotation: The ``rotation`` (axis-angle) of another node, read from the world file.
            base_type: The built-in node its type derives from (its type by default).
            name: The ``name`` field of another node, read from the world file.
        """
        self._type_name = type_name
        self._base_type = base_type or ("Robot" if robot else type_name)
        self._def = def_name
        self._id = node_id
        self._robot = robot
        #: The index among the world's robots of another robot (live pose), else None.
        self._fleet_index: int | None = None
        self._translation = translation
        self._rotation = rotation
        #: Its translation and rotation as the world file gives them (what a reset restores).
        self._file_pose = (translation, rotation)
        self._strings = {"name": "e-puck", "customData": "", "controller": "<extern>"}
        if not robot:
            self._strings = {} if name is None else {"name": name}
        self._parent: Node | None = None
        self._children: list[Node] = []
        #: Whether it has a ``children`` field besides a grouping node's: a plain robot's, or
        #: a device's among its children.
        self._holds_children = False
        #: Other fields the world file gives the node (a PROTO instance's own fields too).
        self._numbers: dict[str, list[float]] = {}
        self._flags: dict[str, bool] = {}
        #: Its list fields of values: ``Field`` type and items (:mod:`.list_fields`).
        self._list_types: dict[str, int] = {}
        self._lists: dict[str, list[Any]] = {}
        #: The node of each of its fields that holds one (a Shape's ``geometry``...).
        self._field_nodes: dict[str, Node] = {}
        #: The line of its node type in the world file (0: unknown).
        self._line = 0
        #: The obstacles and movable bodies it holds (moved with it).
        self._held = Held()
        #: Its pose in the frame of the one movable body it holds alone (it follows that
        #: body), and its height; None otherwise.
        self._on_body: tuple[Pose2, float] | None = None
        #: The pose a supervisor last moved a live node to (world frame), as it gave it.
        self._given_pose: Pose2 | None = None
        #: The supervisor whose scene tree the node is the root of (None for another node).
        self._tree: Supervisor | None = None

    @classmethod
    def from_scene(cls, node: SceneNode, node_id: int) -> Node:
        """The node of a world file's top-level node (a Solid-like node without a
        ``translation`` or ``rotation`` field is at Webots' defaults)."""
        translation, rotation = node.translation, node.rotation
        if node.base_type in _POSED_TYPES:
            translation = translation or (0.0, 0.0, 0.0)
            rotation = rotation or (0.0, 0.0, 1.0, 0.0)
        made = cls(
            node.type_name,
            node.def_name,
            node_id,
            translation=translation,
            rotation=rotation,
            base_type=node.base_type,
            name=node.name,
        )
        made._line = node.line
        made._take_fields(node)
        return made

    def _take_fields(self, node: SceneNode) -> None:
        """Takes the fields the world file gives ``node`` (a PROTO instance's own, such as the
        E-puck's ``camera_width``, too) and those its PROTO declares that the file leaves out,
        at their defaults, as Webots' ``wb_supervisor_node_get_field`` finds them; strings the
        node already holds (the run's robot's live ``name``, ``customData``) stay."""
        self._numbers = {name: list(values) for name, values in node.numbers.items()}
        if node.type_name in EPUCK_TYPES:
            # The E-puck PROTO's radio channels, at its default where the file sets none.
            for channel in ("emitter_channel", "receiver_channel"):
                self._numbers.setdefault(channel, [float(E_PUCK_CHANNEL)])
        self._flags = dict(node.flags)
        held = dict(self._strings) if self._robot else {}
        self._strings.update(node.strings)
        self._strings.update(held)
        declared = declared_fields(node.type_name)
        for name, values in declared.numbers.items():
            self._numbers.setdefault(name, list(values))
        for name, text in declared.strings.items():
            self._strings.setdefault(name, text)
        for name, flag in declared.flags.items():
            self._flags.setdefault(name, flag)
        self._take_lists(node, declared)

    def _take_lists(self, node: SceneNode, declared: DeclaredFields) -> None:
        """Takes the node's list fields of values the world file writes, each of the kind its
        PROTO or base node declares, and those its PROTO declares that the file leaves out."""
        kinds = {name: kind for name, (kind, _) in declared.lists.items()}
        types = (node.type_name, node.base_type)
        written = dict(node.lists)
        for name, (_, values) in declared.lists.items():
            written.setdefault(name, values)
        for name, values in written.items():
            kind = list_kind(types, name, values, kinds)
            if kind is not None:
                self._list_types[name] = LIST_TYPES[kind][0]
                self._lists[name] = list_items(kind, values)

    def _adopt(self, children: list[Node]) -> None:
        """Makes ``children`` the node's ``children`` field (a node a ``USE`` lists again
        keeps the parent of its ``DEF``)."""
        self._children = children
        for child in children:
            if child._parent is None:
                child._parent = self

    def _adopt_fields(self, nodes: dict[str, Node]) -> None:
        """Makes ``nodes`` the nodes of the node's single-node fields, by field name."""
        self._field_nodes = nodes
        for node in nodes.values():
            if node._parent is None:
                node._parent = self

    def _simulation(self) -> _simulations.RobotSimulation:
        return _simulations.current()

    @property
    def _nested(self) -> bool:
        """Whether the node is inside another node of the world file (not at its top)."""
        return self._parent is not None and self._parent._parent is not None

    def _label(self) -> str:
        """The node as a message names it: its type and DEF name."""
        if self._id == 0:
            return "the scene tree's root"
        return f"node {self._type_name}" + (f" (DEF {self._def})" if self._def else "")

    def _world_frame(self) -> tuple[list[float], list[float]]:
        """The node's origin and rotation matrix (row after row) in the world frame (ENU),
        composed through the nodes above it from their ``translation`` and ``rotation``
        (Webots' defaults, none, where absent)."""
        chain: list[Node] = []
        node: Node | None = self
        while node is not None and node._parent is not None:
            chain.append(node)
            node = node._parent
        frame = WORLD_FRAME
        for node in reversed(chain):
            if node._live:
                x, y, yaw = node._field_pose()
                body = node._body_turn()
                turn = (0.0, 0.0, 1.0, yaw) if body is None else axis_angle(turned(yaw, body))
                frame = placed(frame, (x, y, node._field_height()), turn)
            else:
                frame = placed(frame, node._translation or (0.0, 0.0, 0.0), node._rotation)
        return frame

    @property
    def _live(self) -> bool:
        """Whether the node's pose is the simulation's: a robot's (its own or another's) or
        that of the movable body it holds."""
        return self._robot or self._fleet_index is not None or self._on_body is not None

    def _hold(self, held: Held, bodies: list[dict[str, Any]]) -> None:
        """Makes the node hold ``held`` (``bodies``: the import report's): it follows the one
        movable body it holds alone."""
        self._held = held
        if len(held.bodies) != 1 or held.walls or self._translation is None:
            return
        body = bodies[held.bodies[0]]
        if body.get("owners", [0])[-1] != self._line:
            return  # a node above the body's own: it stays where it is as the body moves
        start = (float(body["center"][0]), float(body["center"][1]), float(body.get("yaw", 0.0)))
        origin = self._world_frame()[0]
        self._on_body = (relative(start, self._planar()), origin[2])

    def _parent_planar(self) -> Pose2:
        """The pose seen from above of the frame the node's fields are in (its parent's)."""
        if self._parent is None or self._parent._parent is None:
            return 0.0, 0.0, 0.0
        return self._parent._planar()

    def _field_pose(self) -> Pose2:
        """A live node's translation x, y and yaw as its fields give them: in its parent's
        frame, as Webots gives every node's (a robot nested in a Transform, Pose or Group, as
        the body a node follows)."""
        return relative(self._parent_planar(), self._pose())

    def _field_height(self) -> float:
        """A live node's translation z: a movable body's as the file gives it, a robot's that
        mazesim does not simulate (no e-puck: its body does not move, as a Robot without
        physics stays at its height in Webots) as the file gives it or a supervisor last set
        it, 0 for an e-puck (on the floor)."""
        if self._on_body or not self._simulated():
            return self._translation[2] if self._translation else 0.0
        return 0.0

    def _simulated(self) -> bool:
        """Whether the node is a robot whose body mazesim simulates (an e-puck of a world run,
        or the run's own robot, for which a run of one controller simulates an e-puck)."""
        simulation = self._simulation()
        index = self._fleet_index
        if index is None and self._robot and simulation.fleet is not None:
            index = simulation.robot_index
        if index is None:
            return self._robot
        robots = simulation.report.get("robots") or []
        return index >= len(robots) or robots[index].get("profile") is not None

    def _set_field_height(self, z: float) -> None:
        """Keeps a supervisor's translation z of a robot mazesim does not simulate."""
        if not self._on_body and not self._simulated() and self._translation is not None:
            x, y, _ = self._translation
            self._translation = (x, y, z)

    def _set_field_pose(self, x: float, y: float, yaw: float) -> None:
        """Moves a live node to the translation x, y and yaw given in its parent's frame."""
        self._move(*composed(self._parent_planar(), (x, y, yaw)))

    def _planar(self) -> Pose2:
        """The node's pose seen from above, composed through the nodes above it (its heading
        a robot's forward's)."""
        origin, matrix = self._world_frame()
        return origin[0], origin[1], heading_of(matrix, self._body_turn() if self._live else None)

    def _body_turn(self) -> list[float] | None:
        """How a robot node's own frame turns to the robot's (x forward, y left, z up;
        :func:`~mazesim.webots.frames.body_turn`): a body built Y-up, or a Z-up body in a
        file of the NUE convention, stood upright by its ``rotation``. None for a node that
        turns about the vertical alone (a robot of the file's own convention, a body it
        holds)."""
        simulation = self._simulation()
        if self._robot:
            y_up = simulation.scene.body_y_up
        elif self._fleet_index is not None:
            robots = simulation.report.get("robots") or []
            if self._fleet_index >= len(robots):
                return None
            y_up = bool(robots[self._fleet_index].get("y_up", simulation.scene.y_up_devices))
        else:
            return None
        if y_up == simulation.scene.nue:
            return None
        return body_turn(y_up, simulation.scene.nue)

    def _live_matrix(self, yaw: float) -> list[float]:
        """A live node's rotation matrix at heading ``yaw`` (row after row): ``Rz(yaw)``, turned
        as :meth:`_body_turn` says."""
        turn = self._body_turn()
        return turned(yaw, turn) if turn is not None else rotation_matrix(0.0, 0.0, 1.0, yaw)

    def _move_held(self, before: Pose2, after: Pose2) -> bool:
        """Moves what the node holds by the motion from ``before`` to ``after``; False, with
        Webots' kind of error, when the simulation refuses it."""
        try:
            world_objects(self._simulation()).move_node(self._line, before, after)
        except MazesimError as refused:
            _print_error(f"Error: {self._label()} cannot be moved there: {refused}")
            return False
        return True

    def _place(
        self,
        translation: tuple[float, float, float] | None = None,
        rotation: tuple[float, float, float, float] | None = None,
    ) -> None:
        """Sets the ``translation`` or ``rotation`` of a node whose pose is read from the file:
        what it holds moves with it (its field stays as it was when that is refused)."""
        before = self._planar() if self._held else None
        kept = (self._translation, self._rotation)
        self._translation = translation or self._translation
        self._rotation = rotation or self._rotation
        if before is not None and not self._move_held(before, self._planar()):
            self._translation, self._rotation = kept

    def _pose(self) -> tuple[float, float, float]:
        """The node's pose seen from above in the world frame: a live node's as the simulation
        holds it, or as it was given while the simulation holds it still there
        (:func:`~mazesim.webots.solids.as_given`), another's from its fields."""
        if self._live:
            physics = self._live_pose()
            if physics is not None:
                return as_given(physics, self._given_pose, self._start_pose())
        if self._translation is None:
            return math.nan, math.nan, math.nan
        yaw = _yaw_of_rotation(list(self._rotation)) if self._rotation else 0.0
        return self._translation[0], self._translation[1], yaw

    def _live_pose(self) -> Pose2 | None:
        """A live node's pose as the simulation holds it (None: a body no longer there)."""
        if self._on_body is not None:
            index = self._held.bodies[0]
            poses = world_objects(self._simulation()).body_poses()
            if index < len(poses):
                x, y, yaw = poses[index]
                return composed((float(x), float(y), float(yaw)), self._on_body[0])
            return None
        if self._fleet_index is not None:
            x, y, yaw = self._simulation().fleet.pose(self._fleet_index)
            return float(x), float(y), float(yaw)
        x, y, yaw = self._simulation().simulator.pose
        return float(x), float(y), float(yaw)

    def _start_pose(self) -> Pose2 | None:
        """A live node's pose at the start as the world file gives it (the import report's, in
        double precision): a robot's, or that of the movable body it follows composed with its
        place on it."""
        report = self._simulation().report
        if self._on_body is not None:
            bodies = report.get("bodies") or []
            index = self._held.bodies[0]
            if index >= len(bodies):
                return None
            body = bodies[index]
            start = (
                float(body["center"][0]),
                float(body["center"][1]),
                float(body.get("yaw", 0.0)),
            )
            return composed(start, self._on_body[0])
        own = self._simulation().robot_index if self._robot else self._fleet_index
        fleet = getattr(self._simulation(), "fleet", None)
        if fleet is not None and own is not None:
            # Every robot of a world run, one a supervisor imported while it runs too.
            robots = [(own, fleet.robots_of([own])[0])]
        else:
            robots = list(enumerate(report.get("robots") or []))
        for index, robot in robots:
            if robot.get("index", index) == own and robot.get("pose") is not None:
                x, y, yaw = robot["pose"]
                return float(x), float(y), float(yaw)
        return None

    def _move(self, x: float, y: float, yaw: float) -> None:
        """Moves the robot, or the movable body the node follows, in the simulation, at rest
        (the pose it reads while it stays there is the one given: :meth:`_pose`)."""
        before = self._pose()
        given = self._given_pose
        self._given_pose = (x, y, yaw)
        if self._on_body is not None:
            self._move_held(before, (x, y, yaw))
            return
        if self._held and not self._move_held(before, (x, y, yaw)):
            return  # a robot kept as an obstacle: refused where its obstacle cannot go
        try:
            if self._fleet_index is not None:
                self._simulation().fleet.move(self._fleet_index, x, y, yaw)
            else:
                self._simulation().move_robot(x, y, yaw)
        except MazesimError as refused:
            # Webots' field setters never raise: the robot stays where it is, with an error.
            self._given_pose = given
            _print_error(f"Error: {self._label()} cannot be moved there: {refused}")

    def _string(self, name: str) -> str:
        """A string field's value: another robot's ``customData`` as the last write left it,
        the robot's own ``setCustomData`` as much as a supervisor's (the world's process keeps
        it), the run's own robot's as its ``getCustomData`` reads it, any other as this node
        holds it."""
        if name == "customData" and self._fleet_index is not None:
            written = self._simulation().fleet.custom_data_field(self._fleet_index)
            if written is not None:
                return str(written)
        if name == "customData" and self._robot and Robot.created is not None:
            # wb_robot_set_custom_data writes the robot's field (reference manual, Robot).
            return Robot.created.getCustomData()
        return self._strings.get(name, "")

    def _tell_custom_data(self, text: str) -> None:
        """Gives a robot the ``customData`` a supervisor wrote into its node: the run's own
        robot reads it at once; another robot of the world, whose controller runs in a process
        of its own, reads it after the world's next step, as in Webots (a node that is no
        robot only keeps it)."""
        if self._robot and Robot.created is not None:
            Robot.created._custom_data = text
        elif self._fleet_index is not None:
            self._simulation().fleet.set_custom_data(self._fleet_index, text)

    def _tell_field(self, name: str, value: Any) -> None:
        """Gives the world a supervisor's edit of a light's field (a light node's, or a light
        PROTO's such as a ``ConstructionLamp``'s), or of the ``translation`` or ``rotation`` of
        a node that holds a light: every robot's light sensors see the light so, in a world run
        from the world's next step on (another node only keeps the value)."""
        if not self._line or _simulations._current is None:
            return
        simulation = self._simulation()
        holders = set().union(*(s.holders for s in simulation.scene.light_sources or []))
        moves_light = name in ("translation", "rotation") and self._line in holders
        if self._type_name in LIGHT_TYPES or moves_light:
            world_objects(simulation).edit_light(self._line, name, value)

    def _tell_controller(self, name: str) -> None:
        """Gives another robot of a world run the controller a supervisor wrote into its
        node's ``controller`` field: as Webots does when the field changes, the robot's running
        controller ends (its ``Robot.step`` returns -1) and the one named starts on the robot
        where it stands, from the world's next step on (none for "" or ``<none>``). The run's
        own node and a run of one controller only keep the value."""
        fleet = self._simulation().fleet
        own = self._fleet_index == self._simulation().robot_index
        if fleet is not None and self._fleet_index is not None and not own:
            fleet.change_controller(self._fleet_index, name)

    def getId(self) -> int:
        """The node's unique id."""
        return self._id

    def getDef(self) -> str:
        """The node's DEF name (empty if it has none)."""
        return self._def

    def getTypeName(self) -> str:
        """The node's type name (``"E-puck"``, ``"Robot"``, ``"Group"``...)."""
        return self._type_name

    def getBaseTypeName(self) -> str:
        """The built-in node the type derives from (``"Robot"`` for the E-puck PROTO,
        ``"Solid"`` for a ``Wall``)."""
        return self._base_type

    def getType(self) -> int:
        """The node's type constant (``Node.ROBOT`` for the robot, ``Node.SOLID`` for a node of
        unknown base)."""
        name = _constant_name(self._base_type)
        return NODE_TYPES.index(name) if name in NODE_TYPES else NODE_TYPES.index("SOLID")

    def isProto(self) -> bool:
        """Whether the node is a PROTO instance."""
        return self._type_name != self._base_type or self._type_name not in _BUILT_IN_TYPES

    def getParentNode(self) -> Node | None:
        """The root for a node at the top of the world file, the Solid, Transform, Pose or Group
        whose ``children`` hold a node, the node whose field holds a node of one (a Shape's
        ``geometry``); None for the root and for nodes inside a PROTO (not kept)."""
        return self._parent

    def remove(self) -> None:
        """Removes the node from the running world, if it is at the top of the scene tree (see
        :meth:`Supervisor._remove_node`); another prints Webots' kind of error."""
        root = self
        while root._parent is not None:
            root = root._parent
        if root._tree is None:
            _refuse_scene_change(f"Node.remove() of {self._label()}")
            return
        root._tree._remove_node(self, "wb_supervisor_node_remove()")

    def _field_types(self) -> dict[str, int]:
        """The fields the node has: name -> ``Field`` type."""
        if self._id == 0:
            return {"children": Field.MF_NODE}
        types = dict.fromkeys(self._strings, Field.SF_STRING)
        types.update(self._list_types)  # a field of nodes below (an empty ``children``) wins
        if self._type_name in GROUPING_TYPES or self._holds_children:
            types["children"] = Field.MF_NODE
        if self._base_type in _END_POINT_TYPES:
            types["endPoint"] = Field.SF_NODE  # empty: a node can be imported into it
        types.update(dict.fromkeys(self._field_nodes, Field.SF_NODE))
        types.update(dict.fromkeys(self._flags, Field.SF_BOOL))
        for name, values in self._numbers.items():
            kinds = {1: Field.SF_FLOAT, 2: Field.SF_VEC2F, 3: Field.SF_VEC3F, 4: Field.SF_ROTATION}
            if len(values) in kinds:
                types[name] = kinds[len(values)]
            if len(values) == 1 and values[0].is_integer():
                types[name] = Field.SF_INT32
            if len(values) == 3 and name.lower().endswith("color"):
                types[name] = Field.SF_COLOR
        declared = declared_fields(self._type_name)
        for name in declared.floats & types.keys():
            if len(self._numbers.get(name, ())) == 1:  # a file's older SFVec3f gravity stays one
                types[name] = Field.SF_FLOAT
        for name in declared.nodes - types.keys():
            types[name] = Field.SF_NODE  # empty where the file leaves it out
        # Every robot of the world has both, live, whatever its node writes (a project's PROTO
        # of the e-puck, unknown here as a Solid, may leave its rotation out).
        if self._live or self._translation is not None:
            types["translation"] = Field.SF_VEC3F
        if self._live or self._rotation is not None:
            types["rotation"] = Field.SF_ROTATION
        return types

    def getField(self, fieldName: str) -> Field | None:
        """The field of that name, or None (with Webots' message)."""
        types = self._field_types()
        if fieldName not in types:
            _print_error(
                f"Error: wb_supervisor_node_get_field(): field '{fieldName}' does not exist "
                f"in node '{self._def or self._type_name}'."
            )
            return None
        return Field(self, fieldName, types[fieldName])

    getProtoField = getField

    def getPosition(self) -> list[float]:
        """The node's position [x, y, z] in metres (world frame, a node inside others' composed
        through theirs; NaN for a node whose position the world file does not give)."""
        if self._live:
            x, y, _ = self._pose()
            if self._on_body is not None:
                return _out([x, y, self._on_body[1]])
            return _out([x, y, 0.0 if self._simulated() else self._world_frame()[0][2]])
        if self._nested and self._translation is not None:
            return _out(self._world_frame()[0])
        return _out(list(self._translation)) if self._translation else [math.nan] * 3

    def getOrientation(self) -> list[float]:
        """The node's rotation matrix, row after row (9 numbers; a node inside others' composed
        through theirs)."""
        if self._nested and not self._live:
            matrix = self._world_frame()[1]
        elif self._live:
            matrix = self._live_matrix(self._pose()[2])
        elif self._rotation is None:
            matrix = rotation_matrix(0.0, 0.0, 1.0, self._pose()[2])
        else:
            matrix = rotation_matrix(*self._rotation)
        return enu_to_nue_matrix(matrix) if _file_frame() else matrix

    def getPose(self, fromNode: Node | None = None) -> list[float]:
        """The node's 4 x 4 homogeneous transform, row after row: in the world frame, or with
        ``fromNode`` in that node's frame (its inverse transform times this node's), as
        Webots' ``wb_supervisor_node_get_pose(node, from_node)`` gives it."""
        x, y, z = self.getPosition()
        r = self.getOrientation()
        if fromNode is None:
            return [*r[0:3], x, *r[3:6], y, *r[6:9], z, 0.0, 0.0, 0.0, 1.0]
        origin = fromNode.getPosition()
        axes = fromNode.getOrientation()
        offset = [x - origin[0], y - origin[1], z - origin[2]]
        # The inverse of a rotation is its transpose: row i of it is column i of ``axes``.
        turn = [
            [sum(axes[3 * k + i] * r[3 * k + j] for k in range(3)) for j in range(3)]
            for i in range(3)
        ]
        move = [sum(axes[3 * k + i] * offset[k] for k in range(3)) for i in range(3)]
        return [*turn[0], move[0], *turn[1], move[1], *turn[2], move[2], 0.0, 0.0, 0.0, 1.0]

    def getCenterOfMass(self) -> list[float]:
        """The centre of mass: the node's position."""
        return self.getPosition()

    def getVelocity(self) -> list[float]:
        """Linear and angular velocity [vx, vy, vz, wx, wy, wz] (m/s, rad/s, world frame)."""
        if self._on_body is not None:
            moving = world_objects(self._simulation()).body_velocities()
            index = self._held.bodies[0]
            if index >= len(moving):  # no simulator holds the world's bodies: none is moving
                return [0.0] * 6
            vx, vy, yaw_rate = moving[index]
        elif self._fleet_index is not None:
            vx, vy, yaw_rate = self._simulation().fleet.velocity(self._fleet_index)
        elif not self._robot:
            return [0.0] * 6
        else:
            vx, vy, yaw_rate = self._simulation().velocity
        return [*_out([vx, vy, 0.0]), *_out([0.0, 0.0, yaw_rate])]

    def setVelocity(self, velocity: list[float]) -> None:
        """Sets the linear and angular velocity [vx, vy, vz, wx, wy, wz] (m/s, rad/s, world
        frame) of the movable bodies the node holds: their motion seen from above, vx, vy and the
        turn rate about the vertical (the floor's friction slows them from the next step on).
        Accepted for a robot, whose velocity comes from its wheels, and for static nodes."""
        if not self._held.bodies:
            return
        values = field_value(velocity, 6, "Node.setVelocity")
        vx, vy, _ = _in(values[:3])
        turn_rate = _in(values[3:6])[2]
        objects = world_objects(self._simulation())
        try:
            for index in self._held.bodies:
                objects.set_body_velocity(index, vx, vy, turn_rate)
        except MazesimError as refused:
            _print_error(f"Error: the velocity of {self._label()} cannot be set: {refused}")

    def resetPhysics(self) -> None:
        """Stops the robot's motion (its wheels' speeds still apply at the next step), or that
        of the movable bodies the node holds; other nodes are static."""
        if self._held.bodies:
            here = self._planar() if self._on_body is None else self._pose()
            world_objects(self._simulation()).move_node(self._line, here, here)
        if self._robot:
            self._simulation().velocity = (0.0, 0.0, 0.0)

    def restartController(self) -> None:
        """Restarts the controller of another robot of a world run (``mazesim webots run
        WORLD``): its process sees ``Robot.step`` return -1, as when Webots ends a controller,
        and a new process of the same controller starts at once, on the robot where it is
        (:mod:`mazesim.webots.lockstep`). The supervisor's own controller, and a run of one
        controller (no other controller runs), answer Webots' error."""
        fleet = self._simulation().fleet
        own = self._fleet_index == self._simulation().robot_index
        if fleet is not None and self._fleet_index is not None and not own:
            if fleet.restart_controller(self._fleet_index):
                return
        _print_error(
            "Error: wb_supervisor_node_restart_controller() is not available in mazesim for "
            f"{self._label()}: only another robot's controller of a world run restarts."
        )

    def getContactPoints(self, includeDescendants: bool = False) -> list[ContactPoint]:
        """The robot's contacts now, each on the node itself (its id), on the floor: with
        another robot of a world run, where their bodies meet; with a wall, the robot's centre
        standing for the point. Another robot's node answers with that robot's contacts."""
        fleet = self._simulation().fleet
        if fleet is not None and self._fleet_index is not None:
            points = fleet.contact_points(self._fleet_index)
            return [ContactPoint(_out(point), self._id) for point in points]
        if self._robot and self._simulation().simulator.colliding:
            x, y, _ = self._pose()
            return [ContactPoint(_out([x, y, 0.0]))]
        return []

    def getNumberOfFields(self) -> int:
        """The number of fields :meth:`getField` knows (:meth:`getFieldByIndex` reads each)."""
        return len(self._field_types())

    def getFieldByIndex(self, index: int) -> Field | None:
        """The field at ``index`` among those :meth:`getField` knows (0 to
        :meth:`getNumberOfFields` - 1), or None with Webots' error: a loop over a node's
        fields reads each once (in mazesim's order, not always the declaration's)."""
        name = self._field_name_at(index)
        return None if name is None else Field(self, name, self._field_types()[name])

    def _field_name_at(self, index: int) -> str | None:
        """The name of the field :meth:`getFieldByIndex` gives (what C's
        ``wb_supervisor_node_get_field_by_index`` asks for), or None with Webots' error."""
        names = list(self._field_types())
        if not 0 <= index < len(names):
            _print_error(
                f"Error: wb_supervisor_node_get_field_by_index(): index {index} out of range "
                f"[0, {len(names) - 1}]."
            )
            return None
        return names[index]

    def getStaticBalance(self) -> bool:
        """True: the robot stands on the floor."""
        return True


def _nodes_of(listed: list[SceneNode], made: dict[int, Node], robot: Node) -> list[Node]:
    """The node of each scene node (``robot`` for the robot's): one per scene node, however
    often ``USE`` lists it (``made`` keeps them)."""
    for scene_node in listed:
        if id(scene_node) not in made and scene_node.robot:
            robot._take_fields(scene_node)
            made[id(scene_node)] = robot
        elif id(scene_node) not in made:
            made[id(scene_node)] = Node.from_scene(scene_node, 0)
    return [made[id(scene_node)] for scene_node in listed]


def _nest(
    top: list[tuple[Node, SceneNode]], first_id: int, robot: Node, made: dict[int, Node]
) -> list[Node]:
    """Gives each grouping node among ``top`` (a top-level node and its scene node) and below it
    the nodes of its ``children`` field (``robot`` for the robot's), and each node below one the
    nodes of its single-node fields; returns those nodes in file order, their ids from
    ``first_id`` on (the single-node fields' after the others')."""
    nested: list[Node] = []
    held: list[Node] = []
    singles: set[int] = set()
    placed: set[int] = set()
    pending = list(reversed(top))
    while pending:
        node, scene_node = pending.pop()
        if id(node) in placed:
            continue  # a USE of a node placed already
        placed.add(id(node))
        if id(node) in singles:
            held.append(node)
        elif node._nested:
            node._id = first_id + len(nested)
            nested.append(node)
        inner: list[Node] = []
        if scene_node.type_name in CHILDREN_TYPES:
            inner = _nodes_of(scene_node.children, made, robot)
            node._adopt(inner)
            node._holds_children = True
        fields = list(scene_node.nodes.values())
        kept = _nodes_of(fields, made, robot)
        node._adopt_fields(dict(zip(scene_node.nodes, kept)))
        singles.update(id(n) for n in kept)
        # The nodes of another robot's slot fields (a pendulum's joint in an E-puck's
        # turretSlot): found by their DEF names with their fields, placed in the robot's frame.
        slotted_scene = [n for listed in scene_node.slots.values() for n in listed]
        slotted = _nodes_of(slotted_scene, made, robot)
        for held_node in slotted:
            held_node._parent = held_node._parent or node
        pending.extend(
            reversed(
                list(
                    zip(
                        [*kept, *inner, *slotted],
                        [*fields, *scene_node.children, *slotted_scene],
                    )
                )
            )
        )
    for index, node in enumerate(held):
        node._id = first_id + len(nested) + index
    return [*nested, *held]


def _follow_robots(nodes: list[Node], robots: list[dict[str, Any]], own: int) -> None:
    """Gives the nodes of the world's other robots their live poses: a node is a robot's when
    its DEF name, or else its ``name`` field, is that robot's."""
    for robot in robots:
        if robot["index"] == own:
            continue
        for node in nodes:
            if node._robot or node._fleet_index is not None or node._held:
                continue  # a robot kept as an obstacle moves as one
            same_def = bool(robot.get("def_name")) and node.getDef() == robot["def_name"]
            same_name = not robot.get("def_name") and robot.get("name") is not None
            if same_def or (same_name and node._strings.get("name") == robot["name"]):
                node._fleet_index = int(robot["index"])
                break


def _detach(node: Node) -> None:
    """Takes ``node`` out of the field of its parent that holds it."""
    parent = node._parent
    if parent is None:
        return
    parent._children = [n for n in parent._children if n is not node]
    parent._field_nodes = {k: n for k, n in parent._field_nodes.items() if n is not node}


def _moving(node: Node) -> Node | None:
    """The node at or above ``node`` that moves in the simulation (a robot, a node of a movable
    body), or None."""
    while node._parent is not None:
        if node._live or node._base_type == "Robot":
            return node
        node = node._parent
    return None


def _inside(node: Node, ancestor: Node) -> bool:
    """Whether ``node`` is below ``ancestor`` in the scene tree."""
    parent = node._parent
    while parent is not None and parent is not ancestor:
        parent = parent._parent
    return parent is ancestor


def _constant_name(type_name: str) -> str:
    """``"DistanceSensor"`` -> ``"DISTANCE_SENSOR"``."""
    out = []
    for i, char in enumerate(type_name):
        if char.isupper() and i and not type_name[i - 1].isupper():
            out.append("_")
        out.append(char.upper())
    return "".join(out)


for _index, _name in enumerate(NODE_TYPES):
    setattr(Node, _name, _index)


class Supervisor(Robot):
    """A robot with the supervisor's powers over the simulation."""

    SIMULATION_MODE_PAUSE = 0
    SIMULATION_MODE_REAL_TIME = 1
    SIMULATION_MODE_FAST = 2

    def __init__(self) -> None:
        """Attaches to the prepared simulation as a supervisor."""
        super().__init__()
        scene = self._simulation.scene
        if scene.supervisor_refused:
            # A plain robot of the world file: Webots refuses every supervisor function.
            _refuse_supervisor(self)
        else:
            self._simulation.supervisor = True
        robot_type = str(self._simulation.report.get("robot_model") or "E-puck")
        self._self = Node(robot_type, scene.robot_def or "", robot=True)
        self._self._strings.update(name=self._simulation.robot_name, customData=self._custom_data)
        if scene.robot_controller is not None or self._simulation.report.get("robot_model"):
            # The robot node's field as Webots reads it: the file's, else its PROTO's default
            # (the E-puck's e-puck_avoid_obstacles), else a Robot node's, "<generic>".
            report = self._simulation.report
            line = report.get("robot_line")
            own = [r for r in report.get("robots") or () if r.get("line") == line]
            declared = default_controller(own[0]) if own else ""
            declared = declared or declared_fields(robot_type).strings.get(
                "controller", "<generic>"
            )
            self._self._strings["controller"] = (
                declared if scene.robot_controller is None else scene.robot_controller
            )
        self._mode = self.SIMULATION_MODE_FAST
        self._movie = MovieRecorder(self._simulation)
        self._root = Node("Group", node_id=0)
        self._root._tree = self
        made: dict[int, Node] = {}
        children = _nodes_of(scene.nodes, made, self._self)
        self._root._adopt(children)
        #: The nodes inside grouping nodes, in file order (the robot's own where it is one).
        self._nested_nodes = _nest(
            list(zip(children, scene.nodes)), len(children) + 2 + len(scene.defs), self._self, made
        )
        if self._self._parent is None:
            children.append(self._self)
            self._root._adopt(children)
        for node_id, child in reversed(list(enumerate(children, start=1))):
            child._id = node_id  # a node a USE lists again keeps the id of its first place
        self._nodes: dict[str, Node] = {}
        #: The id of the first of the file's other DEF nodes, and the next id an imported node
        #: takes.
        self._def_ids = len(children) + 1
        self._next_id = self._def_ids + len(scene.defs) + len(self._nested_nodes) + 1
        #: The DEF names of the file's nodes a supervisor removed.
        self._removed_defs: set[str] = set()
        #: The nodes a supervisor imported into a field of another node than the root.
        self._imports: list[Node] = []
        #: Every node of the world file (one per scene node), whose fields a reset restores.
        self._file_nodes = list(made.values())
        self._simulation.reset_listeners.append(self._restore_file_poses)
        held = held_by_line(self._simulation.report)
        bodies = self._simulation.report.get("bodies", [])
        for node in made.values():
            if node._line in held and not node._robot:
                node._hold(held[node._line], bodies)
        # The robot of the run when it is no e-puck: its collision shapes are the world's
        # obstacles (though not in its own import, where the e-puck stands in for it).
        model = self._simulation.report.get("robot_model")
        if (
            model is not None
            and model not in E_PUCK_MODELS
            and not own_build(self._simulation.report)
        ):
            self._self._line = int(self._simulation.report.get("robot_line") or 0)
            self._self._held = Held(obstacle=True)
        if self._simulation.fleet is not None:
            _follow_robots(
                [*children, *self._nested_nodes],
                self._simulation.fleet.robots(),
                self._simulation.robot_index,
            )

    def _import_nodes(
        self, position: int, text: str, call: str, into: tuple[Node, str] | None = None
    ) -> None:
        """Imports the nodes of ``text`` into the running world at ``position`` of the root's
        ``children`` (-1: at the end; below: from the end, as in Webots), or of the field
        ``into[1]`` of the node ``into[0]`` (a ``children`` field, or an empty single-node
        field such as a ``Slot``'s ``endPoint``), as
        :class:`~mazesim.webots.scene_edits.SceneEdits` does; Webots' kind of error when
        refused, nothing changed."""
        parent, field = into if into is not None else (self._root, "children")
        single = field != "children"
        children = parent._children
        index = int(position) if int(position) >= 0 else len(children) + 1 + int(position)
        if not single and not 0 <= index <= len(children):
            _print_error(f"Error: {call} called with an out of range position: {position}.")
            return
        if single and field in parent._field_nodes:
            _print_error(f"Error: {call} called with a field that holds a node: remove it first.")
            return
        moving = _moving(parent)
        if moving is not None:
            _print_error(
                f"Error: {call} refused by mazesim: {moving._label()} moves in the simulation, "
                "and a node imported into it would not move with it; nothing changed."
            )
            return
        place = None if parent is self._root else (parent._line, parent._world_frame())
        if parent is self._root:
            # Webots renames an imported Solid whose name a top-level sibling has.
            taken = [
                n for c in children if (n := c._strings.get("name") or default_name(c._type_name))
            ]
            text = unique_names(text, taken)
        try:
            change = scene_edits(self._simulation).import_node(text, place)
        except MazesimError as refused:
            _print_error(f"Error: {call} refused by mazesim: {refused}; nothing changed.")
            return
        made: dict[int, Node] = {}
        added = _nodes_of(change.added, made, self._self)
        if parent is self._root:
            for offset, node in enumerate(added):
                node._id = self._next_id + offset
            self._next_id += len(added)
        if parent is not self._root:
            self._imports.extend(added)
        if single:
            parent._adopt_fields({**parent._field_nodes, field: added[0]} if added else {})
        else:
            children[index:index] = added
            parent._adopt(children)
        nested = _nest(list(zip(added, change.added)), self._next_id, self._self, made)
        self._next_id += len(nested)
        self._nested_nodes.extend(nested)
        self._file_nodes.extend(made.values())
        self._held_again(change)
        for node in made.values():
            if node._line in change.held:
                node._hold(change.held[node._line], change.bodies)
        if self._simulation.fleet is not None:  # an imported robot's node follows the robot
            _follow_robots(
                [*added, *nested], self._simulation.fleet.robots(), self._simulation.robot_index
            )

    def _remove_node(self, node: Node, call: str) -> None:
        """Removes ``node``, at the top of the scene tree, from the running world, as
        :class:`~mazesim.webots.scene_edits.SceneEdits` does; Webots' kind of error when
        refused (the robot's own node, a node inside another), nothing changed. Another
        robot's node leaves the world with its robot, whose controller's ``Robot.step`` then
        returns -1 (:mod:`mazesim.webots.robots_changed`)."""
        imported = any(node is n for n in self._imports)
        if node._robot or (node._parent is not self._root and not imported):
            what = "the robot's own node" if node._robot else "a node inside another node"
            _print_error(f"Error: {call} refused by mazesim: {what} stays; nothing changed.")
            return
        try:
            change = scene_edits(self._simulation).remove_node(node._line)
        except MazesimError as refused:
            _print_error(f"Error: {call} refused by mazesim: {refused}; nothing changed.")
            return
        gone = [node, *(n for n in self._nested_nodes if _inside(n, node))]
        _detach(node)
        self._nested_nodes = [n for n in self._nested_nodes if n not in gone]
        self._removed_defs.update(n._def for n in gone if n._def)
        self._held_again(change)

    def _held_again(self, change: Change) -> None:
        """Gives the nodes the walls and movable bodies they hold in the changed world (their
        indices may move)."""
        for node in self._file_nodes:
            if node._robot or not node._held:
                continue
            held = change.held.get(node._line)
            node._held.walls = list(held.walls) if held is not None else []
            node._held.bodies = list(held.bodies) if held is not None else []
            if not node._held.bodies:
                node._on_body = None

    def getSelf(self) -> Node:
        """The robot's own node."""
        return self._self

    def getRoot(self) -> Node:
        """The scene tree's root: a Group whose ``children`` field lists the world file's
        top-level nodes (only the robot in a mazesim world)."""
        return self._root

    def getFromDef(self, name: str) -> Node | None:
        """The node of that DEF name (the first in the file), or None.

        As Webots' libController does, a name no node has gives None silently; an empty one
        gives None with Webots' error. A world without DEF names (a mazesim world) gives the
        robot's node for any name, until a supervisor imports a node into it.
        """
        if not name:
            _print_error(
                "Error: wb_supervisor_node_get_from_def() called with a NULL or empty 'def' "
                "argument."
            )
            return None
        if "." in name:
            return self._from_def_path(name.split("."))
        scene = self._simulation.scene
        unnamed = not scene.defs and self._simulation.scene_edits is None
        if name == scene.robot_def or unnamed:
            return self._self
        for child in [*self._root._children, *self._nested_nodes]:
            if child.getDef() == name:
                return child
        if name in scene.defs and name not in self._removed_defs:
            if name not in self._nodes:
                node_id = self._def_ids + list(scene.defs).index(name)
                self._nodes[name] = Node(scene.defs[name], name, node_id)
            return self._nodes[name]
        return None

    def _from_def_path(self, names: list[str]) -> Node | None:
        """The node of a dotted DEF path (``"ROBOT.JOINT.SOLID"``): the node of the first DEF
        name, then each next one the first node of that DEF name inside the last, as Webots'
        reference manual has ``wb_supervisor_node_get_from_def`` use dots "as scoping operator
        in the DEF parameter"; None when a name is empty or not found."""
        if not all(names):
            return None
        node = self.getFromDef(names[0])
        for name in names[1:]:
            if node is None:
                return None
            node = _inside_named(node, name)
        return node

    def getFromId(self, id: int) -> Node | None:
        """The node of that id (the root, a top-level node, a node inside a grouping node, a DEF
        node asked for before), or None."""
        for node in [self._root, *self._root._children, *self._nested_nodes, *self._nodes.values()]:
            if node.getId() == id:
                return node
        return None

    def getFromDevice(self, device: Any) -> Node | None:
        """The robot's node stands for its devices: None (devices have no nodes here)."""
        return None

    def getSelected(self) -> None:
        """None: nothing is selected in a headless run."""
        return None

    def simulationQuit(self, status: int) -> None:
        """Ends the run: the next ``step`` returns -1; ``mazesim webots run`` exits with
        ``status``."""
        self._simulation.quit_status = int(status)

    def simulationReset(self) -> None:
        """Asks for the world to be put back as its file has it, as Webots' reset does, at the
        end of the next step: every robot at its start, every wall a supervisor moved and every
        movable body at its start, all at rest, and the nodes' ``translation`` and ``rotation``
        fields as the file gives them. As in Webots, every robot's clock (``getTime``, 0 after
        that step) and wheel position sensors start again from the reset, its motors are back at
        the world file's position control (the joint's position, at ``maxVelocity``), the noise
        streams start again from their seeds, the Emitter and Receiver queues are
        emptied and the controllers go on."""
        self._simulation.request_reset()

    def _restore_file_poses(self) -> None:
        """The nodes' ``translation`` and ``rotation`` fields as the file gives them, and the
        imported nodes out of the tree, as Webots' reset takes them out (the world's reset has
        reached this robot)."""
        edits = self._simulation.scene_edits
        if edits is not None:
            if self._simulation.fleet is not None:  # the world's process changed the world
                edits.take_out_imports(apply=False)
            first = edits.file_lines + 1
            listed = [*self._root._children, *self._nested_nodes]
            imported = [n for n in listed if n._line >= first and not n._robot]
            gone = {*imported, *(n for n in self._nested_nodes for i in imported if _inside(n, i))}
            for node in imported:
                _detach(node)
            self._nested_nodes = [n for n in self._nested_nodes if n not in gone]
            self._file_nodes = [n for n in self._file_nodes if n not in gone]
            self._imports.clear()
        for node in [*self._file_nodes, *self._nodes.values()]:
            node._translation, node._rotation = node._file_pose

    def simulationResetPhysics(self) -> None:
        """Stops the motion of the robot (its wheels' speeds still apply at the next step) and
        of every movable body."""
        self._simulation.velocity = (0.0, 0.0, 0.0)
        objects = world_objects(self._simulation)
        for index in range(len(objects.body_poses())):
            objects.set_body_velocity(index, 0.0, 0.0, 0.0)

    def simulationPhysicsReset(self) -> None:
        """Webots 8's name of :meth:`simulationResetPhysics` (the C library's
        ``wb_supervisor_simulation_physics_reset``)."""
        self.simulationResetPhysics()

    def simulationRevert(self) -> None:
        """Webots 8's name of :meth:`worldReload` (the C library's
        ``wb_supervisor_simulation_revert``)."""
        self.worldReload()

    def simulationGetMode(self) -> int:
        """The mode set last (fast by default: a headless run runs as fast as it can)."""
        return self._mode

    def simulationSetMode(self, mode: int) -> None:
        """Sets the mode; a headless run runs as fast as it can in the real-time and fast
        modes. In the pause mode, as in Webots, ``step(0)`` returns at once without advancing
        and a ``step`` of a longer duration waits for the simulation to be resumed, which
        nothing does in a headless run: the run ends there (the step returns -1, as when Webots
        is closed while paused), with exit status 0."""
        self._mode = int(mode)
        self._simulation.paused = self._mode == self.SIMULATION_MODE_PAUSE

    def setLabel(self, *args: Any) -> None:
        """Accepted; there is no 3D view to draw labels on."""

    def worldReload(self) -> None:
        """Reloads the world, as Webots does: in a run of the whole world, before the next step
        the world is put back as its file has it (as :meth:`simulationReset` puts it, with the
        ``controller`` and ``customData`` fields a supervisor wrote back at the file's values)
        and every controller, this one too, is ended (its next ``step`` returns -1) and started
        again, on a clock back at 0. In a run of one controller, it resets the simulation and
        the controller goes on."""
        fleet = self._simulation.fleet
        if fleet is not None:
            fleet.reload_world()
        else:
            self.simulationReset()

    def worldLoad(self, filename: str) -> None:
        """Loads a world, as far as a run of one world can: the world being run (its own file,
        by any path) is reloaded as :meth:`worldReload` reloads it; for another world the run
        ends here, as every controller of the world ends in Webots when it opens another (this
        one's next ``step`` returns -1), with a line saying so and how to run that world
        (``mazesim webots run``, each world its own run). A name without ``.wbt`` or a file
        that is not there is refused with Webots' kind of error, and the run goes on."""
        wanted = Path(str(filename))
        if wanted.suffix != ".wbt" or not wanted.is_file():
            _print_error(
                f"Error: wb_supervisor_world_load(): '{_shortened(str(filename))}' is not a "
                ".wbt world file that exists; the world goes on."
            )
            return
        own = self._simulation.report.get("path") if self._simulation.report else None
        if own is not None and wanted.resolve() == Path(str(own)).resolve():
            self.worldReload()
            return
        _print_error(
            f"mazesim: Supervisor.worldLoad('{_shortened(str(filename))}'): a run simulates one "
            "world, so it ends here, where Webots would open that world and start its "
            f"controllers (run it on its own: mazesim webots run {_shortened(str(wanted))})."
        )
        self._simulation.quit_status = 0

    def worldSave(self, filename: str | None = None) -> bool:
        """Writes the world as it stands to ``filename`` (a ``.wbt`` path, relative to the
        controller's folder; without one, the world's own file, as Webots saves it): the world
        file's text as the supervisor changed it (imports and removals), with every node's
        ``translation`` and ``rotation`` fields where the scene tree has them now (a robot's
        where it is, in its parent's frame). True once written; False, with Webots' error, for
        a name without ``.wbt``, a file that cannot be written, or a run whose world is no
        Webots world file."""
        if filename is not None and not str(filename).endswith(".wbt"):
            _print_error(
                'Error: wb_supervisor_world_save(): the target file should end with the ".wbt" '
                "extension."
            )
            return False
        try:
            text = scene_edits(self._simulation).text()
        except MazesimError as refused:
            _print_error(f"Error: wb_supervisor_world_save(): {refused}.")
            return False
        nodes = [self._self, *self._root._children, *self._nested_nodes]
        for node in dict.fromkeys(nodes):
            types = node._field_types()
            posed = {n: types[n] for n in ("translation", "rotation") if n in types}
            if node._line and posed:
                fields: dict[str, list[float]] = {
                    name: Field(node, name, kind).value for name, kind in posed.items()
                }
                text = with_fields(text, node._line, fields)
        target = filename if filename is not None else str(self._simulation.report["path"])
        try:
            # Atomic, as every file mazesim writes: a reader (Webots, a second save) sees the old
            # world file or the new one whole.
            with atomic_file(target) as out:
                out.write(text.encode("utf-8"))
        except MazesimError as failed:
            reason = getattr(failed, "strerror", None) or failed
            _print_error(f"Error: wb_supervisor_world_save(): cannot write {target}: {reason}.")
            return False
        return True

    def exportImage(self, filename: str, quality: int) -> None:
        """Writes the view of the world now to ``filename`` (relative to the controller's
        folder), a PNG or, at ``quality`` (1 to 100), a JPEG by its extension: the top-down
        frame that ``--video`` draws (:mod:`mazesim.webots.view_export`). Another extension,
        a quality out of range or a file that cannot be written is refused with Webots' kind
        of error, and nothing is written."""
        from mazesim.webots.view_export import export_view

        refused = export_view(self._simulation, str(filename), quality)
        if refused is not None:
            _print_error(refused)

    def step(self, time_step: float | None = None) -> int:
        """:meth:`Robot.step <mazesim.webots.robot.Robot.step>`, and a frame of the movie
        being recorded (:meth:`movieStartRecording`) after it."""
        result = super().step(time_step)
        self._movie.frame()
        return result

    def movieStartRecording(
        self,
        filename: str,
        width: int,
        height: int,
        codec: int,
        quality: int,
        acceleration: int,
        caption: bool,
    ) -> None:
        """Starts recording a movie of the simulation into ``filename`` (relative to the
        controller's folder): the top-down view of each step, as :mod:`mazesim.webots.movie`
        says; a second start, an empty name, a size, ``quality`` (1 to 100) or
        ``acceleration`` (1 or more) out of range is refused with Webots' error."""
        self._movie.start(filename, width, height, quality, acceleration)

    def movieStopRecording(self) -> None:
        """Stops the movie and writes its file."""
        self._movie.stop()

    def movieIsReady(self) -> bool:
        """True unless a movie is being recorded (before a start, and once a stop wrote it)."""
        return self._movie.ready

    def movieFailed(self) -> bool:
        """Whether the last movie could not be written."""
        return self._movie.failed

    def virtualRealityHeadsetIsUsed(self) -> bool:
        """False."""
        return False


def _inside_named(node: Node, name: str) -> Node | None:
    """The first node of DEF ``name`` inside ``node`` (in its ``children`` and its single-node
    fields, depth first, in file order), or None."""
    pending = [*node._children, *node._field_nodes.values()][::-1]
    while pending:
        inner = pending.pop()
        if inner._def == name:
            return inner
        pending.extend([*inner._children, *inner._field_nodes.values()][::-1])
    return None
