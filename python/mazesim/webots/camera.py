"""The e-puck's camera: a forward view rendered from the 2D world, in colour.

Each pixel is a ray from the camera (0.03 m ahead of the axle, 0.028 m above the floor, level,
field of view 0.84 rad, 52 x 39 pixels as in Webots' E-puck PROTO). A ray that meets another
robot's body below its top sees that robot (the E-puck PROTO's colours), one that meets a ball
(a movable body whose collision shape is a sphere, resting on the floor where it is now) sees
it, 80 % of its colour; one that meets a wall
(a sensed-only one too, which nothing collides with) below the wall's height sees the wall, 80 %
of its colour; a ray going down that meets the floor
first sees the floor paint in its colour. A wall, paint or floor that gives no colour (see
:meth:`mazesim.World.wall_colours`) is grey from its reflectance factor ``f``
(``(f - 0.2) / 0.8``, so a white floor is 255 and black paint 0, the inverse of the infra-red
model); anything else sees the sky. Images are BGRA bytes, as Webots gives them.

A camera whose node has a Recognition node recognises objects
(:mod:`mazesim.webots.recognition`); the E-puck PROTO's own camera has none.
"""

from __future__ import annotations

import math
import os
import weakref
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from numbers import Integral
from typing import TYPE_CHECKING, Any, Union

import numpy as np
import numpy.typing as npt

from mazesim._hot_paths import checks_own_arguments
from mazesim.errors import InvalidArgumentError, WrongTypeError, _shown
from mazesim.webots.devices import _print_error, _Sensor, device_side, sampling_period
from mazesim.webots.frames import Axes, axes_or_none, camera_heading
from mazesim.webots.node_types import node_type
from mazesim.webots.rays import FloorPaint, WallBoxes
from mazesim.webots.recognition import CameraPose, RecognisedObject, recogniser_of
from mazesim.webots.robot_frames import Mount, RobotShape
from mazesim.webots.walls_now import OtherRobots, WallsNow

if TYPE_CHECKING:
    from mazesim.webots.simulation import RobotSimulation

__all__ = [
    "Ball",
    "Block",
    "Camera",
    "CameraRecognitionObject",
    "CameraView",
    "RobotBody",
    "drawn_body",
    "node_view",
    "placed_shape",
    "render",
]

#: Image size and field of view of Webots' E-puck PROTO camera.
DEFAULT_WIDTH = 52
DEFAULT_HEIGHT = 39
DEFAULT_FOV = 0.84
#: The camera's position on the robot (m): ahead of the wheel axle, above the floor.
CAMERA_X = 0.03
CAMERA_Z = 0.028
#: Wall height (m) the camera draws a wall the world gives no top (a mazesim world's without
#: ``height``): the e-puck worlds' usual walls.
WALL_HEIGHT = 0.1
#: Grey of a wall of reflectance 1 (walls are drawn a little darker than a white floor).
WALL_SHADE = 0.8
#: A JPEG of a quality above this keeps its colours at full resolution (4:4:4), as Webots'
#: writer (stb_image_write, src/controller/c/g_image.c) does; at or below, at half (4:2:0).
JPEG_FULL_COLOUR_ABOVE = 90
#: Colour of the sky (RGB).
SKY = (150, 180, 210)
#: Another e-puck as the camera sees it, from Webots' E-puck PROTO (R2022b,
#: projects/robots/gctronic/e-puck/protos/E-puck.proto): its bounding cylinder (radius 0.037 m,
#: 0.045 m high, centred 0.025 m up) is the body, drawn in the shell's
#: ``EPUCK_TRANSPARENT_APPEARANCE`` (baseColor 0.5 0.5 0.5) but for the edge of its top plate
#: (0.037 to 0.0385 m up), its ``EPUCK_SIDE_PRINT_APPEARANCE`` green.
ROBOT_TOP = 0.0475
ROBOT_RADIUS = 0.037
ROBOT_BOTTOM = 0.0025
ROBOT_COLOUR = (0.5, 0.5, 0.5)
PLATE_EDGE = (0.037, 0.0385)
PLATE_COLOUR = (0.184314, 0.635294, 0.184314)


@dataclass(frozen=True)
class RobotBody:
    """Another robot as the camera sees it: an upright cylinder at (x, y) of ``radius``."""

    x: float
    y: float
    radius: float


@dataclass(frozen=True)
class Ball:
    """A ball as the camera sees it: a sphere of ``radius`` resting on the floor at (x, y), of
    ``colour`` (red, green, blue in [0, 1]; None: the grey of its infra-red ``reflectance``)."""

    x: float
    y: float
    radius: float
    colour: tuple[float, float, float] | None
    reflectance: float
    #: The height of its centre (None: ``radius``, resting on the floor).
    z: float | None = None


@dataclass(frozen=True)
class Block:
    """A box or an upright cylinder with physics as the camera sees it, standing on the floor
    at (x, y): a box of ``size`` (its extents along its own axes, turned by ``yaw``), or with
    ``size`` None a cylinder of ``radius``; its top ``height`` above the floor, its bottom
    ``base``, of ``colour`` (as a :class:`Ball`'s) and infra-red ``reflectance``."""

    x: float
    y: float
    yaw: float
    size: tuple[float, float] | None
    radius: float
    height: float
    colour: tuple[float, float, float] | None
    reflectance: float
    #: The height of its bottom (0: standing on the floor; a shape a robot holds up).
    base: float = 0.0


