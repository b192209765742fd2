"""Webots' camera recognition: what a camera with a ``Recognition`` node recognises.

A Camera whose ``recognition`` field holds a Recognition node (``maxRange`` 100 m,
``maxObjects`` -1, ``occlusion`` 1, ``frameColor``, ``frameThickness``, ``segmentation``, as in
Webots' reference manual) recognises the Solids, robots among them, whose ``recognitionColors``
is not empty. The import reads both from the world's text with its PROTOs expanded
(:func:`read_recognition`): each object's node line, ``model``, colours, pose seen from above
and the box that holds its ``boundingObject`` (its Shapes' geometry without one) in its own
frame.

At each of its sampling periods the camera (:class:`Recogniser`) keeps, in world order, the
objects that are not its own robot, lie in its field of view (a point of their box inside it,
or the box across it) and within ``maxRange``, and (``occlusion`` 1 or 2) whose centre the ray
from the camera reaches before a wall of the 2D world (where a supervisor moved it) or another
robot's body does, other than the object's own walls and body.
Of more than ``maxObjects`` it keeps the biggest on the image. Each object's position and size
are those of its box in the camera's frame, clipped to the field of view as Webots clips them
(``WbObjectDetection::isWithinBounds``): a Box's corners are brought into the field of view; a
round object (Sphere, Cylinder or Capsule) is measured from its centre's distance to each side of
the field of view, the part beyond a side taken off its size and half of it off its position, and
is out of view once its centre lies beyond a side by more than half its size. Its position and
size on the image project the box's corners as Webots' planar camera does
(``src/webots/nodes/WbCamera.cpp``, ``WbObjectDetection.cpp``). The camera frame is Webots'
since R2022a, x forward, y left, z up; for a world of an earlier release, x right, y up, z
backward (the object ahead has a negative z). Robots follow their live pose, and so does an
object a robot carries (among its children or in a slot; that robot's body does not hide it),
a Solid that holds
one movable body that body's, a Solid with walls that a supervisor moved (it, or a node above
it) the move's. Segmentation images are not simulated.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, TypedDict

import numpy as np

from mazesim.webots.frames import WORLD_FRAME, Frame, nue_to_enu, placed
from mazesim.webots.line_of_sight import disc_entries, moved_walls, robot_body_radii
from mazesim.webots.proto.syntax import (
    Field,
    Node,
    first_value,
    line_numbers,
    nodes_in_order,
    parse_nodes,
    world_version,
)
from mazesim.webots.rays import WallBoxes
from mazesim.webots.scene import ROBOT_TYPES
from mazesim.webots.solids import composed, relative

__all__ = [
    "CameraPose",
    "RecognisableObject",
    "RecognitionReport",
    "RecognitionSettings",
    "Recogniser",
    "RecognisedObject",
    "read_recognition",
    "recogniser_of",
]

#: Node types that are robots once PROTOs are expanded (a ``Supervisor`` node of old worlds too).
_ROBOTS = ROBOT_TYPES | {"Supervisor"}
#: Geometries as wide seen from any side about the vertical.
_ROUND = {"Cylinder", "Capsule", "Sphere"}


class RecognitionSettings(TypedDict):
    """A camera's Recognition node: the ``line`` of its robot's node, the camera's ``name``
    and the node's fields."""

    robot_line: int
    camera: str
    max_range: float
    max_objects: int
    occlusion: int
    frame_color: list[float]
    frame_thickness: int
    segmentation: bool


class RecognisableObject(TypedDict):
    """A Solid with ``recognitionColors``: its node's ``line`` and ``id`` (its place among the
    file's top-level nodes, as a supervisor numbers them; 0 inside another node), ``model``,
    ``colors`` (red, green, blue of each), ``origin`` (x, y, z, world frame) and ``yaw``, the
    ``box_center`` and ``box_size`` of the box that holds it in its own frame turned by
    ``yaw``, whether that box is ``round`` (cylinders, capsules and spheres only: seen
    from any side as wide), and the line of the robot it is part of or is (``robot_line``, 0
    for none: a camera does not recognise its own robot's)."""

    line: int
    robot_line: int
    id: int
    model: str
    colors: list[float]
    origin: list[float]
    yaw: float
    box_center: list[float]
    box_size: list[float]
    round: bool


