"""Sensors computed in Python from the robot's pose and motion: light sensors, accelerometer,
gyro, GPS, compass, inertial unit, touch sensor, and distance sensors the world adds.

Frames are Webots' since R2022a (ENU): the world's x east, y north, z up; a device's x forward,
y left, z up. Each sensor maps its physical quantity through its lookup table (interpolated
linearly, clamped at both ends) and adds Gaussian noise of the table's relative standard
deviation, seeded from the run's seed and the device's name.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, ClassVar

import numpy as np
import numpy.typing as npt

from mazesim.webots.devices import (
    DistanceSensor,
    LookupTable,
    Row,
    _ScalarSensor,
    _Tabled,
    _VectorSensor,
    derived_reading,
    noise_stream,
)
from mazesim.webots.distance_rays import DistanceRays, RayHits, sensor_distance
from mazesim.webots.distance_rays import sensor_type as read_sensor_type
from mazesim.webots.frames import Axes, axes_or_none, enu_to_nue, nue_to_enu
from mazesim.webots.lights import irradiance
from mazesim.webots.node_types import node_type
from mazesim.webots.robot_frames import Footprint
from mazesim.webots.walls_now import ObstaclesNow, OtherRobots, WallsNow

if TYPE_CHECKING:
    from mazesim.webots.simulation import RobotSimulation

Floats = npt.NDArray[np.float64]

__all__ = [
    "Accelerometer",
    "Compass",
    "DeviceMount",
    "GPS",
    "Gyro",
    "InertialUnit",
    "LightSensor",
    "LookupTable",
    "RayDistanceSensor",
    "TouchSensor",
]

#: Standard gravity (m/s^2), what an accelerometer at rest reads along z.
GRAVITY = 9.81
#: The light sensors' table of Webots' E-puck PROTO (ls0-ls7 ``lookupTable [1 4095 0.01 2 0
#: 0.01]``): irradiance (W/m^2), value, relative noise; 1 W/m^2 or less reads 4095.
LIGHT_TABLE = ((1.0, 4095.0, 0.01), (2.0, 0.0, 0.01))
#: The accelerometer's table of the E-puck PROTO (``[-100 -100 0.003 100 100 0.003]``): m/s^2 in
#: and out, 0.3 % noise.
ACCELEROMETER_TABLE = ((-100.0, -100.0, 0.003), (100.0, 100.0, 0.003))
#: The gyro's table of the E-puck PROTO (``[-13.315805 -100000 0.003 13.315805 100000 0.003]``):
#: rad/s in, raw counts out (about 7,510 a rad/s), 0.3 % noise.
GYRO_TABLE = ((-13.315805, -100000.0, 0.003), (13.315805, 100000.0, 0.003))
#: Webots' default DistanceSensor table (generic, 0.1 m).
DISTANCE_TABLE = ((0.0, 0.0, 0.0), (0.1, 1000.0, 0.0))
#: North in the world frame (Webots' WorldInfo.northDirection default since R2022a).
NORTH = (0.0, 1.0, 0.0)
#: North in the world frame of a world before R2022a (``WorldInfo.northDirection``'s default
#: there, the NUE file's x).
NUE_NORTH = nue_to_enu(1.0, 0.0, 0.0)[:2]
#: How far from the robot's up (as a component of a unit vector) a device's up axis may lean
#: and the device still read by its yaw alone.
LEVEL_TOLERANCE = 1e-6


class DeviceMount:
    """Where a device sits on the robot: translation (m) and yaw (rad) in the robot's frame,
    and, where the import gives them, the device's x, y and z axes in that frame (the import
    report's ``axes``: rows of three numbers). ``placed``: the frame is the floor's below the
    robot's node (a robot mazesim does not move, raised or tilted where its node stands), so
    the translation's z is the device's height above the floor."""

    def __init__(
        self,
        translation: Sequence[float] = (0.0, 0.0, 0.0),
        yaw: float = 0.0,
        pitch: float = 0.0,
        axes: Sequence[Sequence[float]] | None = None,
        placed: bool = False,
    ) -> None:
        padded = [*(float(v) for v in translation), 0.0, 0.0, 0.0][:3]
        self.x, self.y, self.z = padded
        self.yaw = float(yaw)
        #: How far the device's x axis points below the horizontal (rad).
        self.pitch = float(pitch)
        self.axes = axes_or_none(axes)
        self.placed = placed

    def height_above_floor(self, simulation: RobotSimulation) -> float:
        """The device's height above the floor: its own above the robot's origin, plus how
        high the origin rests (a plain Robot's on its wheels; an E-puck's is on the floor);
        a placed mount's own."""
        return self.z if self.placed else self.z + simulation.scene.origin_height

    def world_pose(self, pose: tuple[float, float, float]) -> tuple[float, float, float]:
        """The device's x, y, heading in the world for a robot pose."""
        x, y, yaw = pose
        c, s = math.cos(yaw), math.sin(yaw)
        return x + c * self.x - s * self.y, y + s * self.x + c * self.y, yaw + self.yaw