@dataclass(frozen=True)
class CameraView:
    """Where a camera sits and what it sees: pose on the robot (``x`` forward, ``y`` left,
    ``z`` up, m; ``yaw`` its heading left of the robot's forward, ``pitch`` its tilt down, rad),
    image size, field of view; ``axes`` its forward, left and up directions in the robot's
    frame when it is also turned about its view (a camera on a tilted robot), else None."""

    width: int = DEFAULT_WIDTH
    height: int = DEFAULT_HEIGHT
    fov: float = DEFAULT_FOV
    x: float = CAMERA_X
    z: float = CAMERA_Z
    pitch: float = 0.0
    wall_height: float = WALL_HEIGHT
    y: float = 0.0
    yaw: float = 0.0
    axes: Axes | None = None


def node_view(entry: Mapping[str, Any], y_up: bool, mount: Mount | None = None) -> CameraView:
    """The view of a Camera node the import lists among the robot's devices (an entry of
    ``extension_devices``): its ``width``, ``height`` and ``fieldOfView`` (Webots' defaults 64,
    64 and 0.7854 where the node has none), where it sits and where it looks: along its x axis
    (Webots R2022a on), or its -z axis in a file before (``y_up``); on a robot node raised or
    tilted (``mount``, a robot that mazesim does not move), from the camera's full pose."""
    fields: Mapping[str, Any] = entry.get("fields") or {}
    x, y, z = (float(v) for v in (entry.get("translation") or (0.0, 0.0, 0.0))[:3])
    yaw, pitch = float(entry.get("yaw", 0.0)), float(entry.get("pitch", 0.0))
    axes = axes_or_none(entry.get("axes"))
    turned: Axes | None = None
    if axes is not None:
        # Forward, left and up of the camera's image in the robot's frame.
        looks: Axes = (axes[0], axes[1], axes[2])
        if y_up:
            looks = (_opposite(axes[2]), _opposite(axes[0]), axes[1])
        if mount is not None:
            x, y, z = mount.point((x, y, z))
            turned = tuple(mount.direction(v) for v in looks)
            looks = turned
        yaw, pitch = camera_heading(looks[0])
    elif mount is not None:
        x, y, z = mount.point((x, y, z))
    named = f"Camera {_shown(str(entry.get('name', 'camera')))}"
    return CameraView(
        width=device_side(fields.get("width"), 64, f"{named} width"),
        height=device_side(fields.get("height"), 64, f"{named} height"),
        fov=float(fields.get("fieldOfView", 0.7854)),
        x=x,
        y=y,
        z=max(z, 0.001),
        pitch=pitch,
        yaw=yaw,
        axes=turned,
    )


def _opposite(v: tuple[float, float, float]) -> tuple[float, float, float]:
    return (-v[0], -v[1], -v[2])


def render(
    view: CameraView,
    walls: WallBoxes,
    floor: FloorPaint,
    pose: tuple[float, float, float],
    robots: Sequence[RobotBody] = (),
    balls: Sequence[Ball] = (),
    blocks: Sequence[Block] = (),
) -> npt.NDArray[np.uint8]:
    """Renders the view from a robot pose.

    Args:
        view: The camera.
        walls: The world's walls.
        floor: The world's floor paint.
        pose: The robot's x, y, yaw.
        robots: The other robots, where they are now.
        balls: The balls, where they are now.
        blocks: The boxes and cylinders with physics, where they are now.

    Returns:
        A (height, width, 4) array of B, G, R, A.
    """
    dx, dy, rise = _rays(view, pose[2])
    ox, oy = _lens(view, pose)
    with np.errstate(divide="ignore", invalid="ignore"):
        floor_t = np.where(rise < 0.0, view.z / -rise, np.inf)
    # Each wall stands from the floor to its top (``view.wall_height`` where the world gives
    # none): a ray passes over a lower one or lands on its top.
    if view.pitch == 0.0 and view.axes is None:
        # A level camera: every row of a column casts along the same line across the floor.
        columns = np.stack([dx[0], dy[0]], axis=1)
        wall_t, wall, _ = walls.cast_sloped((ox, oy), columns, view.z, rise, view.wall_height)
    else:
        # Each pixel casts its own ray; one that meets the floor nearer than the nearest wall
        # is, seen from above, sees the floor whatever wall it would meet: it casts none.
        reach = floor_t * np.hypot(dx, dy)
        casts = ~(reach < walls.nearest_distance((ox, oy)))
        wall_t = np.full(rise.shape, np.inf)
        wall = np.full(rise.shape, -1, dtype=np.intp)
        if casts.any():
            directions = np.stack([dx[casts], dy[casts]], axis=1)
            wall_t[casts], wall[casts], _ = walls.cast_sloped(
                (ox, oy), directions, view.z, rise[casts], view.wall_height
            )
    sees_wall = np.isfinite(wall_t) & (wall_t <= floor_t)
    robot_t = _robot_hits(view, (ox, oy), dx, dy, rise, robots)
    sees_robot = np.isfinite(robot_t) & (robot_t <= floor_t)
    sees_robot &= ~(sees_wall & (wall_t < robot_t))
    sees_wall &= ~sees_robot
    bodies: list[Ball | Block] = [*balls, *blocks]
    ball_t, ball = _body_hits(view, (ox, oy), dx, dy, rise, bodies)
    sees_ball = np.isfinite(ball_t) & (ball_t <= floor_t)
    sees_ball &= ~(sees_wall & (wall_t < ball_t)) & ~(sees_robot & (robot_t < ball_t))
    sees_wall &= ~sees_ball
    sees_robot &= ~sees_ball
    sees_floor = ~sees_wall & ~sees_robot & ~sees_ball & np.isfinite(floor_t)
    # Each pixel's entry of one palette: the sky, the floor's regions, the walls, a robot's
    # plate and body, the bodies; the image is then one gather of the palette's colours.
    floor_colours, wall_colours = _palette_of(floor), _palette_of(walls)
    body_colours = _levels(
        np.array([b.reflectance for b in bodies]),
        np.array([b.colour or (math.nan,) * 3 for b in bodies], dtype=np.float64).reshape(-1, 3),
        WALL_SHADE,
    )[:, ::-1]
    robot_colours = _levels(np.ones(2), np.array([PLATE_COLOUR, ROBOT_COLOUR]), WALL_SHADE)[:, ::-1]
    sky = np.array([SKY[::-1]], dtype=np.uint8)
    palette = np.concatenate([sky, floor_colours, wall_colours, robot_colours, body_colours])
    entry = np.zeros(rise.shape, dtype=np.intp)
    first_wall = 1 + len(floor_colours)
    first_robot = first_wall + len(wall_colours)
    if sees_floor.any():
        t = floor_t[sees_floor]
        region = floor.region(ox + t * dx[sees_floor], oy + t * dy[sees_floor]) + 1
        entry[sees_floor] = 1 + region
    if sees_wall.any():
        entry[sees_wall] = first_wall + wall[sees_wall]
    if sees_robot.any():
        height = view.z + robot_t[sees_robot] * rise[sees_robot]
        plate = (height >= PLATE_EDGE[0]) & (height <= PLATE_EDGE[1])
        entry[sees_robot] = np.where(plate, first_robot, first_robot + 1)
    if sees_ball.any():
        entry[sees_ball] = first_robot + 2 + ball[sees_ball]
    image = np.empty(rise.shape + (4,), dtype=np.uint8)
    image[..., :3] = palette[entry]
    image[..., 3] = 255
    return image


