"""Webots' ``Field``: one field of a node a supervisor reads and sets.

A field reads by its own type (a translation, an axis-angle rotation, a name or ``customData``
string, the nodes of a ``children`` field, the node of an SFNode field) through the node that
holds it (:class:`~mazesim.webots.supervisor.Node`); setting a robot's or a movable body's
``translation`` or ``rotation`` moves it in the simulation. Nodes are imported into a
``children`` or an empty ``endPoint`` field and removed from them
(:mod:`mazesim.webots.scene_edits`); another such change prints Webots' kind of error and
changes nothing. Positions are read
and written in the world file's frame (Webots' old NUE frame for worlds before R2022a).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from mazesim._paths import read_input
from mazesim.errors import (
    InvalidArgumentError,
    MazesimError,
    MazesimIOError,
    WrongTypeError,
    _a_type,
    _shown,
)
from mazesim.webots import simulation as _simulations
from mazesim.webots.devices import _print_error
from mazesim.webots.frames import (
    axis_angle,
    enu_to_nue,
    heading_of,
    nue_to_enu,
    rotation_matrix,
    turned,
)
from mazesim.webots.importer import MAX_WORLD_BYTES
from mazesim.webots.list_fields import LIST_TYPES, ListFieldValues
from mazesim.webots.webots_api import NotSimulated, webots_property

if TYPE_CHECKING:
    from mazesim.webots.supervisor import Node

__all__ = ["Field"]


def _refuse_scene_change(call: str) -> None:
    """Prints the refusal of a call that would add a node to the running world or remove one
    elsewhere than in the scene tree root's ``children`` (as Webots prints the error of a call
    it cannot carry out, and the controller goes on)."""
    _print_error(
        f"Error: {call} is not supported by mazesim: a supervisor imports nodes into a "
        "children field or an empty endPoint field and removes top-level or imported nodes, "
        "not elsewhere; nothing changed."
    )


def _file_frame() -> bool:
    """Whether the world file is in Webots' old NUE frame: a supervisor then reads and writes
    positions, rotations and velocities in it, as the file writes them (Webots before R2022a
    did), and mazesim converts them as the importer converts the world."""
    return _simulations.current().scene.nue


def _out(vector: list[float]) -> list[float]:
    """A world-frame (ENU) vector as the supervisor reports it."""
    return list(enu_to_nue(*vector[:3])) if len(vector) == 3 and _file_frame() else vector


def _in(vector: list[float]) -> list[float]:
    """A vector the supervisor was given, in the world frame (ENU)."""
    return list(nue_to_enu(*vector[:3])) if _file_frame() else vector


class Field(ListFieldValues, NotSimulated):
    """A field of a node: the robot's ``translation``, ``rotation``, ``name``, ``customData``."""

    SF_BOOL = 0x01
    SF_INT32 = 0x02
    SF_FLOAT = 0x03
    SF_VEC2F = 0x04
    SF_VEC3F = 0x05
    SF_ROTATION = 0x06
    SF_COLOR = 0x07
    SF_STRING = 0x08
    SF_NODE = 0x09
    MF = 0x10
    MF_BOOL = 0x11
    MF_INT32 = 0x12
    MF_FLOAT = 0x13
    MF_VEC2F = 0x14
    MF_VEC3F = 0x15
    MF_ROTATION = 0x16
    MF_COLOR = 0x17
    MF_STRING = 0x18
    MF_NODE = 0x19
    _type_names = {
        0x01: "SFBool",
        0x02: "SFInt32",
        0x03: "SFFloat",
        0x04: "SFVec2f",
        0x05: "SFVec3f",
        0x06: "SFRotation",
        0x07: "SFColor",
        0x08: "SFString",
        0x09: "SFNode",
        0x19: "MFNode",
        **{number: kind for kind, (number, _) in LIST_TYPES.items()},
    }

    def __init__(self, node: Node, name: str, field_type: int) -> None:
        self._node = node
        self._name = name
        self._type = field_type

    def getName(self) -> str:
        """The field's name."""
        return self._name

    def getType(self) -> int:
        """The field's type (``Field.SF_VEC3F``...)."""
        return self._type

    type = webots_property("getType")

    def getTypeName(self) -> str:
        """The field's type name (``"SFVec3f"``...)."""
        return self._type_names[self._type]

    def getCount(self) -> int:
        """-1 for a single field; the number of nodes of a ``children`` field, or of items of
        a list field of values."""
        if self._type == self.MF_NODE:
            return len(self._node._children)
        return len(self._node._lists[self._name]) if self._name in self._node._lists else -1

    def getMFNode(self, index: int) -> Node | None:
        """The node at ``index`` of a ``children`` field (the root's, or a Solid's, Transform's,
        Pose's or Group's; negative: from the end, as in Webots), or None with Webots' error."""
        if self._type != self.MF_NODE:
            self._wrong("get_mf_node")
            return None
        children = self._node._children
        if not -len(children) <= int(index) < len(children):
            _print_error(
                f"Error: wb_supervisor_field_get_mf_node() called with an out of range index: "
                f"{index}."
            )
            return None
        return children[int(index)]

    def getSFNode(self) -> Node | None:
        """The node a field of one node holds (a Shape's ``geometry`` or ``appearance``, an
        Appearance's ``material``), or None with Webots' error for another field."""
        if self._type != self.SF_NODE:
            self._wrong("get_sf_node")
            return None
        return self._node._field_nodes.get(self._name)

    def importMFNodeFromString(self, position: int, nodeString: str) -> None:
        """Imports the nodes of ``nodeString`` into the running world at ``position`` of a
        ``children`` field (-1: at the end): the root's, or a Solid's, Pose's, Transform's or
        Group's that does not move in the simulation, whose frame places them, as the world
        file's nodes are imported; the robot meets them from the next step on
        (:mod:`mazesim.webots.scene_edits`). Webots' kind of error, nothing changed, for
        another field or nodes mazesim does not add in a run."""
        tree = self._tree("importMFNodeFromString")
        if tree is not None:
            tree._import_nodes(position, str(nodeString), "importMFNodeFromString()", self._into)

    def importSFNodeFromString(self, nodeString: str) -> None:
        """Imports the node of ``nodeString`` into an empty ``endPoint`` field (a ``Slot``'s or
        a joint's), placed in the frame of the node that holds the field, as
        :meth:`importMFNodeFromString` does; Webots' kind of error for another field."""
        tree = self._tree("importSFNodeFromString", single=True)
        if tree is not None:
            tree._import_nodes(0, str(nodeString), "importSFNodeFromString()", self._into)

    def importMFNode(self, position: int, filename: str) -> None:
        """Imports the nodes of a ``.wbo`` file as :meth:`importMFNodeFromString` does (an
        older name)."""
        self._import_file(position, filename, "importMFNode")

    def _import_file(self, position: int, filename: str, call: str, single: bool = False) -> None:
        """Imports the nodes of a ``.wbo`` file, as ``call`` (``importMFNode``...) does."""
        tree = self._tree(call, single)
        if tree is None:
            return
        try:
            # The one bounded reader of input files: a FIFO, a device or an endless file is
            # refused, not waited on or read until the memory runs out.
            data = read_input(filename, MAX_WORLD_BYTES, "a .wbo file")
            if len(data) > MAX_WORLD_BYTES:
                raise MazesimIOError(f"expected at most {MAX_WORLD_BYTES} bytes, found more")
        except (MazesimError, OSError) as failure:
            _print_error(f"Error: {call}(): cannot read '{filename}': {failure}.")
            return
        text = data.decode("utf-8", "replace")
        tree._import_nodes(position, text, f"{call}()", self._into)

    def importSFNode(self, filename: str) -> None:
        """Imports the node of a ``.wbo`` file as :meth:`importSFNodeFromString` does."""
        self._import_file(0, filename, "importSFNode", single=True)

    def removeMF(self, index: int) -> None:
        """Removes the node at ``index`` of a ``children`` field from the running world, as
        ``Node.remove()`` does, or the item at ``index`` of a list field of values; Webots'
        kind of error for another field."""
        if self._type != self.MF_NODE and self._name in self._node._lists:
            self._remove_item(index)
            return
        tree = self._tree("removeMF")
        if tree is None:
            return
        node = self.getMFNode(index)
        if node is not None:
            tree._remove_node(node, "wb_supervisor_field_remove_mf()")

    def removeSF(self) -> None:
        """Removes the node of an ``endPoint`` field from the running world, as
        ``Node.remove()`` does; Webots' kind of error for another field."""
        tree = self._tree("removeSF", single=True)
        node = self._node._field_nodes.get(self._name) if tree is not None else None
        if tree is not None and node is None:
            _print_error("Error: wb_supervisor_field_remove_sf() called with an empty field.")
        elif tree is not None and node is not None:
            tree._remove_node(node, "wb_supervisor_field_remove_sf()")

    @property
    def _into(self) -> tuple[Node, str] | None:
        """The node and field nodes are imported into (None: the root's ``children``)."""
        return None if self._node._id == 0 else (self._node, self._name)

    def _tree(self, call: str, single: bool = False) -> Any:
        """The supervisor whose scene tree holds the field, when nodes can be imported into it
        by ``call`` (a ``children`` field, or an ``endPoint`` field for a call on ``single``
        fields), or None after printing the refusal of ``call`` on another field."""
        root = self._node
        while root._parent is not None:
            root = root._parent
        name, wanted = ("endPoint", self.SF_NODE) if single else ("children", self.MF_NODE)
        fits = self._name == name and self._type == wanted
        tree = root._tree if fits else None
        if tree is None:
            _refuse_scene_change(f"Field.{call}() on {self._where()}")
        return tree

    def _where(self) -> str:
        """The field and its node, as a refusal names them."""
        return f"field '{self._name}' of {self._node._label()}"

    def _wrong(self, function: str) -> None:
        _print_error(
            f"Error: wb_supervisor_field_{function}() called with a field of type "
            f"{self.getTypeName()}."
        )

    def c_sf_vec3f(self) -> list[float] | None:
        """The node's translation [x, y, z] in metres (in its parent's frame; a robot's and a
        movable body's are live), or another field of three numbers as the world file gives
        it."""
        if self._name != "translation":
            return self._numbers("get_sf_vec3f", (self.SF_VEC3F, self.SF_COLOR))
        node = self._node
        if node._live:
            x, y, _ = node._field_pose()
            return _out([x, y, node._field_height()])
        return _out(list(node._translation or ()))

    def setSFVec3f(self, values: list[float]) -> None:
        """Moves the robot, or what the node holds, to [x, y, z] (z is ignored for an e-puck and
        a movable body: they stay on the floor; a robot mazesim does not simulate keeps it);
        another node's translation is recorded, and so is another field of three numbers (a
        light's ``location``, a ``scale``): it reads back as set."""
        vector = field_value(values, 3, "Field.setSFVec3f")
        if self._name != "translation":
            self._set_numbers("set_sf_vec3f", (self.SF_VEC3F, self.SF_COLOR), vector)
            return
        node = self._node
        x, y, z = _in(vector)
        if node._live:
            node._set_field_pose(x, y, node._field_pose()[2])
            node._set_field_height(z)
        else:
            node._place(translation=(x, y, z))
            node._tell_field("translation", [float(v) for v in vector])

    def c_sf_rotation(self) -> list[float] | None:
        """The node's rotation as axis and angle (the robot's is live: [0, 0, 1, yaw], the yaw in
        (-pi, pi], so that a half turn set reads back as the half turn, not as -pi; a robot
        stood upright by its ``rotation`` reads ``Rz(yaw) T``, T its body's turn)."""
        if self._name != "rotation":
            self._wrong("get_sf_rotation")
            return None
        node = self._node
        live = None
        if node._live:
            yaw = _half_open(node._field_pose()[2])
            turn = node._body_turn()
            live = [0.0, 0.0, 1.0, yaw] if turn is None else list(axis_angle(turned(yaw, turn)))
        rotation = live or list(node._rotation or ())
        return [*_out(rotation[:3]), rotation[3]] if rotation else rotation

    def setSFRotation(self, values: list[float]) -> None:
        """Turns the robot, or what the node holds, to an axis-angle rotation (its yaw about z is
        kept); another node's rotation is recorded."""
        rotation = field_value(values, 4, "Field.setSFRotation")
        if self._name != "rotation":
            self._wrong("set_sf_rotation")
            return
        node = self._node
        ax, ay, az, angle = rotation
        ax, ay, az = _in([ax, ay, az])
        if node._live:
            x, y, _ = node._field_pose()
            yaw = heading_of(rotation_matrix(ax, ay, az, angle), node._body_turn())
            node._set_field_pose(x, y, yaw)
        else:
            node._place(rotation=(ax, ay, az, angle))
            node._tell_field("rotation", [float(v) for v in rotation])

    def _numbers(self, function: str, types: tuple[int, ...]) -> list[float] | None:
        if self._type not in types or self._name not in self._node._numbers:
            self._wrong(function)
            return None
        return list(self._node._numbers[self._name])

    def c_sf_int32(self) -> int | None:
        """The value of an integer field the world file gives (a PROTO's ``channel 2``)."""
        values = self._numbers("get_sf_int32", (self.SF_INT32,))
        return None if values is None else int(values[0])

    def c_sf_float(self) -> float | None:
        """The value of a number field the world file gives."""
        values = self._numbers("get_sf_float", (self.SF_FLOAT, self.SF_INT32))
        return None if values is None else values[0]

    def c_sf_bool(self) -> bool | None:
        """The value of a ``TRUE`` / ``FALSE`` field the world file gives."""
        if self._type != self.SF_BOOL:
            self._wrong("get_sf_bool")
            return None
        return self._node._flags.get(self._name, False)

    def c_sf_vec2f(self) -> list[float] | None:
        """The value of a field of two numbers the world file gives."""
        return self._numbers("get_sf_vec2f", (self.SF_VEC2F,))

    def c_sf_color(self) -> list[float] | None:
        """The value of a colour field the world file gives."""
        # The file does not say whether three numbers are a colour or a vector: both read.
        return self._numbers("get_sf_color", (self.SF_COLOR, self.SF_VEC3F))

    def _set_numbers(self, function: str, types: tuple[int, ...], values: list[float]) -> None:
        if self._type not in types or self._name not in self._node._numbers:
            self._wrong(function)
            return
        self._node._numbers[self._name] = [float(v) for v in values]
        self._node._tell_field(self._name, list(self._node._numbers[self._name]))

    def setSFInt32(self, value: int) -> None:
        """Records a new value of an integer field."""
        self._set_numbers(
            "set_sf_int32", (self.SF_INT32,), field_value(value, 0, "Field.setSFInt32")
        )

    def setSFFloat(self, value: float) -> None:
        """Records a new value of a number field."""
        self._set_numbers(
            "set_sf_float",
            (self.SF_FLOAT, self.SF_INT32),
            field_value(value, 1, "Field.setSFFloat"),
        )

    def setSFColor(self, values: list[float]) -> None:
        """Records a new value of a colour field (a Material's ``diffuseColor``: the rendering
        does not change)."""
        self._set_numbers(
            "set_sf_color",
            (self.SF_COLOR, self.SF_VEC3F),
            field_value(values, 3, "Field.setSFColor"),
        )

    def setSFBool(self, value: bool) -> None:
        """Records a new value of a ``TRUE`` / ``FALSE`` field."""
        flag = field_value(value, -1, "Field.setSFBool")
        if self._type != self.SF_BOOL:
            self._wrong("set_sf_bool")
            return
        self._node._flags[self._name] = bool(flag)
        self._node._tell_field(self._name, bool(flag))

    def c_sf_string(self) -> str | None:
        """The value of a string field (``name``, ``customData``, ``controller``)."""
        if self._type != self.SF_STRING:
            self._wrong("get_sf_string")
            return None
        return self._node._string(self._name)

    def setSFString(self, value: str) -> None:
        """Sets a string field (a robot's ``customData`` is what its controller's
        ``getCustomData`` reads; another robot's ``controller``, in a world run, ends its
        controller and starts the one named, as Webots does)."""
        text = field_value(value, -2, "Field.setSFString")
        if self._type != self.SF_STRING:
            self._wrong("set_sf_string")
            return
        self._node._strings[self._name] = text
        if self._name == "customData":
            self._node._tell_custom_data(text)
        elif self._name == "controller":
            self._node._tell_controller(text)

    @property
    def value(self) -> Any:
        """The field's value, read by the field's own type (a node for an SFNode field, None for
        a multiple field), as Webots' Python ``Field.value`` reads it."""
        if self._type == self.SF_VEC3F:
            return self.c_sf_vec3f()
        if self._type == self.SF_ROTATION and self._name == "rotation":
            return self.c_sf_rotation()
        if self._type == self.SF_NODE:
            return self.getSFNode()
        if self._type & self.MF:
            return None
        getters = {
            self.SF_INT32: self.c_sf_int32,
            self.SF_FLOAT: self.c_sf_float,
            self.SF_BOOL: self.c_sf_bool,
            self.SF_VEC2F: self.c_sf_vec2f,
            self.SF_COLOR: self.c_sf_color,
            self.SF_ROTATION: lambda: self._numbers("get_sf_rotation", (self.SF_ROTATION,)),
        }
        if self._type in getters:
            return getters[self._type]()
        return self.c_sf_string()

    @value.setter
    def value(self, value: Any) -> None:
        setters: dict[int, Callable[[Any], None]] = {
            self.SF_VEC3F: self.setSFVec3f,
            self.SF_ROTATION: self.setSFRotation,
            self.SF_INT32: self.setSFInt32,
            self.SF_FLOAT: self.setSFFloat,
            self.SF_BOOL: self.setSFBool,
            self.SF_COLOR: self.setSFColor,
        }
        setters.get(self._type, self.setSFString)(value)

    # Webots' Python API (its ctypes ``Field``, since R2023b) gives every single-value getter
    # as ``return self.value``: it reads the field by its own type whatever the getter's name
    # (``getSFVec3f()`` of a rotation field is its four numbers); the C API's typed functions
    # (``c_sf_*`` above, which compiled controllers call) print Webots' error and give NULL.
    def getSFBool(self) -> Any:
        """The field's value, read by its own type (see :attr:`value`)."""
        return self.value

    def getSFInt32(self) -> Any:
        """The field's value, read by its own type (see :attr:`value`)."""
        return self.value

    def getSFFloat(self) -> Any:
        """The field's value, read by its own type (see :attr:`value`)."""
        return self.value

    def getSFVec2f(self) -> Any:
        """The field's value, read by its own type (see :attr:`value`)."""
        return self.value

    def getSFVec3f(self) -> Any:
        """The field's value, read by its own type (see :attr:`value`): a translation in
        metres (a robot's and a movable body's are live)."""
        return self.value

    def getSFRotation(self) -> Any:
        """The field's value, read by its own type (see :attr:`value`): a rotation as axis and
        angle (the robot's is live: [0, 0, 1, yaw], or ``Rz(yaw) T`` for a robot stood upright
        by its ``rotation``, :func:`~mazesim.webots.frames.body_turn`)."""
        return self.value

    def getSFColor(self) -> Any:
        """The field's value, read by its own type (see :attr:`value`)."""
        return self.value

    def getSFString(self) -> Any:
        """The field's value, read by its own type (see :attr:`value`): ``name``,
        ``customData``, ``controller``..."""
        return self.value