class _TableVector(_Tabled, _VectorSensor):
    """A three-axis sensor: a vector in the device frame through a lookup table."""

    _default_table: ClassVar[tuple[Row, ...]] = ()
    #: Whether the vector is in the device's own frame, which in the Y-up PROTOs of worlds
    #: before R2022a is x right, y up, z back (the ENU x forward, y left, z up before).
    _device_frame: ClassVar[bool] = False
    #: Whether the reading depends on how the device's frame is tilted on the robot, though it
    #: is no vector in that frame (an InertialUnit's attitude).
    _reads_tilt: ClassVar[bool] = False

    def __init__(
        self,
        name: str,
        simulation: RobotSimulation,
        mount: DeviceMount | None = None,
        table: Sequence[Sequence[float]] | None = None,
    ) -> None:
        super().__init__(name, simulation)
        self._mount = mount or DeviceMount()
        self._table = LookupTable(self._default_table if table is None else table)
        self._rng = noise_stream(simulation, name)

    def _read(self) -> list[float]:
        tilted = self._tilted_axes()
        if tilted is not None:
            robot = self._robot_vector()
            measured = tuple(sum(a * v for a, v in zip(axis, robot)) for axis in tilted)
        else:
            measured = self._measure()
            if self._device_frame and self._y_up_frame():
                measured = enu_to_nue(*measured)
        return [self._table(v, self._rng) for v in measured]

    def _y_up_frame(self) -> bool:
        """Whether the device, level on the robot, reads in a Y-up frame (x right, y up, z
        back): one of the e-puck's own (placed by no axes of the import) in a body modelled
        Y-up (``Scene.body_y_up``: a robot saved expanded from a file before R2022a, stood
        upright in a later one too); one the world places, in a Y-up PROTO (a file before
        R2022a). In a later file, the import's axes of a device in a Y-up body tilt it."""
        scene = self._simulation.scene
        return scene.body_y_up if self._mount.axes is None else scene.y_up_devices

    def _measure(self) -> tuple[float, float, float]:
        raise NotImplementedError

    def _robot_vector(self) -> tuple[float, float, float]:
        """The measured vector in the robot's frame (x forward, y left, z up)."""
        raise NotImplementedError

    def _tilted_axes(self) -> Axes | None:
        """The device's axes when it reads in its own frame and that frame is not the robot's
        turned about the vertical (its up axis, z, or y in a Y-up PROTO, is not the robot's
        up): a compass in the E-puck's groundSensorsSlot, whose frame is turned a quarter turn
        down; None otherwise (:meth:`_measure` then reads it, by its yaw)."""
        axes = self._mount.axes
        if not (self._device_frame or self._reads_tilt) or axes is None:
            return None
        up = axes[1] if self._simulation.scene.y_up_devices else axes[2]
        level = abs(up[0]) < LEVEL_TOLERANCE and abs(up[1]) < LEVEL_TOLERANCE and up[2] > 0.0
        return None if level else axes

    def _heading(self) -> float:
        return self._simulation.simulator.pose[2] + self._mount.yaw