def _rays(
    view: CameraView, yaw: float
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Each pixel's ray (height, width) from a robot heading ``yaw``: its x and y in the
    world and its rise, per unit along the camera's forward axis."""
    focal = (view.width / 2.0) / math.tan(view.fov / 2.0)
    left = (view.width / 2.0 - (np.arange(view.width) + 0.5)) / focal
    up = (view.height / 2.0 - (np.arange(view.height) + 0.5)) / focal
    if view.axes is not None:
        ahead, aside, above = (np.asarray(v, dtype=np.float64) for v in view.axes)
        ray = (
            ahead[None, None, :]
            + left[None, :, None] * aside[None, None, :]
            + up[:, None, None] * above[None, None, :]
        )
        cos_r, sin_r = math.cos(yaw), math.sin(yaw)
        dx = cos_r * ray[..., 0] - sin_r * ray[..., 1]
        dy = sin_r * ray[..., 0] + cos_r * ray[..., 1]
        return dx, dy, np.ascontiguousarray(ray[..., 2])
    cos_y, sin_y = math.cos(yaw + view.yaw), math.sin(yaw + view.yaw)
    if view.pitch == 0.0:
        # A level camera: a column's rays run along one line, a row's rise alike; read-only
        # views of one column and one row, not arrays of every pixel.
        shape = (view.height, view.width)
        dx = np.broadcast_to(cos_y - sin_y * left, shape)
        dy = np.broadcast_to(sin_y + cos_y * left, shape)
        return dx, dy, np.broadcast_to(up[:, None], shape)
    # Pitch (down positive) turns each ray about the camera's left axis.
    cos_p, sin_p = math.cos(view.pitch), math.sin(view.pitch)
    forward = cos_p + sin_p * up[:, None] * np.ones_like(left)[None, :]
    rise = up[:, None] * cos_p - sin_p * np.ones_like(left)[None, :]
    dx = cos_y * forward - sin_y * left[None, :]
    dy = sin_y * forward + cos_y * left[None, :]
    return dx, dy, rise


def _lens(view: CameraView, pose: Sequence[float]) -> tuple[float, float]:
    """Where the camera's lens is, seen from above, on a robot at ``pose`` (x, y, yaw)."""
    x, y, yaw = pose[0], pose[1], pose[2]
    cos_y, sin_y = math.cos(yaw), math.sin(yaw)
    return x + cos_y * view.x - sin_y * view.y, y + sin_y * view.x + cos_y * view.y


def _body_hits(
    view: CameraView,
    origin: tuple[float, float],
    dx: npt.NDArray[np.float64],
    dy: npt.NDArray[np.float64],
    rise: npt.NDArray[np.float64],
    bodies: Sequence[Ball | Block],
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.intp]]:
    """The ray parameter at which each ray meets the nearest movable body (``inf`` where none),
    and which body it meets."""
    nearest = np.full(rise.shape, np.inf)
    which = np.zeros(rise.shape, dtype=np.intp)
    for index, body in enumerate(bodies):
        if isinstance(body, Ball):
            t = _sphere_t(view, origin, dx, dy, rise, body)
        else:
            t = _block_t(view, origin, dx, dy, rise, body)
        closer = t < nearest
        nearest = np.where(closer, t, nearest)
        which = np.where(closer, index, which)
    return nearest, which


def _sphere_t(
    view: CameraView,
    origin: tuple[float, float],
    dx: npt.NDArray[np.float64],
    dy: npt.NDArray[np.float64],
    rise: npt.NDArray[np.float64],
    ball: Ball,
) -> npt.NDArray[np.float64]:
    """Where each ray meets a ball resting on the floor (``inf`` where it does not)."""
    # |origin + t d - centre| = radius in 3D, the centre ``radius`` above the floor.
    centre = ball.radius if ball.z is None else ball.z
    cx, cy, cz = origin[0] - ball.x, origin[1] - ball.y, view.z - centre
    a = dx * dx + dy * dy + rise * rise
    b = cx * dx + cy * dy + cz * rise
    c = cx * cx + cy * cy + cz * cz - ball.radius * ball.radius
    disc = b * b - a * c
    with np.errstate(invalid="ignore", divide="ignore"):
        t = (-b - np.sqrt(disc)) / a
    return np.where((disc >= 0.0) & (t >= 0.0), t, np.inf)