class RecognitionReport(TypedDict):
    """The import report's ``recognition``: the cameras with a Recognition node and the
    objects they can recognise, in file order."""

    cameras: list[RecognitionSettings]
    objects: list[RecognisableObject]


def read_recognition(text: str) -> RecognitionReport:
    """The Recognition nodes of a world's cameras and its recognisable objects.

    Args:
        text: The world's text, its PROTOs expanded.

    Raises:
        WorldFormatError: The text is not a world's nodes (the import says so first).
    """
    report: RecognitionReport = {"cameras": [], "objects": []}
    if "Recognition" not in text and "recognitionColors" not in text:
        return report  # nothing to recognise, nothing that recognises: no need to parse
    top = parse_nodes(text, "<world>", max_depth=None)
    line_of = line_numbers(text)
    nue = world_version(text)[1] or first_value(top, "coordinateSystem", Field.string) == "NUE"
    defined: dict[str, list[Node]] = {}
    for node in nodes_in_order(top):
        if node.def_name is not None and node.use_name is None:
            defined.setdefault(node.def_name, []).append(node)
    # (node, its holder's frame, the line of the robot it is in, its top-level id)
    pending: list[tuple[Node, Frame, int, int]] = [
        (node, WORLD_FRAME, 0, index) for index, node in reversed(list(enumerate(top, start=1)))
    ]
    while pending:
        node, holder, robot_line, top_id = pending.pop()
        if node.use_name is not None:
            continue
        frame = _frame_of(node, holder)
        line = line_of(node.type_start)
        if node.type_name in _ROBOTS and robot_line == 0:
            robot_line = line
        if node.type_name == "Camera":
            name = first_value([node], "name", Field.string) or "camera"
            _camera(node.field("recognition"), name, robot_line, report)
        elif node.type_name in _ROBOTS:
            # The E-puck PROTO's field for its own camera's Recognition node.
            _camera(node.field("camera_recognition"), "camera", robot_line, report)
        if (colours := _colours(node)) is not None:
            found = _object(node, frame, nue, colours, line, top_id, defined)
            if found is not None:
                found["robot_line"] = robot_line
                report["objects"].append(found)
        inner = [
            (child, frame, robot_line, 0)
            for item in node.fields
            if item.name not in ("boundingObject", "recognition", "camera_recognition")
            for child in item.nodes
        ]
        pending.extend(reversed(inner))
    return report


def _numbers(node: Node, name: str, count: int) -> tuple[float, ...] | None:
    return first_value([node], name, lambda item: item.numbers(count))


def _whole(node: Node, name: str, default: int) -> int:
    """An SFInt32 field's value, or ``default`` when absent or not a finite number (a value
    past the 32-bit range is clamped to it, as Webots' parser keeps an SFInt32)."""
    value = (_numbers(node, name, 1) or (float(default),))[0]
    if not math.isfinite(value):
        return default
    return int(min(max(value, -(2.0**31)), 2.0**31 - 1))


def _frame_of(node: Node, holder: Frame) -> Frame:
    """The frame of a node placed in ``holder`` by its translation and rotation."""
    offset = _numbers(node, "translation", 3) or (0.0, 0.0, 0.0)
    return placed(holder, offset, _numbers(node, "rotation", 4))


def _camera(field: Field | None, camera: str, robot_line: int, report: RecognitionReport) -> None:
    """Adds the Recognition node a camera's ``field`` holds (a Camera's ``recognition``, an
    E-puck's ``camera_recognition``), if it holds one, to the report as camera ``camera``'s."""
    held = field.nodes[0] if field is not None and field.nodes else None
    if held is None or held.type_name != "Recognition":
        return
    occlusion = first_value([held], "occlusion", lambda item: item.flag())
    level = _numbers(held, "occlusion", 1)
    report["cameras"].append(
        {
            "robot_line": robot_line,
            "camera": camera,
            "max_range": (_numbers(held, "maxRange", 1) or (100.0,))[0],
            "max_objects": _whole(held, "maxObjects", -1),
            # An SFBool before R2021b, an SFInt32 (0, 1 or 2) since.
            "occlusion": int(level[0]) if level else int(occlusion is not False),
            "frame_color": list(_numbers(held, "frameColor", 3) or (1.0, 0.0, 0.0)),
            "frame_thickness": _whole(held, "frameThickness", 1),
            "segmentation": bool(first_value([held], "segmentation", Field.flag)),
        }
    )