class Accelerometer(_TableVector):
    """Specific force in the device frame (m/s^2): the body's acceleration plus 9.81 up (along
    z; along y in a world before R2022a, whose PROTOs are Y-up)."""

    _node_type = node_type("ACCELEROMETER")
    _device_frame = True

    _api = "wb_accelerometer"
    _default_table = ACCELEROMETER_TABLE

    def _measure(self) -> tuple[float, float, float]:
        ax, ay = self._simulation.acceleration
        heading = self._heading()
        c, s = math.cos(heading), math.sin(heading)
        return c * ax + s * ay, -s * ax + c * ay, GRAVITY

    def _robot_vector(self) -> tuple[float, float, float]:
        ax, ay = self._simulation.acceleration
        yaw = self._simulation.simulator.pose[2]
        c, s = math.cos(yaw), math.sin(yaw)
        return c * ax + s * ay, -s * ax + c * ay, GRAVITY


class Gyro(_TableVector):
    """Angular velocity about the device's axes (rad/s): the yaw rate about z (about y in a
    world before R2022a)."""

    _node_type = node_type("GYRO")
    _device_frame = True

    _api = "wb_gyro"
    _default_table = GYRO_TABLE

    def _measure(self) -> tuple[float, float, float]:
        return 0.0, 0.0, self._simulation.velocity[2]

    def _robot_vector(self) -> tuple[float, float, float]:
        return self._measure()


class Compass(_TableVector):
    """The north direction in the device frame (unit vector)."""

    _node_type = node_type("COMPASS")
    _device_frame = True

    _api = "wb_compass"

    def __init__(
        self,
        name: str,
        simulation: RobotSimulation,
        mount: DeviceMount | None = None,
        table: Sequence[Sequence[float]] | None = None,
        north: Sequence[float] = NORTH,
    ) -> None:
        super().__init__(name, simulation, mount, table)
        nx, ny = float(north[0]), float(north[1])
        length = math.hypot(nx, ny) or 1.0
        self._north = (nx / length, ny / length)

    def _measure(self) -> tuple[float, float, float]:
        heading = self._heading()
        c, s = math.cos(heading), math.sin(heading)
        nx, ny = self._north
        return c * nx + s * ny, -s * nx + c * ny, 0.0

    def _robot_vector(self) -> tuple[float, float, float]:
        yaw = self._simulation.simulator.pose[2]
        c, s = math.cos(yaw), math.sin(yaw)
        nx, ny = self._north
        return c * nx + s * ny, -s * nx + c * ny, 0.0


class GPS(_TableVector):
    """The device's position in the world frame (m) and its speed; in a world of Webots' old
    NUE frame (before R2022a) in that frame, as the world file writes positions: the inverse of
    the importer's conversion, [-y, height, -x]."""

    _node_type = node_type("GPS")

    LOCAL = 0
    WGS84 = 1
    _api = "wb_gps"

    def _measure(self) -> tuple[float, float, float]:
        x, y, _ = self._mount.world_pose(self._simulation.simulator.pose)
        if self._simulation.scene.nue:
            # Worlds before R2022a: x north, y up, z east (Webots' NUE frame).
            return enu_to_nue(x, y, self._mount.z)
        return x, y, self._mount.z

    @derived_reading()
    def getSpeed(self) -> float:
        """The speed (m/s) over the last step; NaN before the first sampling period."""
        vx, vy, _ = self._simulation.velocity
        return math.hypot(vx, vy)

    @derived_reading(3)
    def getSpeedVector(self) -> list[float]:
        """The velocity (m/s) in the world frame over the last step; NaNs before the first
        sampling period."""
        vx, vy, _ = self._simulation.velocity
        return list(enu_to_nue(vx, vy, 0.0)) if self._simulation.scene.nue else [vx, vy, 0.0]

    def getCoordinateSystem(self) -> int:
        """:data:`LOCAL`: metres in the world frame."""
        return self.LOCAL

    @staticmethod
    def convertToDegreesMinutesSeconds(decimalDegree: float) -> str:
        """Formats decimal degrees as Webots does, e.g. ``12°34'56.78"``."""
        degrees = int(decimalDegree)
        minutes_float = abs(decimalDegree - degrees) * 60.0
        minutes = int(minutes_float)
        seconds = (minutes_float - minutes) * 60.0
        return f"{degrees}°{minutes}'{seconds:.2f}\""