def _block_t(
    view: CameraView,
    origin: tuple[float, float],
    dx: npt.NDArray[np.float64],
    dy: npt.NDArray[np.float64],
    rise: npt.NDArray[np.float64],
    block: Block,
) -> npt.NDArray[np.float64]:
    """Where each ray meets a box or upright cylinder standing on the floor, on its side below
    its top or on its top (``inf`` where it does not)."""
    ox, oy = origin[0] - block.x, origin[1] - block.y
    with np.errstate(invalid="ignore", divide="ignore"):
        if block.size is None:
            # The ray's horizontal path enters and leaves the disc at the roots of
            # a t^2 + 2 b t + c = 0.
            a = dx * dx + dy * dy
            b = ox * dx + oy * dy
            c = ox * ox + oy * oy - block.radius * block.radius
            root = np.sqrt(b * b - a * c)
            enter, leave = (-b - root) / a, (-b + root) / a
        else:
            # The box's own axes: the ray's path crosses each pair of faces (slabs).
            cos_y, sin_y = math.cos(block.yaw), math.sin(block.yaw)
            enter = np.full(rise.shape, -np.inf)
            leave = np.full(rise.shape, np.inf)
            for half, start, step in (
                (block.size[0] / 2.0, cos_y * ox + sin_y * oy, cos_y * dx + sin_y * dy),
                (block.size[1] / 2.0, -sin_y * ox + cos_y * oy, -sin_y * dx + cos_y * dy),
            ):
                near, far = (-half - start) / step, (half - start) / step
                # A path along the faces' plane is inside the slab throughout, or never.
                inside = np.abs(start) <= half
                near = np.where(step == 0.0, np.where(inside, -np.inf, np.inf), near)
                far = np.where(step == 0.0, np.where(inside, np.inf, -np.inf), far)
                enter = np.maximum(enter, np.minimum(near, far))
                leave = np.minimum(leave, np.maximum(near, far))
        top_t = (block.height - view.z) / rise
    crosses = (enter <= leave) & (enter >= 0.0)
    height = view.z + np.where(crosses, enter, 0.0) * rise
    side = crosses & (height >= block.base) & (height <= block.height)
    # Over the top edge (or above the footprint), a ray going down lands on the top before it
    # leaves the footprint.
    top = (enter <= leave) & (rise < 0.0) & (top_t >= np.maximum(enter, 0.0)) & (top_t <= leave)
    return np.where(side, enter, np.where(top, top_t, np.inf))


def _robot_hits(
    view: CameraView,
    origin: tuple[float, float],
    dx: npt.NDArray[np.float64],
    dy: npt.NDArray[np.float64],
    rise: npt.NDArray[np.float64],
    robots: Sequence[RobotBody],
) -> npt.NDArray[np.float64]:
    """The ray parameter at which each ray meets the nearest other robot's body between its
    bottom and top, or its top seen from above (``inf`` where none)."""
    nearest = np.full(rise.shape, np.inf)
    for robot in robots:
        # |origin + t d - centre| = radius, with d horizontal: a t^2 + 2 b t + c = 0.
        cx, cy = origin[0] - robot.x, origin[1] - robot.y
        a = dx * dx + dy * dy
        b = cx * dx + cy * dy
        c = cx * cx + cy * cy - robot.radius * robot.radius
        disc = b * b - a * c
        with np.errstate(invalid="ignore", divide="ignore"):
            root = np.sqrt(disc)
            enter, leave = (-b - root) / a, (-b + root) / a
            top_t = (ROBOT_TOP - view.z) / rise
        t = np.where((disc >= 0.0) & (enter >= 0.0), enter, np.inf)
        height = view.z + np.where(np.isfinite(t), t, 0.0) * rise
        t = np.where((height <= ROBOT_TOP) & (height >= ROBOT_BOTTOM), t, np.inf)
        # A ray going down from above the body lands on its top inside the disc.
        top = (disc >= 0.0) & (rise < 0.0) & (top_t >= np.maximum(enter, 0.0)) & (top_t <= leave)
        t = np.where(top, np.minimum(t, top_t), t)
        nearest = np.minimum(nearest, t)
    return nearest


#: What a camera samples: the robot's pose, the other robots and the movable bodies.
_Sample = tuple[tuple[float, float, float], list[RobotBody], list[Union[Ball, Block]]]


def drawn_body(pose: Sequence[float], body: Mapping[str, Any]) -> Ball | Block:
    """A movable body of the import report (``kind``, ``size`` or ``radius``, ``colour``,
    ``sphere``, ``height``, ``reflectance``) at ``pose`` (x, y, yaw) as the camera draws it: a
    ball when its collision shape is a sphere, else a box or an upright cylinder."""
    colour = body.get("colour")
    look = None if colour is None else (float(colour[0]), float(colour[1]), float(colour[2]))
    reflectance = float(body.get("reflectance", 1.0))
    x, y, yaw = (float(v) for v in pose[:3])
    if body.get("kind") == "circle":
        radius = float(body["radius"])
        if body.get("sphere"):
            return Ball(x, y, radius, look, reflectance)
        return Block(x, y, yaw, None, radius, _height(body, 2.0 * radius), look, reflectance)
    width, depth = (float(v) for v in body["size"])
    height = _height(body, min(width, depth))
    return Block(x, y, yaw, (width, depth), 0.0, height, look, reflectance)