def _colours(node: Node) -> list[float] | None:
    """A node's ``recognitionColors`` (red, green, blue of each), None when empty or absent."""
    field = node.field("recognitionColors")
    if field is None:
        return None
    words = [t for t in field.tokens if t.kind == "word"]
    try:
        values = [float(t.text) for t in words]
    except ValueError:
        return None
    usable = len(values) - len(values) % 3
    return values[:usable] or None


def _object(
    node: Node,
    frame: Frame,
    nue: bool,
    colours: list[float],
    line: int,
    top_id: int,
    defined: dict[str, list[Node]],
) -> RecognisableObject | None:
    """A recognisable node as the report gives it; None when it has nothing to measure."""
    points, rounded = _bounds(node, frame, nue, defined)
    if not points:
        return None
    origin = list(frame[0])
    # Its heading: its x axis, or in an NUE world its -z axis (where a robot of such a world
    # faces, which the import takes as the robot's yaw 0).
    ahead = [frame[1][0], frame[1][3], frame[1][6]]
    if nue:
        origin = list(nue_to_enu(*origin))
        ahead = list(nue_to_enu(-frame[1][2], -frame[1][5], -frame[1][8]))
        points = [nue_to_enu(*p) for p in points]
    yaw = math.atan2(ahead[1], ahead[0])
    c, s = math.cos(yaw), math.sin(yaw)
    local = [
        (
            c * (p[0] - origin[0]) + s * (p[1] - origin[1]),
            -s * (p[0] - origin[0]) + c * (p[1] - origin[1]),
            p[2] - origin[2],
        )
        for p in points
    ]
    low = [min(p[k] for p in local) for k in range(3)]
    high = [max(p[k] for p in local) for k in range(3)]
    return {
        "line": line,
        "robot_line": 0,
        "id": top_id,
        "model": first_value([node], "model", Field.string) or "",
        "colors": colours,
        "origin": origin,
        "yaw": yaw,
        "box_center": [(low[k] + high[k]) / 2.0 for k in range(3)],
        "box_size": [high[k] - low[k] for k in range(3)],
        "round": rounded,
    }


def _bounds(
    node: Node, frame: Frame, nue: bool, defined: dict[str, list[Node]]
) -> tuple[list[tuple[float, float, float]], bool]:
    """Corner points (file frame) of the geometries of a node's ``boundingObject``, else of
    the Shapes among its children; and whether they are all round. A ``USE`` stands for the
    last node of its ``DEF`` name before it."""
    field = node.field("boundingObject")
    roots: list[tuple[Node, Frame]] = []
    if field is not None and field.nodes:
        roots = [(field.nodes[0], frame)]
    else:
        roots = [
            (child, frame)
            for item in node.fields
            if item.name == "children"
            for child in item.nodes
        ]
    points: list[tuple[float, float, float]] = []
    rounded = True
    pending = list(reversed(roots))
    while pending:
        part, holder = pending.pop()
        if part.use_name is not None:
            earlier = [d for d in defined.get(part.use_name, []) if d.start < part.start]
            if not earlier:
                continue
            part = earlier[-1]
        here = _frame_of(part, holder) if part.type_name in ("Transform", "Pose") else holder
        if part.type_name in ("Transform", "Pose", "Group"):
            inner = [
                (c, here) for item in part.fields if item.name == "children" for c in item.nodes
            ]
            pending.extend(reversed(inner))
        elif part.type_name == "Shape":
            geometry = part.field("geometry")
            if geometry is not None and geometry.nodes:
                pending.append((geometry.nodes[0], here))
        elif (half := _half_extents(part, nue)) is not None:
            rounded = rounded and part.type_name in _ROUND
            origin, m = here
            for sx in (-1.0, 1.0):
                for sy in (-1.0, 1.0):
                    for sz in (-1.0, 1.0):
                        v = (sx * half[0], sy * half[1], sz * half[2])
                        points.append(
                            (
                                origin[0] + m[0] * v[0] + m[1] * v[1] + m[2] * v[2],
                                origin[1] + m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
                                origin[2] + m[6] * v[0] + m[7] * v[1] + m[8] * v[2],
                            )
                        )
    return points, rounded and bool(points)


