"""A two-wheeled robot of its own build: the wheels, axle and body its node gives.

Webots' tutorials build a differential-drive robot by hand: a plain ``Robot`` whose children
hold two ``HingeJoint`` nodes, each turning a wheel (its ``endPoint`` Solid, whose
``boundingObject`` rolls on the floor) by a ``RotationalMotor`` named as the author likes
(``motor_1``, ``left_motor``, or the E-puck's ``left wheel motor`` as Webots' MyBot), beside a
body of the author's size. The import takes such a robot for the one it simulates (the core's
``Importer::two_wheeled``: exactly two motors, each a hinge's, about parallel axes, the wheels
apart), its model its node type unless its name, its model or a ``ps0`` says it is an e-puck;
:func:`own_drive` reads what its node
makes of the drive, and :func:`drive_layout` writes it into the e-puck's profile, so the robot
rolls as its own wheels roll it in Webots:

- its wheel radius, the radius of each wheel's ``boundingObject`` (a ``Cylinder`` or
  ``Sphere``, under ``Pose``, ``Transform``, ``Group`` or ``Shape`` nodes and ``USE``\\ s), else
  the height of the wheel (its end point, else its hinge's anchor) above the robot's origin (a
  robot standing on its origin);
- its axle length, how far apart the two wheels sit across the robot (their end points'
  translations, else their hinges' anchors: Webots' MyBot puts both anchors on the axle's
  midpoint);
- which wheel is the left one (the one further along the robot's y, its left), whatever the
  motors' names; a wheel turning by a positive speed about its axis ``a`` rolls the robot along
  ``a x up``, forward for an axis pointing left (``0 1 0``, as the E-puck's);
- its body's radius: the farthest its own ``boundingObject`` reaches across the floor from its
  origin (a ``Cylinder``'s or ``Sphere``'s radius, a ``Box``'s half diagonal, plus their
  offset), as mazesim's robot is a disc;
- its wheels' top speed, the lower of the two motors' ``maxVelocity`` (Webots' default 10
  rad/s), past which Webots holds a speed set.

A robot whose wheels are the E-puck's (2 cm, 5.2 cm apart, within 4 mm: an e-puck saved
expanded, or one built by hand to its size) keeps the e-puck profile as it is, whose numbers
are measured on Webots' E-puck. What the disc and the two wheels leave out is said: a body
other than a cylinder or sphere, an axle's midpoint off the robot's origin (mazesim turns the
robot about its origin), wheels of different radii (both roll by their mean).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from mazesim.errors import _shown
from mazesim.webots.frames import WORLD_FRAME, Frame, nue_to_enu, placed
from mazesim.webots.proto.syntax import Field, Node, first_value, nodes_in_order

__all__ = ["OwnDrive", "drive_layout", "own_drive", "resting_height"]

#: Webots' ``RotationalMotor.maxVelocity`` where the node writes none (rad/s).
DEFAULT_MAX_VELOCITY = 10.0
#: How closely (cosine) a wheel's rolling direction must follow the robot's forward axis for
#: its two hinges to be a differential drive.
ACROSS_THE_ROBOT = 0.9
#: How far (m) the axle's midpoint may sit from the robot's origin, or the two wheels' radii
#: differ, before a warning says what the model leaves out.
SAME_PLACE_M = 1e-3
#: The E-puck PROTO's wheels: their radius and how far apart they sit (anchors at +-0.026 m).
EPUCK_WHEEL_RADIUS = 0.02
EPUCK_WHEEL_SPAN = 0.052
#: How far (m) a robot's wheel radius and wheel span may be from the E-puck's for its wheels to
#: be the E-puck's (an e-puck saved expanded, which the e-puck profile simulates as it is).
EPUCK_LIKE_M = 0.004
#: The node types whose ``children`` a hand-built robot's hinges may sit in, composing their
#: poses (as the import's test walks them).
_HOLDERS = {"Pose", "Transform", "Group", "Solid"}


@dataclass(frozen=True)
class OwnDrive:
    """What a two-wheeled robot's node makes of its drive.

    Attributes:
        motors: The names of its left and right wheels' ``RotationalMotor`` nodes.
        sensors: The names of the ``PositionSensor`` nodes beside them in their hinges'
            ``device`` fields (left, right), None where a hinge has none.
        wheel_radius: The wheels' radius (m; their mean when they differ).
        axle_length: The distance between the two wheels' anchors across the robot (m).
        body_radius: The radius of the disc its own ``boundingObject`` fills on the floor (m),
            None when its node has none.
        max_velocity: The wheels' top speed (rad/s).
        warnings: What of the node the two wheels and the disc leave out, one line each.
    """

    motors: tuple[str, str]
    sensors: tuple[str | None, str | None]
    wheel_radius: float
    axle_length: float
    body_radius: float | None
    max_velocity: float
    warnings: list[str] = field(default_factory=list)


@dataclass(frozen=True)
class _Wheel:
    """One hinge of the drive, in the robot's frame."""

    motor: str
    sensor: str | None
    anchor: tuple[float, float, float]
    roll: tuple[float, float, float]
    radius: float | None
    max_velocity: float