class InertialUnit(_TableVector):
    """Roll, pitch and yaw of the device (rad): its frame's attitude in the world, Webots'
    x-y-z extrinsic sequence (the rotation Rz(yaw) Ry(pitch) Rx(roll)) in a world since
    R2022a. On the flat floor roll and pitch are 0 for a device mounted level, and those of its
    mount for one whose ``rotation`` tilts it on the robot.

    In a world before R2022a (NUE, Y-up devices) the attitude is that of the device's frame in
    the reference frame of north (``WorldInfo.northDirection``, x by default), up and their
    cross product, Webots' x-z-y extrinsic sequence (the rotation Ry(yaw) Rz(pitch) Rx(roll),
    Webots' R2020b-R2021b InertialUnit page): the yaw is 0 when the device's x axis points
    north and grows turning left, the roll turns about the device's x axis, the pitch about
    its z axis. A unit mounted unturned in a Y-up robot, whose x axis is the robot's right,
    thus reads the robot's heading in the imported world (0 facing the file's -z, whose right
    is north) where north is the default."""

    _node_type = node_type("INERTIAL_UNIT")
    _reads_tilt = True

    _api = "wb_inertial_unit"

    def _tilt(self) -> Axes | None:
        """The device's axes on the robot when its mount tilts it, in a world since R2022a."""
        return None if self._simulation.scene.y_up_devices else self._tilted_axes()

    def _read(self) -> list[float]:
        if self._simulation.scene.nue:
            return [self._table(v, self._rng) for v in self._nue_attitude()]
        tilted = self._tilt()
        if tilted is None:
            return super()._read()
        yaw = self._simulation.simulator.pose[2]
        c, s = math.cos(yaw), math.sin(yaw)
        # The device's x, y and z axes in the world: the columns of its rotation matrix R.
        x_axis, y_axis, z_axis = ((c * a[0] - s * a[1], s * a[0] + c * a[1], a[2]) for a in tilted)
        attitude = (
            math.atan2(y_axis[2], z_axis[2]),
            -math.asin(max(-1.0, min(1.0, x_axis[2]))),
            math.atan2(x_axis[1], x_axis[0]),
        )
        return [self._table(v, self._rng) for v in attitude]

    def _measure(self) -> tuple[float, float, float]:
        return 0.0, 0.0, math.remainder(self._heading(), math.tau)

    def _nue_attitude(self) -> tuple[float, float, float]:
        """Roll, pitch and yaw in a world before R2022a (see the class notes)."""
        axes = self._mount.axes
        c, s = math.cos(self._mount.yaw), math.sin(self._mount.yaw)
        if axes is None and self._y_up_frame():  # level, its x axis at the mount's yaw, y up
            axes = ((c, s, 0.0), (0.0, 0.0, 1.0), (s, -c, 0.0))
        elif axes is None:  # level in a Z-up body
            axes = ((c, s, 0.0), (-s, c, 0.0), (0.0, 0.0, 1.0))
        yaw = self._simulation.simulator.pose[2]
        c, s = math.cos(yaw), math.sin(yaw)
        x_axis, y_axis, z_axis = ((c * a[0] - s * a[1], s * a[0] + c * a[1], a[2]) for a in axes)
        nx, ny = self._simulation.scene.north or NUE_NORTH
        length = math.hypot(nx, ny) or 1.0
        nx, ny = nx / length, ny / length
        # The reference frame: north, up (z) and north x up = (ny, -nx, 0).
        return (
            math.atan2(-z_axis[2], y_axis[2]),
            math.asin(max(-1.0, min(1.0, x_axis[2]))),
            math.atan2(-(ny * x_axis[0] - nx * x_axis[1]), nx * x_axis[0] + ny * x_axis[1]),
        )

    def getRollPitchYaw(self) -> list[float]:
        """[roll, pitch, yaw] in radians; NaNs before the first sampling period."""
        return list(self._reading("get_roll_pitch_yaw"))

    @derived_reading(4)
    def getQuaternion(self) -> list[float]:
        """The orientation as a quaternion [x, y, z, w] (of the rotation Rz(yaw) Ry(pitch)
        Rx(roll)); NaNs before the first sampling period."""
        roll, pitch, yaw = self.getRollPitchYaw()
        if self._simulation.scene.nue:  # Ry(yaw) Rz(pitch) Rx(roll)
            turns = ((1, yaw), (2, pitch), (0, roll))
            quaternion = [0.0, 0.0, 0.0, 1.0]
            for axis, angle in turns:
                turn = [0.0, 0.0, 0.0, math.cos(angle / 2.0)]
                turn[axis] = math.sin(angle / 2.0)
                quaternion = _product(quaternion, turn)
            return quaternion
        if self._tilt() is None:  # level: its yaw alone (its roll and pitch read 0 noise-free)
            return [0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0)]
        cr, sr = math.cos(roll / 2.0), math.sin(roll / 2.0)
        cp, sp = math.cos(pitch / 2.0), math.sin(pitch / 2.0)
        cy, sy = math.cos(yaw / 2.0), math.sin(yaw / 2.0)
        return [
            sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy,
            cr * cp * cy + sr * sp * sy,
        ]

    def getNoise(self) -> float:
        """The noise of the readings (0: noise-free)."""
        return 0.0