def placed_shape(shape: RobotShape, pose: Sequence[float]) -> Ball | Block:
    """A robot's visual shape where the robot stands at ``pose`` (x, y, yaw), as the camera
    draws it: 80 % of its colour, or the grey of a white surface when it gives none."""
    x, y, yaw = (float(v) for v in pose[:3])
    c, s = math.cos(yaw), math.sin(yaw)
    cx, cy = x + c * shape.x - s * shape.y, y + s * shape.x + c * shape.y
    if shape.sphere:
        centre = (shape.bottom + shape.top) / 2.0
        return Ball(cx, cy, shape.radius, shape.colour, 1.0, z=centre)
    return Block(
        cx, cy, yaw + shape.yaw, shape.size, shape.radius, shape.top, shape.colour, 1.0,
        base=shape.bottom,
    )  # fmt: skip


def solids_now(
    simulation: RobotSimulation, robots: OtherRobots, visual: bool = True
) -> list[Ball | Block]:
    """What a camera of ``simulation``'s robot draws beside the walls, the floor and the other
    robots' bodies, where it is now: the world's movable bodies (those a supervisor imported
    too, not those it removed) and, with ``visual``, the visual shapes of the other robots of
    a world run (an e-puck's that its drawn body holds left out)."""
    from mazesim.webots.solids import world_objects

    drawn = [drawn_body(pose, body) for pose, body in world_objects(simulation).drawn_bodies()]
    if not visual:
        return drawn
    drawn.extend(
        placed_shape(shape, pose)
        for shape, pose, e_puck in robots.shapes_now()
        if not (e_puck and _inside_body(shape))
    )
    return drawn


def _inside_body(shape: RobotShape) -> bool:
    """Whether an e-puck's visual shape lies inside the body the camera draws for it."""
    reach = shape.radius if shape.size is None else math.hypot(*shape.size) / 2.0
    return (
        shape.bottom >= ROBOT_BOTTOM - 1e-9
        and shape.top <= ROBOT_TOP + 1e-9
        and math.hypot(shape.x, shape.y) + reach <= ROBOT_RADIUS + 1e-9
    )


def _height(body: Mapping[str, Any], otherwise: float) -> float:
    """A body's ``height``, or ``otherwise`` for a report without one (a mazesim world's)."""
    height = body.get("height")
    return float(height) if height else otherwise


def _palette_of(surfaces: FloorPaint | WallBoxes) -> npt.NDArray[np.uint8]:
    """Blue, green and red levels ((N, 3)) of the floor's regions (the bare floor first) or of
    the walls, as a camera sees them; made once per floor or walls."""
    made = _PALETTES.get(surfaces)
    if made is None:
        if isinstance(surfaces, FloorPaint):
            levels = _levels(surfaces.reflectances, surfaces.colours, 1.0)
        else:
            levels = _levels(surfaces.reflectance, surfaces.colour, WALL_SHADE)
        made = _PALETTES[surfaces] = np.ascontiguousarray(levels[:, ::-1])
    return made


#: The palette of each floor and walls a camera drew (their colours do not change).
_PALETTES: weakref.WeakKeyDictionary[FloorPaint | WallBoxes, npt.NDArray[np.uint8]] = (
    weakref.WeakKeyDictionary()
)


def _levels(
    reflectance: npt.NDArray[np.float64], colour: npt.NDArray[np.float64], shade: float
) -> npt.NDArray[np.uint8]:
    """Red, green and blue levels ((N, 3)) of surfaces of these reflectances and colours
    (NaN: none given, grey from the reflectance), ``shade`` of full light."""
    grey = np.clip((reflectance - 0.2) / 0.8, 0.0, 1.0) * 255.0 * shade
    level = np.where(np.isnan(colour), grey[:, None], colour * 255.0 * shade)
    return np.asarray(np.rint(level), dtype=np.uint8)


class CameraRecognitionObject:
    """An object the camera recognises (see :mod:`mazesim.webots.recognition`); one made
    without ``seen`` holds nothing (NaN position, no colour)."""

    def __init__(self, seen: RecognisedObject | None = None) -> None:
        self.id = -1
        self.position = [math.nan] * 3
        self.orientation = [math.nan] * 4
        self.size = [math.nan] * 2
        self.position_on_image = [0, 0]
        self.size_on_image = [0, 0]
        self.number_of_colors = 0
        self.colors: list[float] = []
        self.model = ""
        if seen is not None:
            self.id = seen.id
            self.position = list(seen.position)
            self.orientation = list(seen.orientation)
            self.size = list(seen.size)
            self.position_on_image = list(seen.position_on_image)
            self.size_on_image = list(seen.size_on_image)
            self.number_of_colors = len(seen.colors) // 3
            self.colors = list(seen.colors)
            self.model = seen.model

    def getId(self) -> int:
        """The object's node id."""
        return self.id

    def getPosition(self) -> list[float]:
        """The position of the object's centre in the camera's frame (m)."""
        return self.position

    def getOrientation(self) -> list[float]:
        """The object's orientation relative to the camera (axis-angle)."""
        return self.orientation

    def getSize(self) -> list[float]:
        """The object's width and height as the camera sees it (m)."""
        return self.size

    def getPositionOnImage(self) -> list[int]:
        """The centre of the object's box on the image (pixels)."""
        return self.position_on_image

    def getSizeOnImage(self) -> list[int]:
        """The size of the object's box on the image (pixels)."""
        return self.size_on_image

    def getNumberOfColors(self) -> int:
        """How many colours the object has."""
        return self.number_of_colors

    def getColors(self) -> list[float]:
        """The object's colours: red, green and blue of each."""
        return self.colors

    def getModel(self) -> str:
        """The object's ``model`` field."""
        return self.model

    # The spelling of Webots' Python API before R2023a (its SWIG-made module): controllers
    # written then call ``get_position_on_image()``, ``get_colors()``...
    get_id = getId
    get_position = getPosition
    get_orientation = getOrientation

    def get_size(self) -> list[int]:
        """The object's size as the SWIG-made API before R2023a gave it: each metre figure
        truncated to an int (its ``PyInt_FromLong(size[i])``; 0 for an object under 1 m)."""
        return [int(v) for v in self.size]

    get_position_on_image = getPositionOnImage
    get_size_on_image = getSizeOnImage
    get_number_of_colors = getNumberOfColors
    get_colors = getColors

    def get_model(self) -> bytes:
        """The object's ``model`` field as bytes, as the SWIG-made API before R2023a gave it
        (``PyBytes_FromStringAndSize``; controllers of then call ``get_model().decode()``)."""
        return self.model.encode("utf-8")