def own_drive(robot: Node, y_up: bool) -> OwnDrive | str | None:
    """The drive of a plain robot node holding two wheels of its own (see the module); None
    when its node holds no two motors each turning a hinge of its own; and why its own wheels
    do not drive it (a sentence) when they are not a drive mazesim's robot rolls on: hinges
    whose axes do not point to the robot's left (a positive speed then does not roll it
    forward), anchors not apart across it, a wheel of no size. ``y_up``: the robot's inside is
    modelled Y-up (its frame turned to Z-up as :func:`~mazesim.webots.frames.nue_to_enu`
    turns it)."""
    resolve = _resolver(robot)
    motors = [n for n in nodes_in_order(f for item in robot.fields for f in item.nodes)]
    if sum(1 for n in motors if n.type_name == "RotationalMotor") != 2:
        return None
    wheels = _wheels(robot, y_up, resolve)
    if len(wheels) != 2:
        return None
    left, right = sorted(wheels, key=lambda wheel: -wheel.anchor[1])
    backward = [_shown(wheel.motor) for wheel in wheels if wheel.roll[0] < ACROSS_THE_ROBOT]
    if backward:
        return (
            f"the hinge axis of motor {' and '.join(backward)} does not point to the robot's "
            "left (0 1 0), so a positive speed does not roll it forward"
        )
    axle = abs(left.anchor[1] - right.anchor[1])
    if axle <= 0.0:
        return "its two wheels are not apart across it"
    warnings: list[str] = []
    radii = [wheel.radius if wheel.radius is not None else wheel.anchor[2] for wheel in wheels]
    if min(radii) <= 0.0:
        return "a wheel has no boundingObject and sits no higher than the robot's origin"
    if (
        abs(sum(radii) / 2 - EPUCK_WHEEL_RADIUS) <= EPUCK_LIKE_M
        and abs(axle - EPUCK_WHEEL_SPAN) <= EPUCK_LIKE_M
    ):
        # An e-puck saved expanded: the profile's numbers, measured on Webots' E-puck, stand.
        return None
    if abs(radii[0] - radii[1]) > SAME_PLACE_M:
        warnings.append(
            f"its wheels' radii differ ({radii[0]:.4f} and {radii[1]:.4f} m): both roll by "
            f"their mean, {sum(radii) / 2:.4f} m"
        )
    middle = ((left.anchor[0] + right.anchor[0]) / 2, (left.anchor[1] + right.anchor[1]) / 2)
    if math.hypot(*middle) > SAME_PLACE_M:
        warnings.append(
            f"its axle's midpoint sits at ({middle[0]:.4f}, {middle[1]:.4f}) m from its origin: "
            "mazesim turns it about its origin, Webots about the axle"
        )
    body, body_warning = _body_radius(robot, y_up, resolve)
    warnings += body_warning
    return OwnDrive(
        motors=(left.motor, right.motor),
        sensors=(left.sensor, right.sensor),
        wheel_radius=sum(radii) / 2,
        axle_length=axle,
        body_radius=body,
        max_velocity=min(left.max_velocity, right.max_velocity),
        warnings=warnings,
    )


def resting_height(robot: Node, y_up: bool) -> float:
    """How high a plain robot node's origin rests above the floor on its two wheels (m): each
    wheel's radius less its height above the origin, their mean (0 without two wheels, or for
    a wheel of no size: a robot standing on its origin). A plain Robot's origin is often its
    axle or its body's centre, so a sensor pointed at the floor is that much higher than its
    place in the robot says (a line follower's 7 mm sensor read as 0 mm: always black)."""
    wheels = _wheels(robot, y_up, _resolver(robot))
    if len(wheels) != 2:
        return 0.0
    heights = [
        (wheel.radius if wheel.radius is not None else wheel.anchor[2]) - wheel.anchor[2]
        for wheel in wheels
    ]
    return max(0.0, sum(heights) / 2)