#: The largest magnitude of a number a field is set to: a position, an angle or a colour beyond
#: it is no place in a world within mazesim's limits (``docs/reliability.md#input-limits``).
LARGEST_FIELD_NUMBER = 1e9
#: What each kind of value a field setter takes is, for its message (by ``count``).
_KINDS = {-2: "a str", -1: "a bool", 0: "an int of 32 bits", 1: "a finite number"}


def field_value(value: Any, count: int, function: str) -> Any:
    """The value a field setter ``function`` (``"Field.setSFVec3f"``) was given, checked
    against what the field holds: the one check of every setter of :class:`Field`. ``count``
    says what it takes: -2 a text, -1 a bool, 0 an integer of 32 bits, 1 a number, else a list,
    tuple or numpy array (Webots' SWIG API, to R2022b, read any sequence) of at most
    ``count`` finite numbers, of which missing ones are 0 as in Webots' Python API, which
    copies the list into a C array of ``count`` doubles (``setSFRotation([0, 0, -1])`` is the
    rotation by angle 0): more values than the field holds, another kind of value, a NaN or a
    number beyond :data:`LARGEST_FIELD_NUMBER` is refused, where Webots raises, instead of
    being dropped or put into the world.

    Raises:
        WrongTypeError: A value of another kind.
        InvalidArgumentError: Too many numbers, or one not finite or too large.
    """
    where = f"{function}()"
    if count == -2:
        if not isinstance(value, str):
            raise WrongTypeError(f"{where}: expected {_KINDS[count]}, found {_a_type(value)}")
        return value
    if count == -1:
        if not isinstance(value, (bool, int)):
            raise WrongTypeError(f"{where}: expected {_KINDS[count]}, found {_a_type(value)}")
        return bool(value)
    if count in (0, 1):
        numbers = [_field_number(value, where, integer=count == 0)]
        if count == 0 and not -(2**31) <= numbers[0] < 2**31:
            raise InvalidArgumentError(
                f"{where}: expected {_KINDS[0]}, found {_shown(value)}; give a value that fits "
                "32 bits"
            )
        return numbers
    if hasattr(value, "tolist") and not isinstance(value, (list, tuple)):
        # A numpy array of the field's numbers: Webots' SWIG API (to R2022b) read any sequence.
        listed = value.tolist()
        value = listed if isinstance(listed, list) else value
    if not isinstance(value, (list, tuple)):
        raise WrongTypeError(f"{where}: expected a list of {count} numbers, found {_a_type(value)}")
    if len(value) > count:
        raise InvalidArgumentError(
            f"{where}: expected a list of {count} numbers, found {len(value)}; "
            f"give the field's {count} values"
        )
    numbers = [_field_number(v, where, integer=False) for v in value]
    return numbers + [0.0] * (count - len(numbers))