class LightSensor(_Tabled, _ScalarSensor):
    """Light: the irradiance from the world's lights (:mod:`mazesim.webots.lights`) where the
    sensor is, facing its direction, through its table: the E-puck PROTO's for ls0-ls7, a
    world-added node's own ``lookupTable`` (none where it is empty: the irradiance itself) or
    Webots' node default (``equipment``)."""

    _node_type = node_type("LIGHT_SENSOR")

    _api = "wb_light_sensor"

    def __init__(
        self,
        name: str,
        simulation: RobotSimulation,
        table: Sequence[Sequence[float]] = LIGHT_TABLE,
        mount: DeviceMount | None = None,
    ) -> None:
        super().__init__(name, simulation)
        self._table = LookupTable(table)
        self._mount = mount or DeviceMount()
        self._rng = noise_stream(simulation, name)

    def _read(self) -> float:
        x, y, heading = self._mount.world_pose(self._simulation.simulator.pose)
        light = irradiance(self._simulation.lights_now(), (x, y, self._mount.z), heading)
        return self._table(light, self._rng)


#: How close (m) a bumper's bounding object comes to a wall, a movable body or another robot
#: for their contact: the bodies mazesim's contacts stop stand this near at most.
TOUCH_TOLERANCE = 0.001


class TouchSensor(_ScalarSensor):
    """A bumper: 1 while its bounding object touches a wall, a movable body or another robot,
    else 0 (reference manual, TouchSensor: a bumper reads 1 on a collision of its own
    ``boundingObject``). ``footprints`` are that bounding object seen from above, in the
    device's frame, placed by ``mount``; a bumper whose bounding object the world file does not
    give (one a PROTO holds) reads the whole body's contact instead."""

    _node_type = node_type("TOUCH_SENSOR")

    BUMPER = 0
    FORCE = 1
    FORCE3D = 2
    _api = "wb_touch_sensor"

    def __init__(
        self,
        name: str,
        simulation: RobotSimulation,
        mount: DeviceMount | None = None,
        footprints: Sequence[Footprint] = (),
    ) -> None:
        super().__init__(name, simulation)
        self._mount = mount or DeviceMount()
        self._footprints = list(footprints)
        self._walls = WallsNow(simulation)
        self._robots = OtherRobots.of(simulation)

    def _read(self) -> float:
        simulator = self._simulation.simulator
        if not self._footprints:
            return 1.0 if simulator.colliding else 0.0
        x, y, heading = self._mount.world_pose(simulator.pose)
        c, s = math.cos(heading), math.sin(heading)
        placed = [
            Footprint(
                x + c * f.x - s * f.y, y + s * f.x + c * f.y, heading + f.yaw, f.half, f.radius
            )
            for f in self._footprints
        ]
        walls = self._walls.walls()
        boxes = [
            Footprint(
                float(cx), float(cy), math.atan2(float(sn), float(cs)), (float(hx), float(hy)), 0.0
            )
            for (cx, cy), (hx, hy), cs, sn in zip(walls.center, walls.half, walls.cos, walls.sin)
        ]
        others = boxes + self._robots_now() + self._bodies_now()
        touching = any(
            _touch(mine, other)
            for mine in placed
            for other in others
            if math.hypot(other.x - mine.x, other.y - mine.y)
            <= _reach(mine) + _reach(other) + TOUCH_TOLERANCE
        )
        return 1.0 if touching else 0.0

    def _robots_now(self) -> list[Footprint]:
        """The other robots' bodies now, as discs."""
        return [Footprint(x, y, 0.0, None, radius) for x, y, radius in self._robots.now()]

    def _bodies_now(self) -> list[Footprint]:
        """The world's movable bodies where they are now."""
        from mazesim.webots.solids import world_objects

        found = []
        for (x, y, yaw), body in world_objects(self._simulation).drawn_bodies():
            if body.get("kind") == "circle":
                found.append(Footprint(x, y, yaw, None, float(body["radius"])))
            else:
                width, depth = (float(v) / 2.0 for v in body["size"])
                found.append(Footprint(x, y, yaw, (width, depth), 0.0))
        return found

    @derived_reading(3)
    def getValues(self) -> list[float]:
        """A force-3d sensor's reading: zeros (a bumper has no force vector); NaNs before the
        first sampling period."""
        return [0.0, 0.0, 0.0]

    def getType(self) -> int:
        """:data:`BUMPER`."""
        return self.BUMPER

    def getLookupTable(self) -> list[float]:
        """The empty table of a bumper."""
        return []