def _half_extents(geometry: Node, nue: bool) -> tuple[float, float, float] | None:
    """Half the extents of a geometry along its own axes (a cylinder's and capsule's axis is
    their z axis since R2022a, their y axis in a world of an earlier release, ``nue``), None
    for a geometry without a size."""
    kind = geometry.type_name
    if kind == "Box":
        size = _numbers(geometry, "size", 3) or (2.0, 2.0, 2.0)
        return size[0] / 2.0, size[1] / 2.0, size[2] / 2.0
    radius = (_numbers(geometry, "radius", 1) or (1.0,))[0]
    if kind == "Sphere":
        return radius, radius, radius
    if kind in ("Cylinder", "Capsule"):
        height = (_numbers(geometry, "height", 1) or (2.0,))[0]
        half = height / 2.0 + (radius if kind == "Capsule" else 0.0)
        return (radius, half, radius) if nue else (radius, radius, half)
    return None


@dataclass(frozen=True)
class RecognisedObject:
    """An object a camera recognises, as Webots' ``WbCameraRecognitionObject`` holds it."""

    id: int
    position: tuple[float, float, float]
    orientation: tuple[float, float, float, float]
    size: tuple[float, float]
    position_on_image: tuple[int, int]
    size_on_image: tuple[int, int]
    colors: tuple[float, ...]
    model: str


@dataclass(frozen=True)
class CameraPose:
    """Where a camera is: its position (m, world frame), heading and downward pitch (rad), its
    image's width and height (pixels) and horizontal field of view (rad)."""

    x: float
    y: float
    z: float
    yaw: float
    pitch: float
    width: int
    height: int
    fov: float


#: A pose seen from above: x, y (m) and yaw (rad).
Pose2 = tuple[float, float, float]


def _start_pose(robot: Mapping[str, Any]) -> Pose2:
    """A robot's pose seen from above as the import placed it (x, y, yaw)."""
    pose = [float(v) for v in (robot.get("pose") or ())][:3]
    x, y, yaw = pose + [0.0] * (3 - len(pose))
    return (x, y, yaw)