def _field_number(value: Any, where: str, integer: bool) -> Any:
    """One number of a field's value, as an int or a float (see :func:`field_value`)."""
    kind = "an int" if integer else "a number"
    if isinstance(value, (str, bytes)) or not isinstance(value, (int, float, np.number)):
        raise WrongTypeError(f"{where}: expected {kind}, found {_a_type(value)}")
    if integer:
        if not float(value).is_integer():
            raise InvalidArgumentError(f"{where}: expected {kind}, found {_shown(value)}")
        return int(value)
    number = float(value)
    if not math.isfinite(number) or abs(number) > LARGEST_FIELD_NUMBER:
        raise InvalidArgumentError(
            f"{where}: expected finite numbers of at most {LARGEST_FIELD_NUMBER:g} in "
            f"magnitude, found {_shown(value)}"
        )
    return number


#: How far below -pi a yaw may be and still be read as the half turn pi: the simulator keeps
#: headings in single precision, whose step near pi is 2.4e-7.
_HALF_TURN_TOLERANCE = 1e-6


def _half_open(yaw: float) -> float:
    """``yaw`` wrapped into (-pi, pi], a heading within single precision of -pi read as pi."""
    wrapped = math.remainder(yaw, math.tau)
    return wrapped + math.tau if wrapped <= -math.pi + _HALF_TURN_TOLERANCE else wrapped


def _yaw_of_rotation(rotation: list[float]) -> float:
    """The heading (rad) of an axis-angle rotation: the angle of its image of the x axis."""
    ax, ay, az, angle = (rotation + [0.0, 0.0, 1.0, 0.0][len(rotation) :])[:4]
    return heading_of(rotation_matrix(ax, ay, az, angle))