def _reach(shape: Footprint) -> float:
    """How far a footprint reaches from its centre."""
    return shape.radius + (math.hypot(*shape.half) if shape.half is not None else 0.0)


def _corners(shape: Footprint) -> list[tuple[float, float]]:
    """A box footprint's four corners (a disc's centre)."""
    if shape.half is None:
        return [(shape.x, shape.y)]
    c, s = math.cos(shape.yaw), math.sin(shape.yaw)
    hx, hy = shape.half
    return [
        (shape.x + c * u - s * v, shape.y + s * u + c * v)
        for u, v in ((hx, hy), (-hx, hy), (-hx, -hy), (hx, -hy))
    ]


def _gap_along(axis: tuple[float, float], first: Footprint, second: Footprint) -> float:
    """How far apart two footprints are along a unit ``axis`` (negative where they overlap)."""
    spans = []
    for shape in (first, second):
        ends = [axis[0] * px + axis[1] * py for px, py in _corners(shape)]
        spans.append((min(ends) - shape.radius, max(ends) + shape.radius))
    (low_a, high_a), (low_b, high_b) = spans
    return max(low_b - high_a, low_a - high_b)


def _touch(first: Footprint, second: Footprint) -> bool:
    """Whether two footprints come within :data:`TOUCH_TOLERANCE` of each other: their gap
    along each box's sides and along the line between their centres (which separates a disc
    from a box's corner, or two discs) is at most the tolerance somewhere on every axis."""
    axes = []
    for shape in (first, second):
        if shape.half is not None:
            c, s = math.cos(shape.yaw), math.sin(shape.yaw)
            axes += [(c, s), (-s, c)]
    for shape, other in ((first, second), (second, first)):
        if shape.half is None:
            # The axis from a disc's centre to the nearest point of the other footprint.
            px, py = _nearest(other, shape.x, shape.y)
            dx, dy = px - shape.x, py - shape.y
            length = math.hypot(dx, dy)
            if length > 0.0:
                axes.append((dx / length, dy / length))
    return all(_gap_along(axis, first, second) <= TOUCH_TOLERANCE for axis in axes)