def drive_layout(layout: dict[str, Any], drive: OwnDrive) -> None:
    """Writes a robot's own drive into a parsed profile file (the e-puck's): its wheel radius,
    axle length, body radius (where its node gives one) and wheels' top speed."""
    layout["wheel_radius"] = drive.wheel_radius
    layout["axle_length"] = drive.axle_length
    layout["max_wheel_speed"] = drive.max_velocity
    if drive.body_radius is not None:
        layout["body_radius"] = drive.body_radius
    layout["description"] = (
        f"a two-wheeled robot of its own build: wheels of {drive.wheel_radius:.4f} m on an "
        f"axle of {drive.axle_length:.4f} m"
    )


Resolve = Callable[[Node], Node]


def _resolver(robot: Node) -> Resolve:
    """The node a ``USE`` inside the robot stands for: the last node its name ``DEF``\\ s
    before it within the robot's node (itself for any other node)."""
    defined: dict[str, list[Node]] = {}
    for node in nodes_in_order(f for item in robot.fields for f in item.nodes):
        if node.def_name is not None and node.use_name is None:
            defined.setdefault(node.def_name, []).append(node)

    def resolve(node: Node) -> Node:
        if node.use_name is None:
            return node
        earlier = [d for d in defined.get(node.use_name, []) if d.end <= node.start]
        return max(earlier, key=lambda d: d.end) if earlier else node

    return resolve


def _vector(node: Node | None, name: str, default: tuple[float, ...]) -> tuple[float, ...]:
    """A field of ``len(default)`` numbers of a node, or ``default``."""
    if node is None:
        return default
    found = first_value([node], name, lambda f: f.numbers(len(default)))
    return tuple(found) if found is not None and len(found) == len(default) else default


def _turned(frame: Frame, vector: Sequence[float]) -> tuple[float, float, float]:
    """A direction given in ``frame`` as seen from the frame ``frame`` is placed in."""
    matrix = frame[1]
    x, y, z = (sum(matrix[3 * i + k] * vector[k] for k in range(3)) for i in range(3))
    return x, y, z


def _wheels(robot: Node, y_up: bool, resolve: Resolve) -> list[_Wheel]:
    """The hinges among the robot's own children (and those of its grouping children) whose
    ``device`` holds one ``RotationalMotor``, in the robot's Z-up frame."""
    wheels: list[_Wheel] = []
    pending = [(n, WORLD_FRAME) for n in _field_nodes(robot, "children")]
    pending.reverse()
    while pending:
        node, holder = pending.pop()
        node = resolve(node)
        if node.type_name == "HingeJoint":
            if (wheel := _wheel(node, holder, y_up, resolve)) is not None:
                wheels.append(wheel)
            continue
        if node.type_name in _HOLDERS:
            offset = _vector(node, "translation", (0.0, 0.0, 0.0))
            frame = placed(holder, offset, _vector(node, "rotation", (0.0, 0.0, 1.0, 0.0)))
            pending.extend(reversed([(n, frame) for n in _field_nodes(node, "children")]))
    return wheels


def _field_nodes(node: Node, name: str) -> list[Node]:
    """The nodes of one field of a node."""
    return [n for item in node.fields if item.name == name for n in item.nodes]


def _wheel(joint: Node, holder: Frame, y_up: bool, resolve: Resolve) -> _Wheel | None:
    """A hinge with one ``RotationalMotor`` as a wheel of the robot, None otherwise."""
    devices = [resolve(n) for n in _field_nodes(joint, "device")]
    motors = [n for n in devices if n.type_name == "RotationalMotor"]
    if len(motors) != 1:
        return None
    sensors = [n for n in devices if n.type_name == "PositionSensor"]
    parameters = next(iter(_field_nodes(joint, "jointParameters")), None)
    parameters = resolve(parameters) if parameters is not None else None
    axis = _turned(holder, _vector(parameters, "axis", (1.0, 0.0, 0.0)))
    end = next(iter(_field_nodes(joint, "endPoint")), None)
    end = resolve(end) if end is not None else None
    # Where the wheel sits: its end point's translation (two hinges may share one anchor on
    # the axle's line, as Webots' MyBot's do), else its anchor.
    written = _vector(end, "translation", (math.nan,) * 3)
    if any(math.isnan(v) for v in written):
        written = _vector(parameters, "anchor", (0.0, 0.0, 0.0))
    ax, ay, az = placed(holder, written)[0]
    anchor = (ax, ay, az)
    if y_up:
        axis, anchor = nue_to_enu(*axis), nue_to_enu(*anchor)
    norm = math.hypot(*axis)
    if norm == 0.0:
        return None
    # A positive speed about the axis rolls the robot along axis x up.
    roll = (axis[1] / norm, -axis[0] / norm, 0.0)
    radius = _round_radius(end, resolve) if end is not None else None
    velocity = _vector(motors[0], "maxVelocity", (DEFAULT_MAX_VELOCITY,))[0]
    return _Wheel(
        motor=first_value([motors[0]], "name", Field.string) or "motor",
        sensor=(first_value([sensors[0]], "name", Field.string) or "") if sensors else None,
        anchor=anchor,
        roll=roll,
        radius=radius,
        max_velocity=velocity if velocity > 0.0 else DEFAULT_MAX_VELOCITY,
    )