class Recogniser:
    """What a camera with a Recognition node recognises (see the module's docstring)."""

    def __init__(
        self,
        settings: RecognitionSettings,
        objects: Sequence[RecognisableObject],
        report: Mapping[str, Any],
        old_frame: bool = False,
    ) -> None:
        """Over the ``objects`` of a world imported with ``report``, for a camera of the robot
        on ``settings["robot_line"]``; ``old_frame``: the world is of a release before R2022a
        (Webots' camera frame then x right, y up, z backward)."""
        from mazesim.webots.solids import held_by_line

        self.settings = settings
        self._old_frame = old_frame
        robot_line = int(settings["robot_line"])
        self._objects = [
            o
            for o in objects
            if int(o["line"]) != robot_line
            and (robot_line == 0 or int(o.get("robot_line", 0) or 0) != robot_line)
        ]
        robots = report.get("robots") or []
        #: The robot index of each object that is a robot (it follows its live pose).
        self._robot = {int(r["line"]): i for i, r in enumerate(robots) if "line" in r}
        #: The camera's own robot's index (its body hides nothing from it).
        self._own_robot = self._robot.get(robot_line)
        #: The robot index of each object a robot carries (among its children or in a slot): it
        #: moves with that robot, whose body does not hide it; with each robot's start pose.
        self._carrier = {
            int(o["line"]): self._robot[carrier]
            for o in self._objects
            if (carrier := int(o.get("robot_line", 0) or 0)) in self._robot
            and int(o["line"]) not in self._robot
        }
        self._starts: list[Pose2] = [_start_pose(r) for r in robots]
        #: The body radius of each robot simulated as one (None: its shapes are walls).
        self._radii = robot_body_radii(report)
        held = held_by_line(report)
        #: The walls each node holds, by its line (a supervisor's move of it moves them).
        self._held_walls = {line: list(h.walls) for line, h in held.items() if h.walls}
        #: The nodes whose moves move each object that holds walls: it, and those above it.
        self._holders: dict[int, list[int]] = {}
        bodies = report.get("bodies") or []
        #: The movable body an object holds alone (it follows that body), with its import pose.
        self._body: dict[int, tuple[int, Pose2]] = {}
        #: The walls each object holds (they do not hide it).
        self._walls: dict[int, set[int]] = {}
        for thing in self._objects:
            line = int(thing["line"])
            own = held.get(line)
            if own is None:
                continue
            self._walls[line] = set(own.walls)
            if own.walls:
                walls = set(own.walls)
                self._holders[line] = [
                    holder for holder, moved in self._held_walls.items() if walls <= set(moved)
                ]
            if len(own.bodies) == 1 and own.bodies[0] < len(bodies):
                body = bodies[own.bodies[0]]
                centre = body.get("center") or (0.0, 0.0)
                start = (float(centre[0]), float(centre[1]), float(body.get("yaw") or 0.0))
                self._body[line] = (own.bodies[0], start)

    @property
    def follows_robots(self) -> bool:
        """Whether some object is a robot or a robot carries it, whose live pose is needed."""
        return bool(self._carrier) or any(int(o["line"]) in self._robot for o in self._objects)

    @property
    def follows_bodies(self) -> bool:
        """Whether some object holds a movable body, whose live pose is needed."""
        return bool(self._body)

    @property
    def follows_moves(self) -> bool:
        """Whether some object or wall a supervisor may move is in the world, whose moves
        (``node_moves``) are needed."""
        return bool(self._holders) or (
            bool(self._held_walls) and int(self.settings["occlusion"]) > 0
        )

    @property
    def needs_robot_poses(self) -> bool:
        """Whether the robots' live poses are needed: some object is a robot, or another
        robot's body may hide an object (``occlusion`` 1 or 2)."""
        others = any(r is not None for i, r in enumerate(self._radii) if i != self._own_robot)
        return self.follows_robots or (others and int(self.settings["occlusion"]) > 0)

    def recognise(
        self,
        camera: CameraPose,
        walls: WallBoxes | None,
        robot_poses: Sequence[Pose2 | None] | None = None,
        body_poses: Sequence[Pose2] | None = None,
        node_moves: Mapping[int, tuple[Pose2, Pose2]] | None = None,
    ) -> list[RecognisedObject]:
        """The objects recognised from ``camera`` now, the robots at ``robot_poses`` (every
        robot of the world's, in the report's order; None for one a supervisor removed, which
        is gone), the movable bodies at ``body_poses``
        (None: where the import put them) and the nodes a supervisor moved by ``node_moves``
        (by line, the node's pose seen from above in the file and now)."""
        moves = node_moves or {}
        found: list[_Candidate] = []
        for thing in self._objects:
            posed = self._pose(thing, robot_poses, body_poses, moves)
            if posed is None:
                continue
            candidate = self._seen(thing, *posed, camera)
            if candidate is not None:
                found.append(candidate)
        if walls is not None and int(self.settings["occlusion"]) > 0 and found:
            walls = moved_walls(walls, self._held_walls, moves)
            found = self._unhidden(found, camera, walls, robot_poses)
        limit = int(self.settings["max_objects"])
        if 0 < limit < len(found):
            # The biggest on the image, in world order among equals.
            found.sort(key=lambda c: -c.seen.size_on_image[0] * c.seen.size_on_image[1])
            found = found[:limit]
        return [candidate.seen for candidate in found]

    def _pose(
        self,
        thing: RecognisableObject,
        robot_poses: Sequence[Pose2 | None] | None,
        body_poses: Sequence[Pose2] | None,
        moves: Mapping[int, tuple[Pose2, Pose2]],
    ) -> tuple[tuple[float, float, float], float] | None:
        """An object's origin and yaw now (None for a robot a supervisor removed)."""
        x, y, z = (float(v) for v in thing["origin"])
        yaw = float(thing["yaw"])
        line = int(thing["line"])
        if robot_poses is not None and line in self._robot and self._robot[line] < len(robot_poses):
            robot = robot_poses[self._robot[line]]
            if robot is None:
                return None
            px, py, pyaw = robot
            return (float(px), float(py), z), float(pyaw)
        carrier = self._carrier.get(line)
        if robot_poses is not None and carrier is not None and carrier < len(robot_poses):
            now = robot_poses[carrier]
            if now is None:
                return None  # removed with the robot that carries it
            x, y, yaw = composed(now, relative(self._starts[carrier], (x, y, yaw)))
            return (x, y, z), yaw
        if body_poses is not None and line in self._body:
            index, (sx, sy, syaw) = self._body[line]
            if index < len(body_poses):
                bx, by, byaw = (float(v) for v in body_poses[index])
                turn = byaw - syaw
                c, s = math.cos(turn), math.sin(turn)
                dx, dy = x - sx, y - sy
                return (bx + c * dx - s * dy, by + s * dx + c * dy, z), yaw + turn
        for holder in self._holders.get(line, []):
            if holder in moves:
                before, now = moves[holder]
                x, y, yaw = composed(now, relative(before, (x, y, yaw)))
        return (x, y, z), yaw

    def _seen(
        self,
        thing: RecognisableObject,
        origin: tuple[float, float, float],
        yaw: float,
        camera: CameraPose,
    ) -> _Candidate | None:
        """The object as the camera sees it, or None when it is out of the field of view or
        beyond ``maxRange``."""
        max_range = float(self.settings["max_range"])
        cx, cy, cz = (float(v) for v in thing["box_center"])
        half = [float(v) / 2.0 for v in thing["box_size"]]
        c, s = math.cos(yaw), math.sin(yaw)
        centre = (origin[0] + c * cx - s * cy, origin[1] + s * cx + c * cy, origin[2] + cz)
        reach = math.sqrt(sum(h * h for h in half))
        gap = math.dist(centre, (camera.x, camera.y, camera.z))
        if gap > max_range + reach or not _may_be_in_view(centre, reach, camera):
            return None
        # The box's axes: the object's, or (a round object) the camera's.
        axes_yaw = camera.yaw if thing["round"] else yaw
        ca, sa = math.cos(axes_yaw), math.sin(axes_yaw)
        corners = [
            (
                centre[0] + ca * u * half[0] - sa * v * half[1],
                centre[1] + sa * u * half[0] + ca * v * half[1],
                centre[2] + w * half[2],
            )
            for u in (-1.0, 1.0)
            for v in (-1.0, 1.0)
            for w in (-1.0, 1.0)
        ]
        local = [_in_camera(p, camera) for p in corners]
        if thing["round"]:
            bounds = _round_bounds(_in_camera(centre, camera), local, camera)
        else:
            bounds = _clipped_bounds(local, camera)
        if bounds is None:
            return None
        low, high = bounds
        position = tuple((low[k] + high[k]) / 2.0 for k in range(3))
        size = tuple(high[k] - low[k] for k in range(3))
        if abs(position[0]) > max_range + size[0] / 2.0:
            return None
        image = _on_image(position, size, camera)
        if image is None:
            return None
        turn = math.remainder(yaw - camera.yaw, math.tau)
        axis = -1.0 if turn < 0.0 else 1.0
        if self._old_frame:
            x, y, z = position
            placed_at = (-y, z, -x)
            orientation = (0.0, axis, 0.0, abs(turn))
        else:
            placed_at = (position[0], position[1], position[2])
            orientation = (0.0, 0.0, axis, abs(turn))
        seen = RecognisedObject(
            id=int(thing["id"]),
            position=placed_at,
            orientation=orientation,
            size=(size[1], size[2]),
            position_on_image=image[0],
            size_on_image=image[1],
            colors=tuple(float(v) for v in thing["colors"]),
            model=str(thing["model"]),
        )
        return _Candidate(seen, int(thing["line"]), (origin[0], origin[1]), size[0])

    def _unhidden(
        self,
        found: list[_Candidate],
        camera: CameraPose,
        walls: WallBoxes,
        robot_poses: Sequence[Pose2 | None] | None,
    ) -> list[_Candidate]:
        """Those of ``found`` whose origin the ray from the camera reaches, seen from above,
        before any wall but their own and any other robot's body (at ``robot_poses``) but
        their own, or past it by less than half their depth along the camera's axis (Webots:
        a collision farther than that from the object hides it)."""
        directions = np.array(
            [[c.origin[0] - camera.x, c.origin[1] - camera.y] for c in found], dtype=np.float64
        )
        along, wall = walls.cast_walls((camera.x, camera.y), directions)
        kept = []
        for candidate, t, hit, direction in zip(found, along, wall, directions):
            short = (1.0 - float(t)) * float(np.hypot(direction[0], direction[1]))
            own = int(hit) in self._walls.get(candidate.line, set())
            if not (own or not math.isfinite(t) or short <= candidate.depth / 2.0):
                continue
            if robot_poses is None or not self._behind_robot(candidate, camera, robot_poses):
                kept.append(candidate)
        return kept

    def _behind_robot(
        self, candidate: _Candidate, camera: CameraPose, robot_poses: Sequence[Pose2 | None]
    ) -> bool:
        """Whether another robot's body (a disc seen from above; none for a robot a supervisor
        removed) meets the ray from the camera to the candidate's origin farther than half the
        candidate's depth from it."""
        dx, dy = candidate.origin[0] - camera.x, candidate.origin[1] - camera.y
        length = math.hypot(dx, dy)
        if length == 0.0:
            return False
        itself = self._robot.get(candidate.line, self._carrier.get(candidate.line))
        count = min(len(robot_poses), len(self._radii))
        radii = np.array(
            [
                math.nan if radius is None or index in (self._own_robot, itself) else radius
                for index, radius in enumerate(self._radii[:count])
            ],
            dtype=np.float64,
        )
        gone = (math.nan, math.nan)
        centres = np.array(
            [gone if p is None else (float(p[0]), float(p[1])) for p in robot_poses[:count]],
            dtype=np.float64,
        ).reshape(-1, 2)
        unit = np.array([[dx / length, dy / length]], dtype=np.float64)
        enter = disc_entries((camera.x, camera.y), unit, centres, radii)[0]
        return bool(np.any((enter >= 0.0) & (length - enter > candidate.depth / 2.0)))