def _nearest(shape: Footprint, x: float, y: float) -> tuple[float, float]:
    """The point of a box footprint (a disc's centre) nearest to ``x``, ``y``."""
    if shape.half is None:
        return shape.x, shape.y
    c, s = math.cos(shape.yaw), math.sin(shape.yaw)
    u = c * (x - shape.x) + s * (y - shape.y)
    v = -s * (x - shape.x) + c * (y - shape.y)
    u = max(-shape.half[0], min(shape.half[0], u))
    v = max(-shape.half[1], min(shape.half[1], v))
    return shape.x + c * u - s * v, shape.y + s * u + c * v


#: A distance sensor whose x axis points more than this below the horizontal (rad, 45 degrees)
#: reads the floor under it rather than the walls; one pointing less far down meets whichever
#: of a wall and the floor its ray reaches first.
DOWNWARD_PITCH = math.pi / 4


#: Webots' DistanceSensor ``aperture`` where the node leaves it out (rad; the reference
#: manual's DistanceSensor node: ``SFFloat aperture 1.5708``).
DISTANCE_SENSOR_APERTURE = 1.5708


class RayDistanceSensor(DistanceSensor):
    """A distance sensor the world adds: its rays from its mount against the walls, the movable
    bodies and the other robots (:class:`~mazesim.webots.walls_now.ObstaclesNow`) and the
    floor (a :class:`DistanceSensor`, with the world's table, type, aperture, number of rays,
    ``gaussianWidth`` and, of an infra-red one, ``redColorSensitivity``: how much of the
    reflection factor ``f`` it applies, the distance ``d`` read as ``d + (d / f - d) *
    sensitivity``, Webots' DistanceSensor; 1 by default). How several rays are laid out and
    make one reading, and how a sonar hears: :mod:`mazesim.webots.distance_rays`."""

    def __init__(
        self,
        name: str,
        simulation: RobotSimulation,
        mount: DeviceMount,
        table: Sequence[Sequence[float]] | None = None,
        sensor_type: str = "generic",
        aperture: float = DISTANCE_SENSOR_APERTURE,
        red_sensitivity: float = 1.0,
        rays: int = 1,
        gaussian_width: float = 1.0,
    ) -> None:
        _ScalarSensor.__init__(self, name, simulation)
        self._aperture = aperture
        self._red_sensitivity = red_sensitivity
        self._mount = mount
        self._table = LookupTable(DISTANCE_TABLE if table is None else table)
        self._type = read_sensor_type(sensor_type)
        self._rays = DistanceRays.of(rays, aperture, gaussian_width, self._type)
        # Each ray's heading from the mount's and its pitch down, in the robot's frame.
        self._headings, self._pitches = _ray_bearings(mount, self._rays)
        self._obstacles = ObstaclesNow(simulation, sensed=self._type == self.INFRA_RED)
        self._rng = noise_stream(simulation, name)

    def _read(self) -> float:
        """Each ray from the mount (:meth:`_hits`), made one distance as the sensor's type makes
        it (:func:`~mazesim.webots.distance_rays.sensor_distance`), through the table; 0
        through an empty one (``lookupTable []``), as Webots' DistanceSensor reads then."""
        if not self._table.rows:
            return 0.0
        reach = self.getMaxRange()
        d = sensor_distance(self._type, self._rays, self._hits(), reach, self._red_sensitivity)
        return self._table(min(d, reach), self._rng)

    def _hits(self) -> RayHits:
        """What each ray meets. A ray pointing down (``pitch`` above 0) slopes to the floor: it
        goes ``distance / cos(pitch)`` to a wall ``distance`` ahead and meets the floor ``z /
        sin(pitch)`` away, and the nearer of the two is what it meets (Webots casts the ray in
        3D: a sensor tilted 15 degrees down from 1 cm up reads the floor 3.9 cm away). Beyond
        :data:`DOWNWARD_PITCH` the floor is all it meets. A wall (a body, a robot) stands from
        the floor to its top (the world's, else higher than any ray): a ray passes over a wall
        lower than it where it crosses it, or falls onto its top."""
        x, y, heading = self._mount.world_pose(self._simulation.simulator.pose)
        turned = heading + self._headings
        flat = np.stack([np.cos(turned), np.sin(turned)], axis=1)
        walls = self._obstacles.boxes()
        height = self._mount.height_above_floor(self._simulation)
        rise = -np.tan(self._pitches)
        distance, wall, on_top = walls.cast_sloped((x, y), flat, height, rise)
        slant = np.maximum(np.cos(self._pitches), 1e-9)
        distances, factors = distance / slant, walls.reflectances(wall)
        # The cosine of the angle between a ray and the surface it meets, at its normal.
        incidence = np.where(on_top, np.sin(self._pitches), 1.0)
        if self._type == self.SONAR:
            normals = walls.side_normals((x, y), flat, distance, wall)
            sides = slant * np.abs(np.sum(normals * flat, axis=1))
            incidence = np.where(on_top, incidence, sides)
        with np.errstate(divide="ignore", invalid="ignore"):
            down = (self._pitches > 0.0) & (height > 0.0)
            floor = np.where(down, height / np.sin(self._pitches), np.inf)
        steep = self._pitches > DOWNWARD_PITCH
        for ray in np.flatnonzero(steep | (floor < np.minimum(distances, self.getMaxRange()))):
            pitch = float(self._pitches[ray])
            distances[ray], factors[ray] = self._floor_hit(heading + self._headings[ray], pitch)
            incidence[ray] = math.sin(pitch)
        return RayHits(distances, factors, incidence)

    def _floor_hit(self, heading: float, pitch: float) -> tuple[float, float]:
        """How far a ray of ``heading`` (in the world) and ``pitch`` goes to the floor and the
        floor's reflection factor where it meets it: ``z / sin(pitch)`` away, ahead of the mount
        by ``z / tan(pitch)``. The height is the mount's as Webots has it (the R2022a E-puck's
        slot holds a sensor 0.3 mm up), above the robot's resting origin
        (:meth:`DeviceMount.height_above_floor`); one on or below the floor's plane meets it a
        micrometre away."""
        height = max(self._mount.height_above_floor(self._simulation), 1e-6)
        sine = math.sin(pitch)
        ahead = height * math.cos(pitch) / sine
        x, y, _ = self._mount.world_pose(self._simulation.simulator.pose)
        x, y = x + ahead * math.cos(heading), y + ahead * math.sin(heading)
        return height / sine, float(self._simulation.world.floor_reflectance(x, y))

    def getType(self) -> int:
        """The sensor type from the world (``GENERIC`` by default)."""
        return self._type

    def getAperture(self) -> float:
        """The node's ``aperture`` (rad): the world's, an ``E-puckDistanceSensor``'s 0.1, else
        Webots' default, 1.5708 (it spreads the rays of a sensor of several)."""
        return self._aperture


