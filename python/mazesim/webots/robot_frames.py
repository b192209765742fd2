"""The robots of a world file in three dimensions: where a robot's node stands and leans, and
the primitive visual shapes its node holds, as a camera sees them.

mazesim moves a robot on the floor's plane (x, y and heading), the frame the import gives a
robot's devices in. A robot node raised above the floor or tilted (a camera robot looking down
at the arena) keeps its height and tilt in Webots: :func:`robot_mount` gives them, so that a
device's pose in the robot's node becomes its pose above the floor. :func:`robot_shapes` lists
the ``Box``, ``Cylinder``, ``Capsule`` and ``Sphere`` shapes of each robot node's children and
of its slots (an E-puck's ``turretSlot``, ``groundSensorsSlot`` and ``bodySlot``, each at the
place the E-puck PROTO mounts it: :data:`SLOT_ORIGINS`), through ``Solid``, ``Transform``,
``Pose``, ``Group`` and device nodes, not a joint's end point nor a ``boundingObject``: what
another robot's camera draws of it beside its body. :func:`carried_shapes` gives those of a
robot node that span the infra-red rays' heights, as a world's carried shapes, which the other
robots' rays and bodies meet.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from mazesim.webots.frames import ENU_TO_NUE, SLOT_ORIGINS, nue_to_enu, rotation_matrix
from mazesim.webots.proto.syntax import line_numbers, nodes_in_order, parse_nodes
from mazesim.webots.scene import Scene, SceneNode, _definitions

__all__ = [
    "SLOT_ORIGINS",
    "Footprint",
    "Mount",
    "RobotShape",
    "bounding_footprints",
    "carried_shapes",
    "infrared_reflectance",
    "robot_mount",
    "robot_shapes",
]

Matrix = npt.NDArray[np.float64]

#: Webots' ``Material.diffuseColor`` default (an ``Appearance`` whose material gives none).
MATERIAL_DIFFUSE = (0.8, 0.8, 0.8)
#: A rotation axis at most this far from vertical (the sine of the angle) counts as upright.
UPRIGHT = 1e-3


@dataclass(frozen=True)
class Mount:
    """A robot node's frame seen from the frame mazesim moves it in (its origin on the floor
    below the node's, x its heading on the floor's plane, z up): ``linear`` (rotation times the
    node's ``scale``) and ``origin`` (its height in z)."""

    linear: tuple[tuple[float, float, float], ...]
    origin: tuple[float, float, float]

    def point(self, p: Sequence[float]) -> tuple[float, float, float]:
        """A point of the robot's node in the floor's frame."""
        v = np.asarray(self.linear) @ np.asarray(p[:3], dtype=np.float64) + self.origin
        return float(v[0]), float(v[1]), float(v[2])

    def direction(self, d: Sequence[float]) -> tuple[float, float, float]:
        """A direction of the robot's node in the floor's frame, of length 1."""
        v = np.asarray(self.linear) @ np.asarray(d[:3], dtype=np.float64)
        v = v / (np.linalg.norm(v) or 1.0)
        return float(v[0]), float(v[1]), float(v[2])

    @property
    def upright(self) -> bool:
        """Whether the node stands upright on the floor, unscaled (nothing to change)."""
        return bool(np.allclose(self.linear, np.eye(3), atol=1e-12) and self.origin[2] == 0.0)


@dataclass(frozen=True)
class RobotShape:
    """A primitive visual shape of a robot, in the frame mazesim moves the robot in (x, y of
    its centre; ``bottom`` and ``top`` heights above the floor, m): a box of ``size`` (its
    extents, turned by ``yaw``), an upright cylinder of ``radius`` (``size`` None), or with
    ``sphere`` a sphere of ``radius``; of ``colour`` (red, green, blue in [0, 1]; None: no
    colour given)."""

    x: float
    y: float
    bottom: float
    top: float
    yaw: float
    size: tuple[float, float] | None
    radius: float
    sphere: bool
    colour: tuple[float, float, float] | None


def _frame(node: SceneNode, scaled: bool = True) -> tuple[Matrix, Matrix]:
    """A node's ``linear`` (rotation times scale) and ``origin`` in its parent's frame."""
    origin = np.asarray(node.translation or (0.0, 0.0, 0.0), dtype=np.float64)
    turn = node.rotation or (0.0, 0.0, 1.0, 0.0)
    linear = np.asarray(rotation_matrix(*turn), dtype=np.float64).reshape(3, 3)
    scale = node.numbers.get("scale")
    if scaled and scale is not None and len(scale) >= 3 and all(s != 0.0 for s in scale[:3]):
        linear = linear * np.asarray(scale[:3], dtype=np.float64)[None, :]
    return linear, origin


#: The cosine of the largest tilt of a robot node's axis still taken as pointing up (the
#: import's tolerance, 0.01 rad).
_UP_COSINE = math.cos(0.01)


def _level(linear: Matrix, origin: Matrix) -> tuple[Matrix, Matrix]:
    """A robot node's frame (in the world) seen from its frame on the floor: heading from its
    forward axis projected on the floor (0 when it points straight up or down), as the import
    takes a robot's start pose. A body built Y-up and stood upright by its rotation (its local y
    up in a file since R2022a; a file before has its nodes turned already) faces its local -z,
    as the import reads it: its frame is taken turned so (its Z-up frame)."""
    up = linear[:, 1] / (np.linalg.norm(linear[:, 1]) or 1.0)
    if up[2] >= _UP_COSINE:
        linear = linear @ np.asarray(ENU_TO_NUE, dtype=np.float64)
    forward = linear[:, 0]
    yaw = math.atan2(forward[1], forward[0]) if math.hypot(forward[0], forward[1]) > 1e-9 else 0.0
    c, s = math.cos(yaw), math.sin(yaw)
    back = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
    return back @ linear, np.array([0.0, 0.0, origin[2]])


def _scale_fixed(scene: Scene, node: SceneNode) -> SceneNode:
    """The node with its ``scale`` in the world frame's order (a file before R2022a writes it
    along its Y-up axes)."""
    scale = node.numbers.get("scale")
    if not scene.nue or scale is None or len(scale) < 3:
        return node
    numbers = dict(node.numbers)
    numbers["scale"] = (scale[2], scale[0], scale[1])
    return SceneNode(
        node.type_name,
        translation=node.translation,
        rotation=node.rotation,
        numbers=numbers,
    )


def robot_mount(scene: Scene) -> Mount | None:
    """The run's robot node's frame seen from its frame on the floor (its height, tilt and
    scale), or None when the scene has no robot node at its top."""
    own = next((node for node in scene.nodes if node.robot), None)
    if own is None:
        return None
    linear, origin = _level(*_frame(_scale_fixed(scene, own)))
    rows = tuple((float(r[0]), float(r[1]), float(r[2])) for r in linear)
    return Mount(rows, (0.0, 0.0, float(origin[2])))


def robot_shapes(scene: Scene) -> dict[int, list[RobotShape]]:
    """The primitive visual shapes of each robot node at the top of the file but the run's
    own, by the line of its node."""
    found: dict[int, list[RobotShape]] = {}
    for node in scene.nodes:
        if node.robot or node.base_type not in ("Robot", "DifferentialWheels"):
            continue
        shapes = [shape for shape, _ in _node_shapes(scene, node)]
        if shapes:
            found[node.line] = shapes
    return found


def carried_shapes(
    scene: Scene, line: int, body_radius: float, heights: tuple[float, float]
) -> list[dict[str, Any]]:
    """The shapes the robot node on ``line`` holds beside its body (reaching beyond
    ``body_radius``) that span the infra-red rays' ``heights`` (lowest, highest; m), as a
    world's ``[[robots.carried]]`` entries: each box or cylinder in the robot's frame with the
    reflection factor Webots' infra-red model gives its appearance
    (:func:`infrared_reflectance`); a sphere as the cylinder of its radius. ``scene`` is that
    of another robot's run, in which the node is one of the others (whose shapes it lists)."""
    own = next((n for n in scene.nodes if n.line == line and not n.robot), None)
    if own is None:
        return []
    carried: list[dict[str, Any]] = []
    for shape, shape_node in _node_shapes(scene, own):
        if shape.top < heights[0] or shape.bottom > heights[1]:
            continue
        entry: dict[str, Any] = {"center": [shape.x, shape.y]}
        if shape.size is None:
            entry["radius"] = shape.radius
            reach = math.hypot(shape.x, shape.y) + shape.radius
        else:
            entry["size"] = list(shape.size)
            entry["yaw"] = shape.yaw
            reach = math.hypot(shape.x, shape.y) + math.hypot(*shape.size) / 2.0
        if reach <= body_radius or not all(v > 0.0 for v in entry.get("size", [1.0])):
            continue
        entry["reflectance"] = infrared_reflectance(shape_node.nodes.get("appearance"))
        carried.append(entry)
    return carried


def infrared_reflectance(appearance: SceneNode | None) -> float:
    """Webots' infra-red reflection factor of a Shape's appearance, ``0.2 + 0.8 * red * (1 -
    0.5 * roughness)`` (reference manual, DistanceSensor), ``red`` its colour's times ``1 -
    transparency``: a ``PBRAppearance``'s ``baseColor`` and ``roughness`` (defaults white and
    0), an ``Appearance``'s ``Material.diffuseColor`` (white without a material), an
    appearance PROTO's ``colorOverride`` (white without one), each of roughness 0 but the
    first; white (1.0) without an appearance."""
    red, transparency, roughness = 1.0, 0.0, 0.0
    if appearance is not None and appearance.type_name == "PBRAppearance":
        red = _first(appearance.numbers, "baseColor", 1.0)
        transparency = _first(appearance.numbers, "transparency", 0.0)
        roughness = _first(appearance.numbers, "roughness", 0.0)
    elif appearance is not None and appearance.type_name == "Appearance":
        material = appearance.nodes.get("material")
        if material is not None:
            red = _first(material.numbers, "diffuseColor", MATERIAL_DIFFUSE[0])
            transparency = _first(material.numbers, "transparency", 0.0)
    elif appearance is not None:
        red = _first(appearance.numbers, "colorOverride", 1.0)
    red = min(1.0, max(0.0, red)) * (1.0 - min(1.0, max(0.0, transparency)))
    return 0.2 + 0.8 * red * (1.0 - 0.5 * min(1.0, max(0.0, roughness)))


def _node_shapes(scene: Scene, node: SceneNode) -> list[tuple[RobotShape, SceneNode]]:
    """The primitive visual shapes a robot node holds, in its floor frame, with their Shape
    nodes."""
    linear, origin = _level(*_frame(_scale_fixed(scene, node)))
    return [
        (shape, shape_node)
        for frame, shape_node in _shapes_below(scene, node, linear, origin)
        if (shape := _shape(scene, shape_node, *frame)) is not None
    ]


def _shapes_below(
    scene: Scene, robot: SceneNode, linear: Matrix, origin: Matrix
) -> Iterator[tuple[tuple[Matrix, Matrix], SceneNode]]:
    """Each Shape among the robot's children and in its slots, with its frame in the robot's
    floor frame."""
    held = [(child, origin) for child in robot.children]
    for slot, nodes in robot.slots.items():
        mount = np.asarray(SLOT_ORIGINS.get((robot.type_name, slot), (0.0, 0.0, 0.0)))
        held.extend((node, linear @ mount + origin) for node in nodes)
    pending = [(child, linear, at, 0) for child, at in reversed(held)]
    while pending:
        node, outer_linear, outer_origin, depth = pending.pop()
        if depth > 64:
            continue
        if node.type_name == "Shape":
            yield (outer_linear, outer_origin), node
            continue
        inner, at = _frame(_scale_fixed(scene, node))
        here = outer_linear @ inner
        placed_at = outer_linear @ at + outer_origin
        pending.extend((child, here, placed_at, depth + 1) for child in reversed(node.children))


def _shape(scene: Scene, node: SceneNode, linear: Matrix, origin: Matrix) -> RobotShape | None:
    """A Shape's primitive geometry placed by ``linear`` and ``origin``, or None for another
    geometry."""
    geometry = node.nodes.get("geometry")
    if geometry is None:
        return None
    colour = _colour(node.nodes.get("appearance"))
    numbers = geometry.numbers
    kind = geometry.type_name
    if kind == "Sphere":
        radius = _first(numbers, "radius", 1.0) * max(
            float(np.linalg.norm(linear[:, i])) for i in range(3)
        )
        x, y, z = (float(v) for v in origin)
        return RobotShape(x, y, z - radius, z + radius, 0.0, None, radius, True, colour)
    if kind == "Box":
        size = numbers.get("size", (2.0, 2.0, 2.0))
        if len(size) < 3:
            return None
        half = np.asarray(size[:3], dtype=np.float64) / 2.0
        if scene.nue:
            half = half[[2, 0, 1]]
        return _block(linear * half[None, :], origin, colour, None)
    if kind in ("Cylinder", "Capsule"):
        radius = _first(numbers, "radius", 1.0)
        half_height = _first(numbers, "height", 2.0) / 2.0
        if kind == "Capsule":
            half_height += radius
        half = np.array([radius, radius, half_height])
        return _block(linear * half[None, :], origin, colour, radius)
    return None


def _block(
    axes: Matrix,
    origin: Matrix,
    colour: tuple[float, float, float] | None,
    round_radius: float | None,
) -> RobotShape:
    """A box or cylinder whose half axes (columns, scaled) are ``axes`` at ``origin``: turned
    about the vertical only, as itself; otherwise the upright box that holds it."""
    x, y, z = (float(v) for v in origin)
    vertical = axes[:, 2]
    length = float(np.linalg.norm(vertical)) or 1.0
    upright = math.hypot(vertical[0], vertical[1]) <= UPRIGHT * length
    if upright:
        half_height = abs(float(vertical[2]))
        if round_radius is not None:
            radius = float(np.linalg.norm(axes[:, 0]))
            return RobotShape(
                x, y, z - half_height, z + half_height, 0.0, None, radius, False, colour
            )
        yaw = math.atan2(axes[1, 0], axes[0, 0])
        width = 2.0 * float(np.linalg.norm(axes[:, 0]))
        depth = 2.0 * float(np.linalg.norm(axes[:, 1]))
        return RobotShape(
            x, y, z - half_height, z + half_height, yaw, (width, depth), 0.0, False, colour
        )
    extent = np.abs(axes).sum(axis=1)
    size = (2.0 * float(extent[0]), 2.0 * float(extent[1]))
    return RobotShape(
        x, y, z - float(extent[2]), z + float(extent[2]), 0.0, size, 0.0, False, colour
    )


def _first(numbers: dict[str, tuple[float, ...]], name: str, default: float) -> float:
    values = numbers.get(name)
    return float(values[0]) if values else default


def _colour(appearance: SceneNode | None) -> tuple[float, float, float] | None:
    """The colour a camera sees of an appearance: a ``PBRAppearance``'s ``baseColor``, an
    ``Appearance``'s ``Material.diffuseColor``, each plus its ``emissiveColor``, an appearance
    PROTO's ``colorOverride``; None for a textured one or none."""
    if appearance is None:
        return None
    kind = appearance.type_name
    if kind == "PBRAppearance":
        if "baseColorMap" in appearance.nodes:
            return None
        base = appearance.numbers.get("baseColor", (1.0, 1.0, 1.0))
        glow = appearance.numbers.get("emissiveColor", (0.0, 0.0, 0.0))
    elif kind == "Appearance":
        if "texture" in appearance.nodes:
            return None
        material = appearance.nodes.get("material")
        if material is None:
            return (1.0, 1.0, 1.0)
        base = material.numbers.get("diffuseColor", MATERIAL_DIFFUSE)
        glow = material.numbers.get("emissiveColor", (0.0, 0.0, 0.0))
    else:
        override = appearance.numbers.get("colorOverride")
        if override is None:
            return None
        base, glow = override, (0.0, 0.0, 0.0)
    if len(base) < 3 or len(glow) < 3:
        return None
    red, green, blue = (min(1.0, max(0.0, float(b) + float(g))) for b, g in zip(base, glow))
    return (red, green, blue)


@dataclass(frozen=True)
class Footprint:
    """A collision shape seen from above, in its device's frame (x forward, y left, m): a box
    of half sides ``half`` turned ``yaw`` about its centre (x, y), or a disc of ``radius`` when
    ``half`` is None (a Cylinder, Capsule or Sphere, taken upright)."""

    x: float
    y: float
    yaw: float
    half: tuple[float, float] | None
    radius: float


#: Webots' defaults of the geometries a boundingObject may hold (reference manual: Box
#: ``size 0.1 0.1 0.1``, Cylinder, Capsule and Sphere ``radius`` 1).
_BOX_SIZE = (0.1, 0.1, 0.1)
_ROUND_RADIUS = 1.0


def bounding_footprints(
    text: str, robot_line: int | None, kind: str, name: str, y_up: bool, default_name: str = ""
) -> list[Footprint]:
    """The ``boundingObject`` of the device node of type ``kind`` named ``name`` that the
    robot node on ``robot_line`` of a world's ``text`` holds (among its children or in its
    slots), seen from above in the device's frame: each Box, Cylinder, Capsule and Sphere,
    placed by the Pose, Transform and Group nodes around it (a turn about the vertical kept,
    a tilt left out). Empty when the file writes no such node (a device a PROTO holds) or the
    node has no boundingObject. A node without a ``name`` field is named ``default_name``;
    ``y_up``: the robot's inside is modelled Y-up (``Scene.body_y_up``)."""
    if robot_line is None:
        return []
    tree = parse_nodes(text.lstrip("\ufeff"), "<world>", max_depth=None)
    every = list(nodes_in_order(tree))
    line_of = line_numbers(text.lstrip("\ufeff"))
    robot = next(
        (n for n in every if n.use_name is None and line_of(n.type_start) == robot_line), None
    )
    if robot is None:
        return []
    defined = _definitions(every)
    inside = nodes_in_order(n for item in robot.fields for n in item.nodes)
    for node in inside:
        named = node.field("name")
        own_name = named.string() if named is not None else None
        if node.type_name != kind or (own_name or default_name) != name:
            continue
        bounding = node.field("boundingObject")
        if bounding is None or not bounding.nodes:
            return []
        return _footprints(bounding.nodes[0], defined, y_up)
    return []


def _footprints(top: Any, defined: dict[int, Any], y_up: bool) -> list[Footprint]:
    """The footprints of a boundingObject's node (:func:`bounding_footprints`)."""
    found: list[Footprint] = []
    pending = [(top, 0.0, 0.0, 0.0, 0)]
    while pending:
        node, x, y, yaw, depth = pending.pop()
        if node.use_name is not None:
            node = defined.get(id(node))
        if node is None or depth > 64:
            continue
        kind = node.type_name
        c, s = math.cos(yaw), math.sin(yaw)
        if kind == "Shape":
            geometry = node.field("geometry")
            pending.extend((n, x, y, yaw, depth + 1) for n in (geometry.nodes if geometry else []))
        elif kind == "Box":
            size = _numbers(node, "size", 3) or _BOX_SIZE
            sx, sy = (size[2], size[0]) if y_up else (size[0], size[1])
            found.append(Footprint(x, y, yaw, (abs(sx) / 2.0, abs(sy) / 2.0), 0.0))
        elif kind in ("Cylinder", "Capsule", "Sphere"):
            radius = (_numbers(node, "radius", 1) or (_ROUND_RADIUS,))[0]
            found.append(Footprint(x, y, yaw, None, abs(radius)))
        elif kind in ("Pose", "Transform", "Group"):
            dx, dy, turn = 0.0, 0.0, 0.0
            if (at := _numbers(node, "translation", 3)) is not None:
                dx, dy, _ = nue_to_enu(*at) if y_up else at
            if (rotation := _numbers(node, "rotation", 4)) is not None:
                axis = nue_to_enu(*rotation[:3]) if y_up else rotation[:3]
                length = math.sqrt(sum(v * v for v in axis)) or 1.0
                if abs(abs(axis[2]) / length - 1.0) <= UPRIGHT:
                    turn = math.copysign(rotation[3], axis[2])
            children = node.field("children")
            pending.extend(
                (n, x + c * dx - s * dy, y + s * dx + c * dy, yaw + turn, depth + 1)
                for n in (children.nodes if children else [])
            )
    return found


def _numbers(node: Any, name: str, count: int) -> tuple[float, ...] | None:
    """The first ``count`` numbers of a parsed node's field, or None."""
    item = node.field(name)
    return item.numbers(count) if item is not None else None