def _round_radius(solid: Node, resolve: Resolve) -> float | None:
    """The radius of the first ``Cylinder`` or ``Sphere`` of a wheel's ``boundingObject``."""
    pending = _field_nodes(solid, "boundingObject")
    while pending:
        node = resolve(pending.pop(0))
        if node.type_name in ("Cylinder", "Sphere"):
            radius = _vector(node, "radius", (0.1 if node.type_name == "Cylinder" else 1.0,))
            return radius[0] if radius[0] > 0.0 else None
        pending.extend(_field_nodes(node, "children") + _field_nodes(node, "geometry"))
    return None


def _body_radius(robot: Node, y_up: bool, resolve: Resolve) -> tuple[float | None, list[str]]:
    """How far the robot's own ``boundingObject`` reaches across the floor from its origin,
    and a warning when a shape of it is neither a cylinder nor a sphere."""
    reach: float | None = None
    others: list[str] = []
    pending = [(n, WORLD_FRAME) for n in _field_nodes(robot, "boundingObject")]
    while pending:
        node, holder = pending.pop(0)
        node = resolve(node)
        if node.type_name in ("Pose", "Transform", "Group"):
            offset = _vector(node, "translation", (0.0, 0.0, 0.0))
            frame = placed(holder, offset, _vector(node, "rotation", (0.0, 0.0, 1.0, 0.0)))
            pending += [(n, frame) for n in _field_nodes(node, "children")]
            continue
        if node.type_name == "Shape":
            pending += [(n, holder) for n in _field_nodes(node, "geometry")]
            continue
        x, y, _ = nue_to_enu(*holder[0]) if y_up else holder[0]
        if node.type_name in ("Cylinder", "Sphere"):
            across = _vector(node, "radius", (0.1 if node.type_name == "Cylinder" else 1.0,))[0]
        elif node.type_name == "Box":
            sx, sy, sz = _vector(node, "size", (0.1, 0.1, 0.1))
            across = math.hypot(sx, sz if y_up else sy) / 2
            others.append(f"a Box of {sx:g} x {sy:g} x {sz:g} m")
        else:
            others.append(f"a {node.type_name}")
            continue
        reach = max(reach or 0.0, math.hypot(x, y) + across)
    warnings = []
    if others and reach is not None:
        warnings.append(
            f"its boundingObject holds {', '.join(others)}: its body collides as a disc of "
            f"radius {reach:.4f} m round its origin, reaching as far"
        )
    return reach, warnings


def _shown_motors(drive: OwnDrive) -> str:
    """The drive's motors, as a warning names them."""
    return " and ".join(_shown(name) for name in drive.motors)


def drive_summary(drive: OwnDrive) -> str:
    """One line saying how the run rolls a two-wheeled robot of its own build."""
    return (
        f"a two-wheeled robot of its own build: motors {_shown_motors(drive)} turn wheels of "
        f"{drive.wheel_radius:.4f} m radius on a {drive.axle_length:.4f} m axle"
        + (f", a body of {drive.body_radius:.4f} m radius" if drive.body_radius else "")
    )


def wheel_names(drive: OwnDrive | None, kind: str) -> Mapping[int, str]:
    """The names of the drive's wheel devices of ``kind`` (``RotationalMotor`` or
    ``PositionSensor``) by side (0 left, 1 right); empty without a drive."""
    if drive is None:
        return {}
    names = drive.motors if kind == "RotationalMotor" else drive.sensors
    return {side: name for side, name in enumerate(names) if name}