@dataclass(frozen=True)
class _Candidate:
    """An object in the field of view: as recognised, its node's line, its origin seen from
    above and its depth along the camera's axis (m)."""

    seen: RecognisedObject
    line: int
    origin: tuple[float, float]
    depth: float


def _in_camera(point: tuple[float, float, float], camera: CameraPose) -> tuple[float, float, float]:
    """A world point in the camera's frame: x forward, y left, z up (pitched ``pitch`` down)."""
    dx, dy, dz = point[0] - camera.x, point[1] - camera.y, point[2] - camera.z
    c, s = math.cos(camera.yaw), math.sin(camera.yaw)
    ahead, left = c * dx + s * dy, -s * dx + c * dy
    cp, sp = math.cos(camera.pitch), math.sin(camera.pitch)
    return ahead * cp - dz * sp, left, ahead * sp + dz * cp


def _may_be_in_view(centre: tuple[float, float, float], reach: float, camera: CameraPose) -> bool:
    """Whether a ball of radius ``reach`` about ``centre`` may meet the field of view (False:
    wholly behind the camera or beyond a side of the field of view)."""
    x, y, z = _in_camera(centre, camera)
    if x < -reach:
        return False
    across, up = _half_tangents(camera)
    for tangent, offset in ((across, abs(y)), (up, abs(z))):
        # The distance of the centre beyond the side plane at that half angle.
        if (offset - x * tangent) / math.sqrt(1.0 + tangent * tangent) > reach:
            return False
    return True