class Camera(_Sensor):
    """The e-puck's ``camera``: images of the forward view, refreshed every sampling period."""

    _node_type = node_type("CAMERA")

    COLOR = 0
    RANGE_FINDER = 1
    BOTH = 2
    _api = "wb_camera"

    def __init__(self, name: str, simulation: RobotSimulation, view: CameraView) -> None:
        super().__init__(name, simulation)
        self._view = view
        #: The walls and floor now (a supervisor's changes followed), and those of the last
        #: sample, which its image is drawn against.
        self._walls_now = WallsNow(simulation, sensed=True)
        self._walls: WallBoxes | None = None
        self._floor: FloorPaint | None = None
        self._pixels: npt.NDArray[np.uint8] | None = None
        self._bytes: bytes | None = None
        #: The robot's pose and the other robots when the camera last sampled (its image is
        #: drawn from them only when the controller asks for it), and those of the last image
        #: drawn.
        self._sampled: _Sample | None = None
        self._rendered_at: _Sample | None = None
        self._rendered_walls: WallBoxes | None = None
        self._rendered_floor: FloorPaint | None = None
        self._value = None
        self._robots = OtherRobots.of(simulation)
        self._recogniser = recogniser_of(
            simulation.report, name, old_frame=simulation.scene.y_up_devices
        )
        #: The walls recognition casts against, none moved (it moves them itself).
        self._recognised_walls = WallsNow(simulation)
        self._recognition_period_ms = 0
        self._recognition_steps = 0
        self._recognition_from = 0
        self._recognised: list[CameraRecognitionObject] = []

    def _read(self) -> Any:
        self._walls = self._walls_now.walls()
        self._floor = self._walls_now.floor()
        x, y, yaw = (float(v) for v in self._simulation.simulator.pose)
        bodies = solids_now(self._simulation, self._robots)
        self._sampled = ((x, y, yaw), self._other_robots(), bodies)
        return True

    def _drawn(self) -> npt.NDArray[np.uint8] | None:
        """The image of the last sample, drawn at the first call that asks for it (a camera
        enabled and never read draws nothing), and drawn again only when the robot, another
        robot or a movable body has moved (or a supervisor moved walls or floor marks) since
        the last image; None before the first sample."""
        if self._sampled is None or self._walls is None or self._floor is None:
            return None
        if (
            self._pixels is None
            or self._rendered_at != self._sampled
            or self._rendered_walls is not self._walls
            or self._rendered_floor is not self._floor
        ):
            pose, robots, bodies = self._sampled
            balls = [body for body in bodies if isinstance(body, Ball)]
            blocks = [body for body in bodies if isinstance(body, Block)]
            self._bytes = None
            self._pixels = render(self._view, self._walls, self._floor, pose, robots, balls, blocks)
            self._rendered_at = self._sampled
            self._rendered_walls = self._walls
            self._rendered_floor = self._floor
        return self._pixels

    def _other_robots(self) -> list[RobotBody]:
        """The other robots of the world run where they are now (none in a run of one
        robot)."""
        return [RobotBody(x, y, radius) for x, y, radius in self._robots.now()]

    def _image(self) -> npt.NDArray[np.uint8] | None:
        if self._period_ms == 0 and self._sampled is None:
            self._warn_disabled("get_image")
        if self._sampled is None and self._period_ms and self._simulation.steps > self._enabled_at:
            # Webots' wb_camera_get_image returns an enabled camera's image buffer, set up at
            # the first step after the camera is enabled and drawn when its first sampling
            # period ends (src/controller/c/camera.c, WbSensor.cpp): black until then.
            return np.zeros((self._view.height, self._view.width, 4), dtype=np.uint8)
        return self._drawn()

    def getImage(self) -> bytes | None:
        """The last image: ``width * height * 4`` bytes, B G R A per pixel, row after row;
        black from the step after the camera is enabled until its first sampling period has
        passed (Webots' buffer before its first image), None before."""
        pixels = self._image()
        if pixels is None:
            return None
        if self._bytes is None:
            self._bytes = pixels.tobytes()
        return self._bytes

    def getImageArray(self) -> list[list[list[int]]] | None:
        """The last image as ``image[x][y] = [r, g, b]`` (Webots' column-major lists)."""
        pixels = self._image()
        if pixels is None:
            return None
        rgb = pixels[:, :, 2::-1].transpose(1, 0, 2)
        return rgb.tolist()

    def getWidth(self) -> int:
        """Image width in pixels."""
        return self._view.width

    def getHeight(self) -> int:
        """Image height in pixels."""
        return self._view.height

    def getFov(self) -> float:
        """Horizontal field of view in radians."""
        return self._view.fov

    def setFov(self, fov: float) -> None:
        """Fixed in the e-puck's camera (no zoom): Webots' error, the field stays."""
        _print_error("Error: wb_camera_set_fov() can only be called on a zoom camera.")

    def getMinFov(self) -> float:
        """The field of view (no zoom)."""
        return self._view.fov

    def getMaxFov(self) -> float:
        """The field of view (no zoom)."""
        return self._view.fov

    def getFocalLength(self) -> float:
        """0: the camera has no focus."""
        return 0.0

    def getFocalDistance(self) -> float:
        """0: the camera has no focus."""
        return 0.0

    def getMinFocalDistance(self) -> float:
        """0: the camera has no focus."""
        return 0.0

    def getMaxFocalDistance(self) -> float:
        """0: the camera has no focus."""
        return 0.0

    def setFocalDistance(self, distance: float) -> None:
        """Webots' error: the camera has no focus."""
        _print_error(
            "Error: wb_camera_set_focal_distance() can only be called on a camera with focus."
        )

    def getNear(self) -> float:
        """The near clipping plane (m) of the E-puck PROTO's camera."""
        return 0.0055

    def getExposure(self) -> float:
        """The exposure (Webots' default 1)."""
        return 1.0

    def setExposure(self, exposure: float) -> None:
        """Accepted; the rendering has no exposure."""

    def _after_step(self) -> None:
        super()._after_step()
        steps = self._recognition_steps
        if steps and (self._simulation.steps - self._recognition_from) % steps == 0:
            self._recognised = [CameraRecognitionObject(seen) for seen in self._recognise()]

    def _recognise(self) -> list[RecognisedObject]:
        """What the camera's Recognition node recognises now."""
        recogniser = self._recogniser
        assert recogniser is not None
        simulation = self._simulation
        x, y, yaw = (float(v) for v in simulation.simulator.pose)
        view = self._view
        lens_x, lens_y = _lens(view, (x, y, yaw))
        camera = CameraPose(
            lens_x,
            lens_y,
            view.z,
            yaw + view.yaw,
            view.pitch,
            view.width,
            view.height,
            view.fov,
        )
        from mazesim.webots.solids import world_objects

        robots = None
        if recogniser.needs_robot_poses and simulation.fleet is not None:
            robots = simulation.fleet.poses()
        objects = world_objects(simulation)
        bodies = objects.body_poses() if recogniser.follows_bodies else None
        moves = objects.node_moves() if recogniser.follows_moves else None
        walls = self._recognised_walls.base()
        return recogniser.recognise(camera, walls, robots, bodies, moves)

    def _without_recognition(self, function: str) -> bool:
        """Whether the camera has no Recognition node (then with Webots' error)."""
        if self._recogniser is None:
            _print_error(
                f"Error: wb_camera_recognition_{function}() called on a Camera without "
                "Recognition node."
            )
            return True
        return False

    def hasRecognition(self) -> bool:
        """Whether the camera's node has a Recognition node (the e-puck's own camera has
        none; a project's e-puck PROTO may give it one)."""
        return self._recogniser is not None

    def recognitionEnable(self, samplingPeriod: int) -> None:
        """Recognises objects every ``samplingPeriod`` ms (rounded up to whole basic steps),
        from the end of the first period on; Webots' error without a Recognition node."""
        period = sampling_period(samplingPeriod, "wb_camera_recognition_enable")
        if period is None:
            return
        if self._without_recognition("enable"):
            return
        self._recognition_period_ms = period
        basic = self._simulation.basic_time_step_ms
        self._recognition_steps = max(1, math.ceil(period / basic - 1e-9)) if period else 0
        self._recognition_from = self._simulation.steps

    def recognitionDisable(self) -> None:
        """Stops recognising (the objects recognised last stay)."""
        if not self._without_recognition("disable"):
            self.recognitionEnable(0)

    def getRecognitionSamplingPeriod(self) -> int:
        """The period given to :meth:`recognitionEnable`, 0 when disabled."""
        if self._without_recognition("get_sampling_period"):
            return 0
        return self._recognition_period_ms

    def _recognition_reading(self, function: str) -> bool:
        """Whether the recognised objects can be read (else with Webots' error)."""
        if self._without_recognition(function):
            return False
        if self._recognition_period_ms == 0:
            _print_error(
                f"Error: wb_camera_recognition_{function}() called for a disabled device! "
                "Please use: wb_camera_recognition_enable()."
            )
            return False
        return True

    def getRecognitionNumberOfObjects(self) -> int:
        """How many objects the last recognition found (0 before the first period ends)."""
        if not self._recognition_reading("get_number_of_objects"):
            return 0
        return len(self._recognised)

    def getRecognitionObjects(self) -> list[CameraRecognitionObject]:
        """The objects the last recognition found, in world order."""
        if not self._recognition_reading("get_objects"):
            return []
        return list(self._recognised)

    def hasRecognitionSegmentation(self) -> bool:
        """False: segmentation images are not simulated."""
        return False

    def enableRecognitionSegmentation(self) -> None:
        """Webots' error: without a Recognition node, or segmentation (not simulated)."""
        if not self._without_recognition("enable_segmentation"):
            _print_error(
                "Error: wb_camera_recognition_enable_segmentation(): segmentation is disabled "
                "in Recognition node."
            )

    def disableRecognitionSegmentation(self) -> None:
        """Nothing to disable."""

    def isRecognitionSegmentationEnabled(self) -> bool:
        """False."""
        return False

    def getRecognitionSegmentationImage(self) -> None:
        """None: no segmentation."""
        return None

    def getRecognitionSegmentationImageArray(self) -> None:
        """None: no segmentation."""
        return None

    def saveRecognitionSegmentationImage(self, filename: str, quality: int) -> int:
        """-1: no segmentation."""
        return -1

    def saveImage(self, filename: str | os.PathLike[str], quality: Any = 100) -> int:
        """Saves the last image as PNG or JPEG (by the file's extension), a JPEG of
        ``quality`` (1-100) as Webots writes one (stb_image_write: its colours at full
        resolution above quality 90, at half resolution from 90 down). As in Webots (its
        camera.c; the reference manual: "for PNG images, the quality parameter is ignored"), a
        PNG's ``quality`` is not read at all (a public controller passes ``'PNG'``), and a
        JPEG's that is no whole number from 1 to 100 prints Webots' error and saves nothing.

        Returns:
            0 on success, -1 on failure (no image yet, unknown extension, a JPEG's quality out
            of range, unwritable file).

        Raises:
            WrongTypeError: ``filename`` is no text or path object of text (or one that cannot
                say its path).
        """
        try:
            filename = os.fspath(filename)
        except Exception as failure:
            raise WrongTypeError(
                f"Camera.saveImage: expected a file name, found {type(filename).__name__} "
                f"({failure})"
            ) from failure
        if not isinstance(filename, str):
            raise WrongTypeError(
                f"Camera.saveImage: expected a file name as text, found {type(filename).__name__}"
            )
        pixels = self._drawn()
        extension = os.path.splitext(filename)[1].lower()
        if extension not in (".png", ".jpg", ".jpeg"):
            # Webots' camera.c, word for word.
            _print_error(
                "Error: wb_camera_save_image() called with unsupported image format (should be "
                "PNG or JPEG)."
            )
            return -1
        jpeg = extension != ".png"
        if jpeg and not (_whole_number(quality) and 1 <= int(quality) <= 100):
            # Webots' camera.c, word for word.
            _print_error("Error: wb_camera_save_image() called with invalid 'quality' argument.")
            return -1
        if pixels is None:
            _print_error(f"Error: wb_camera_save_image() cannot save {_shown(filename)}.")
            return -1
        rgb = np.ascontiguousarray(pixels[:, :, 2::-1])
        try:
            if extension == ".png":
                from matplotlib import image as images

                images.imsave(filename, rgb)
            else:
                from PIL import Image

                level = int(quality)
                subsampling = 0 if level > JPEG_FULL_COLOUR_ABOVE else 2
                Image.fromarray(rgb).save(filename, "JPEG", quality=level, subsampling=subsampling)
        except (OSError, ValueError):
            return -1
        return 0

    # The per-pixel accessors check their own arguments (a controller calls them thousands of
    # times a step, for every pixel it looks at: the surface's general check cost tens of
    # microseconds a call, more than the step's rendering) and refuse a pixel outside the image.
    @staticmethod
    @checks_own_arguments
    def imageGetRed(image: bytes, width: int, x: int, y: int) -> int:
        """The red level (0-255) of pixel (x, y) of a BGRA image."""
        return image[_pixel("imageGetRed", image, width, x, y) + 2]

    @staticmethod
    @checks_own_arguments
    def imageGetGreen(image: bytes, width: int, x: int, y: int) -> int:
        """The green level (0-255) of pixel (x, y) of a BGRA image."""
        return image[_pixel("imageGetGreen", image, width, x, y) + 1]

    @staticmethod
    @checks_own_arguments
    def imageGetBlue(image: bytes, width: int, x: int, y: int) -> int:
        """The blue level (0-255) of pixel (x, y) of a BGRA image."""
        return image[_pixel("imageGetBlue", image, width, x, y)]

    @staticmethod
    @checks_own_arguments
    def imageGetGray(image: bytes, width: int, x: int, y: int) -> int:
        """The grey level (0-255, the mean of red, green and blue) of pixel (x, y)."""
        base = _pixel("imageGetGray", image, width, x, y)
        return (image[base] + image[base + 1] + image[base + 2]) // 3

    @staticmethod
    @checks_own_arguments
    def imageGetGrey(image: bytes, width: int, x: int, y: int) -> int:
        """Same as :meth:`imageGetGray`."""
        base = _pixel("imageGetGrey", image, width, x, y)
        return (image[base] + image[base + 1] + image[base + 2]) // 3