def _ray_bearings(mount: DeviceMount, rays: DistanceRays) -> tuple[Floats, Floats]:
    """Each ray's heading from the mount's (rad, counter-clockwise) and pitch below the
    horizontal, in the robot's frame: one ray along the mount's own heading and pitch; several
    turned by the device's axes (the import's, else those of its heading and pitch unrolled)."""
    if len(rays) == 1:
        return np.zeros(1), np.array([mount.pitch])
    axes = mount.axes
    if axes is None:
        c, s = math.cos(mount.pitch), math.sin(mount.pitch)
        ahead = (c * math.cos(mount.yaw), c * math.sin(mount.yaw), -s)
        left = (-math.sin(mount.yaw), math.cos(mount.yaw), 0.0)
        axes = (ahead, left, tuple(np.cross(ahead, left)))
    along = rays.directions @ np.asarray(axes, dtype=np.float64)
    headings = np.arctan2(along[:, 1], along[:, 0]) - mount.yaw
    pitches = np.arctan2(-along[:, 2], np.hypot(along[:, 0], along[:, 1]))
    return headings, pitches


def _product(first: Sequence[float], second: Sequence[float]) -> list[float]:
    """The Hamilton product of two quaternions [x, y, z, w] (the rotation ``second`` then
    ``first``)."""
    x1, y1, z1, w1 = first
    x2, y2, z2, w2 = second
    return [
        w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
        w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
        w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
        w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
    ]