def _half_tangents(camera: CameraPose) -> tuple[float, float]:
    """The tangents of half the horizontal and half the vertical field of view (square
    pixels: the vertical one from the image's height over its width)."""
    across = math.tan(camera.fov / 2.0)
    return across, across * camera.height / camera.width


def _clipped_bounds(
    corners: list[tuple[float, float, float]], camera: CameraPose
) -> tuple[list[float], list[float]] | None:
    """The box (lowest and highest x, y, z, camera frame) of the corners ahead of the camera
    brought into its field of view and those behind it; None when no corner is ahead, or
    none is in the field of view and the corners do not lie across it."""
    across, up = _half_tangents(camera)
    ahead: list[tuple[float, float, float]] = []
    behind: list[tuple[float, float, float]] = []
    inside = 0
    # Whether a corner lies beyond / within the right, left, bottom and top sides.
    beyond = [False] * 4
    within = [False] * 4
    for x, y, z in corners:
        if x <= 0.0:
            behind.append((x, y, z))
            continue
        limits = (-y - x * across, y - x * across, -z - x * up, z - x * up)
        for side, excess in enumerate(limits):
            if excess > 0.0:
                beyond[side] = True
            else:
                within[side] = True
        if max(limits) <= 0.0:
            inside += 1
        ahead.append((x, min(max(y, -x * across), x * across), min(max(z, -x * up), x * up)))
    if not ahead:
        return None
    if inside == 0:
        sideways = beyond[0] and beyond[1] and within[2] and within[3]
        upright = beyond[2] and beyond[3] and within[0] and within[1]
        if not (sideways or upright):
            return None
    points = ahead + behind
    low = [min(p[k] for p in points) for k in range(3)]
    high = [max(p[k] for p in points) for k in range(3)]
    return low, high