#: What the per-pixel accessors take as an image: ``getImage``'s bytes, or a copy of them.
_IMAGE_TYPES = (bytes, bytearray, memoryview)


def _pixel(name: str, image: Any, width: Any, x: Any, y: Any) -> int:
    """The offset of pixel (x, y)'s first byte (blue) in a BGRA ``image`` ``width`` pixels wide.

    Raises:
        WrongTypeError: The image is not bytes, or width, x or y not an int.
        InvalidArgumentError: The pixel is outside the image.
    """
    if type(image) is bytes and type(width) is int and type(x) is int and type(y) is int:
        base = 4 * (y * width + x)
        if 0 <= x < width and y >= 0 and base + 4 <= len(image):
            return base  # the common case, checked at the least cost
    for label, value in (("width", width), ("x", x), ("y", y)):
        if type(value) is not int and (isinstance(value, bool) or not isinstance(value, Integral)):
            raise WrongTypeError(
                f"Camera.{name}: expected {label} as an int, found {type(value).__name__} "
                f"{_shown(value)}"
            )
    if not isinstance(image, _IMAGE_TYPES):
        raise WrongTypeError(
            f"Camera.{name}: expected the image getImage returned (bytes), found "
            f"{type(image).__name__}"
        )
    base = 4 * (int(y) * int(width) + int(x))
    if not (0 <= x < width and y >= 0 and base + 4 <= len(image)):
        raise InvalidArgumentError(
            f"Camera.{name}: expected a pixel inside the image ({width} pixels wide, "
            f"{len(image) // 4} pixels in all), found ({x}, {y}); x runs from 0 to width - 1"
        )
    return base


def _whole_number(value: Any) -> bool:
    """Whether ``value`` is a whole number (an int, a numpy integer), not a flag or a text."""
    return isinstance(value, (int, np.integer)) and not isinstance(value, bool)