def _round_bounds(
    centre: tuple[float, float, float],
    corners: list[tuple[float, float, float]],
    camera: CameraPose,
) -> tuple[list[float], list[float]] | None:
    """The box (lowest and highest x, y, z, camera frame) of a round object with its
    ``centre`` and its box's ``corners`` in the camera's frame, as Webots measures a Sphere,
    Cylinder or Capsule (``WbObjectDetection::isWithinBounds``): for each side of the field of
    view (right, bottom, left, top), the signed distance ``d`` of the centre from that side
    (positive inside) against half the box's width (right, left) or height (bottom, top):
    beyond by more than that half, the object is out of view (None); within less than it, the
    part ``half - d`` is beyond that side. With a horizontal field of view of 90 degrees or
    less, those parts come off the width and height and half of each off the position, towards
    the view."""
    low = [min(p[k] for p in corners) for k in range(3)]
    high = [max(p[k] for p in corners) for k in range(3)]
    size = [high[k] - low[k] for k in range(3)]
    x, y, z = centre
    across, up = _half_tangents(camera)
    outside = []
    # The right, bottom, left and top sides: their tangent, the centre's offset towards the
    # inside, and the half size measured against them.
    for tangent, offset, half in (
        (across, y, size[1] / 2.0),
        (up, z, size[2] / 2.0),
        (across, -y, size[1] / 2.0),
        (up, -z, size[2] / 2.0),
    ):
        d = (tangent * x + offset) / math.sqrt(1.0 + tangent * tangent)
        if d < -half:
            return None
        outside.append(half - d if d < half else 0.0)
    position = [x, y, z]
    if camera.fov <= math.pi / 2.0:
        right, bottom, left, top = outside
        size[1] -= right + left
        size[2] -= bottom + top
        position[1] += 0.5 * (right - left)
        position[2] += 0.5 * (bottom - top)
    low = [position[k] - size[k] / 2.0 for k in range(3)]
    high = [position[k] + size[k] / 2.0 for k in range(3)]
    return low, high


def _on_image(
    position: tuple[float, ...], size: tuple[float, ...], camera: CameraPose
) -> tuple[tuple[int, int], tuple[int, int]] | None:
    """The centre and size (pixels) on the image of a box of the camera's frame, from its
    corners' projections as Webots' planar camera makes them; None when under a pixel."""
    across, up = _half_tangents(camera)
    us, vs = [], []
    for sx in (-0.5, 0.5):
        for sy in (-0.5, 0.5):
            for sz in (-0.5, 0.5):
                x = position[0] + sx * size[0]
                y = position[1] + sy * size[1]
                z = position[2] + sz * size[2]
                if x < 0.0:
                    u, v = (-0.5 if y > 0.0 else 0.5), (-0.5 if z > 0.0 else 0.5)
                else:
                    depth = abs(x) or 1e-300
                    u, v = 0.5 * (-y / depth) / across, -0.5 * (z / depth) / up
                u = min(max(0.5 + u, 0.0), 1.0)
                v = min(max(0.5 + v, 0.0), 1.0)
                us.append(int((camera.width - 1) * u))
                vs.append(int((camera.height - 1) * v))
    width, height = max(us) - min(us), max(vs) - min(vs)
    if width < 1 or height < 1:
        return None
    centre = (
        math.floor((max(us) + min(us)) / 2.0 + 0.5),
        math.floor((max(vs) + min(vs)) / 2.0 + 0.5),
    )
    return centre, (width, height)


def recogniser_of(report: Mapping[str, Any], camera: str, old_frame: bool) -> Recogniser | None:
    """The recogniser of the camera of that name of the report's robot (``robot_line``), or
    None when it has no Recognition node."""
    found = report.get("recognition") or {}
    line = report.get("robot_line")
    for settings in found.get("cameras") or []:
        if line is not None and int(settings["robot_line"]) == int(line):
            if settings["camera"] == camera:
                return Recogniser(settings, found.get("objects") or [], report, old_frame)
    return None
