"""A lidar and a range finder a Webots world adds to a robot (a ``Lidar`` or ``RangeFinder``
node in an extension slot, or among a plain robot's children), measured by casting rays against
the walls as they stand, the movable bodies and the other robots
(:class:`~mazesim.webots.walls_now.ObstaclesNow`), from where the device sits on the robot.

Webots renders both from OpenGL depth (reference manual, Lidar and RangeFinder). In mazesim's
world each wall stands from the floor to its top (the import writes it; a wall of a mazesim
world without a ``height`` stands above every ray) and there is no ceiling: a ray tilted up or
down by ``e`` meets a wall at horizontal distance ``h`` after ``h / cos(e)`` where it crosses the
wall below its top (it passes over a lower wall, or meets the top of one it falls onto), and a
ray tilted down from height ``z`` meets the floor ``z / sin(e)`` along it. A lidar looks along
its x axis, or its -z axis in a world before R2022a (as a Camera there; the mount's heading,
:func:`mazesim.webots.equipment.extension_device`); its points go from the left of its field of
view to the right (``fieldOfView / 2`` down to ``-fieldOfView / 2 + step`` about its up axis),
its layers from the top; a range finder's pixels give the depth
along its axis (a flat wall ahead reads the same depth across the image), its rows the same as
its middle row. Distances beyond
``maxRange`` read ``inf``, as in Webots.
"""

from __future__ import annotations

import math
import struct
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from mazesim._sizes import number_array
from mazesim.errors import _shown
from mazesim.webots.devices import _print_error, device_side
from mazesim.webots.inert import Lidar, LidarPoint, RangeFinder
from mazesim.webots.sensors import DeviceMount
from mazesim.webots.walls_now import ObstaclesNow

if TYPE_CHECKING:
    from mazesim.webots.simulation import RobotSimulation

__all__ = ["RayLidar", "RayRangeFinder", "lidar_points"]


def _number(fields: Mapping[str, Any], name: str, default: float) -> float:
    value = fields.get(name, default)
    return float(value) if isinstance(value, (int, float)) else default


def _range_image(image: object, size: int) -> list[float]:
    """A range image as a controller reads it: the last period's, or, before the first period
    ends, ``size`` zeros. Webots hands a lidar's or range finder's image memory to the
    controller when it starts (``wb_lidar_get_range_image`` returns it without a check that a
    period has passed, libController's lidar.c), so a controller that reads it between
    ``enable`` and its first step gets the memory's zeros, not NULL: a public project's
    Gymnasium env reads its lidar in ``reset`` before stepping."""
    return list(image) if isinstance(image, list) else [0.0] * size


class _Rays:
    """Horizontal distances to what stands on the floor along rays turned ``angles`` (rad) from
    a mount: the walls a camera sees, the sensed-only ones (a Shape without a boundingObject)
    too, the movable bodies and the other robots, as
    Webots' lidar and range finder measure depth from a rendering of the scene (reference
    manual, Lidar: "from an OpenGL rendering, like the RangeFinder node does")."""

    def __init__(self, simulation: RobotSimulation, mount: DeviceMount) -> None:
        self._simulation = simulation
        self._mount = mount
        self._obstacles = ObstaclesNow(simulation, sensed=True)

    def height(self) -> float:
        """The mount's height above the floor (:meth:`DeviceMount.height_above_floor`)."""
        return self._mount.height_above_floor(self._simulation)

    def horizontal(self, angles: np.ndarray, elevations: Sequence[float] = (0.0,)) -> np.ndarray:
        """How far across the floor each ray turned ``angles`` (columns) and tilted up by each
        of ``elevations`` (rows; rad, negative: down) runs to the first wall it meets (``inf``:
        none), the layers cast together."""
        x, y, heading = self._mount.world_pose(self._simulation.simulator.pose)
        directions = np.stack([np.cos(heading + angles), np.sin(heading + angles)], axis=1)
        rise = np.tan(number_array(elevations, "elevations"))[:, None] * np.ones(len(angles))
        walls = self._obstacles.boxes()
        distance, _, _ = walls.cast_sloped((x, y), directions, self.height(), rise)
        return np.asarray(distance, dtype=float)


class RayLidar(Lidar):
    """A ``Lidar`` node's points: ``horizontalResolution`` rays a layer over ``fieldOfView``,
    ``numberOfLayers`` layers over ``verticalFieldOfView`` (Webots' defaults 512, 1.5708, 4,
    0.2), ranges within ``minRange`` and ``maxRange`` (0.01, 1); its head's frequencies are the
    node's ``defaultFrequency``, ``minFrequency`` and ``maxFrequency`` (10, 1, 25 Hz)."""

    def __init__(
        self, name: str, simulation: RobotSimulation, mount: DeviceMount, fields: Mapping[str, Any]
    ) -> None:
        super().__init__(name, simulation)
        self._rays = _Rays(simulation, mount)
        named = f"Lidar {_shown(name)}"
        self._points = device_side(
            _number(fields, "horizontalResolution", 512), 512, f"{named} horizontalResolution", 0
        )
        self._layers = device_side(
            _number(fields, "numberOfLayers", 4), 4, f"{named} numberOfLayers", 0
        )
        self._fov = _number(fields, "fieldOfView", 1.5708)
        self._vertical_fov = _number(fields, "verticalFieldOfView", 0.2)
        self._min_range = _number(fields, "minRange", 0.01)
        self._max_range = _number(fields, "maxRange", 1.0)
        self._frequency = _number(fields, "defaultFrequency", 10.0)
        self._frequencies = (
            _number(fields, "minFrequency", 1.0),
            _number(fields, "maxFrequency", 25.0),
        )
        self._value = None
        self._cloud_enabled = False
        #: The simulated time (s) of the last reading, the time of its first point.
        self._read_at = 0.0

    def _elevations(self) -> list[float]:
        if self._layers <= 1:
            return [0.0] * self._layers
        step = self._vertical_fov / (self._layers - 1)
        return [self._vertical_fov / 2 - k * step for k in range(self._layers)]

    def _angles(self) -> Any:
        """Each point's heading in a layer (rad, to the left first)."""
        step = self._fov / self._points if self._points else 0.0
        return self._fov / 2 - step * np.arange(self._points)

    def _read(self) -> list[float]:  # type: ignore[override]
        self._read_at = float(self._simulation.time)
        elevations = self._elevations()
        height = self._rays.height()
        flat = self._rays.horizontal(self._angles(), elevations) if elevations else np.zeros((0,))
        ranges: list[float] = []
        for elevation, layer in zip(elevations, flat):
            along = layer / math.cos(elevation)
            if elevation < 0.0 and height > 0.0:
                along = np.minimum(along, height / math.sin(-elevation))
            along = np.where((along > self._max_range) | (along < self._min_range), np.inf, along)
            ranges.extend(float(r) for r in along)
        return ranges

    def getRangeImage(self) -> list[float] | None:  # type: ignore[override]
        """Every layer's ranges (m), the top layer first; zeros before the first period."""
        return _range_image(self._reading("get_range_image"), self._points * self._layers)

    def getLayerRangeImage(self, layer: int) -> list[float] | None:  # type: ignore[override]
        """Layer ``layer``'s ranges (m), or None."""
        image = self.getRangeImage()
        if image is None or not 0 <= int(layer) < self._layers:
            return None
        return image[int(layer) * self._points : (int(layer) + 1) * self._points]

    def enablePointCloud(self) -> None:
        """Makes the point cloud, read at each reading of the range image."""
        self._cloud_enabled = True

    def disablePointCloud(self) -> None:
        """Stops the point cloud."""
        self._cloud_enabled = False

    def isPointCloudEnabled(self) -> bool:
        """Whether :meth:`enablePointCloud` was called (and not undone)."""
        return self._cloud_enabled

    def getPointCloud(self, data_type: str = "list") -> list[LidarPoint] | bytes | None:  # type: ignore[override]
        """Every layer's points, the top layer first: each range of the range image as a point
        in the lidar's frame (see :func:`lidar_points`); None, with Webots' message, while the
        point cloud or the lidar is disabled. ``data_type="buffer"``: the points packed as
        Webots' ``WbLidarPoint`` structs (x, y, z float32, layer_id int32, time float32)."""
        points = self._cloud("wb_lidar_get_point_cloud")
        return None if points is None else _as_data_type(points, data_type)

    def getLayerPointCloud(  # type: ignore[override]
        self, layer: int, data_type: str = "list"
    ) -> list[LidarPoint] | bytes | None:
        """Layer ``layer``'s points, or None (with Webots' message for a layer the lidar has
        not)."""
        points = self._cloud("wb_lidar_get_layer_point_cloud")
        if points is None:
            return None
        if not (isinstance(layer, int) and 0 <= layer < self._layers):
            _print_error(
                "Error: wb_lidar_get_layer_point_cloud() called with an invalid 'layer' argument."
            )
            return None
        chosen = points[layer * self._points : (layer + 1) * self._points]
        return _as_data_type(chosen, data_type)

    def _cloud(self, function: str) -> list[LidarPoint] | None:
        if not self._cloud_enabled:
            _print_error(
                f"Error: {function}() called for a lidar with point cloud disabled. Please use: "
                "wb_lidar_enable_point_cloud()."
            )
            return None
        if self._period_ms == 0:
            _print_error(
                f"Error: {function}() called for a disabled device! Please use: wb_lidar_enable()."
            )
            return None
        image = self._value
        if not isinstance(image, list):  # before the first period: the memory's zeros
            return [LidarPoint() for _ in range(self._points * self._layers)]
        return lidar_points(
            image,
            self._angles(),
            self._elevations(),
            (self._read_at, self._period_ms / 1000.0),
            bool(getattr(self._simulation.scene, "nue", False)),
        )

    def getHorizontalResolution(self) -> int:
        """The node's ``horizontalResolution``."""
        return self._points

    def getNumberOfLayers(self) -> int:
        """The node's ``numberOfLayers``."""
        return self._layers

    def getNumberOfPoints(self) -> int:
        """Points in all layers."""
        return self._points * self._layers

    def getFov(self) -> float:
        """The node's ``fieldOfView`` (rad)."""
        return self._fov

    def getVerticalFov(self) -> float:
        """The node's ``verticalFieldOfView`` (rad)."""
        return self._vertical_fov

    def getMinRange(self) -> float:
        """The node's ``minRange`` (m)."""
        return self._min_range

    def getMaxRange(self) -> float:
        """The node's ``maxRange`` (m)."""
        return self._max_range

    def getFrequency(self) -> float:
        """The node's ``defaultFrequency`` (Hz)."""
        return self._frequency

    def getMinFrequency(self) -> float:
        """The node's ``minFrequency`` (Hz)."""
        return self._frequencies[0]

    def getMaxFrequency(self) -> float:
        """The node's ``maxFrequency`` (Hz)."""
        return self._frequencies[1]


def lidar_points(
    ranges: list[float],
    headings: Any,
    elevations: list[float],
    timing: tuple[float, float],
    nue: bool,
) -> list[LidarPoint]:
    """A lidar's range image as its point cloud (``WbLidar::updatePointCloud``): the range ``r``
    of heading ``a`` (to the left) in the layer of elevation ``e`` is the point ``(r cos a
    cos e, r sin a cos e, r sin e)`` in the lidar's frame, x ahead, y left, z up (Webots R2022a
    on); in a world of Webots' older NUE axes ``(-r sin a cos e, r sin e, -r cos a cos e)``, the
    lidar looking along -z. Each point's time is the reading's ``timing[0]`` less its place
    in the layer's sweep over the sampling period ``timing[1]`` (s), as Webots times a sweep
    ending at the reading; a range out of reach (inf) makes an infinite point. The headings are
    those of mazesim's rays (``fieldOfView / 2 - j fieldOfView / n``), so that each point lies
    where its ray met a wall; Webots' are half a point further round (at 512 points over 1.5708
    rad, 0.0015 rad)."""
    start, period = timing
    width = len(headings)
    points = []
    for layer, elevation in enumerate(elevations):
        up, across = math.sin(elevation), math.cos(elevation)
        for column, heading in enumerate(headings):
            r = ranges[layer * width + column]
            ahead, left = math.cos(heading) * across, math.sin(heading) * across
            if nue:
                point = LidarPoint(-r * left, r * up, -r * ahead, layer)
            else:
                point = LidarPoint(r * ahead, r * left, r * up, layer)
            point.time = start - column * period / width if width else start
            points.append(point)
    return points


def _as_data_type(points: list[LidarPoint], data_type: str) -> list[LidarPoint] | bytes:
    """The points as a list, or for ``data_type="buffer"`` as Webots' ``WbLidarPoint`` structs."""
    if data_type != "buffer":
        return points
    return b"".join(struct.pack("<fffif", p.x, p.y, p.z, p.layer_id, p.time) for p in points)


class RayRangeFinder(RangeFinder):
    """A ``RangeFinder`` node's depth image: ``width`` x ``height`` pixels (Webots' defaults
    64 x 64) over ``fieldOfView`` (0.7854), depths within ``minRange`` and ``maxRange`` (0.01,
    1)."""

    def __init__(
        self, name: str, simulation: RobotSimulation, mount: DeviceMount, fields: Mapping[str, Any]
    ) -> None:
        super().__init__(name, simulation)
        self._rays = _Rays(simulation, mount)
        named = f"RangeFinder {_shown(name)}"
        self._width = device_side(_number(fields, "width", 64), 64, f"{named} width")
        self._height = device_side(_number(fields, "height", 64), 64, f"{named} height")
        self._fov = _number(fields, "fieldOfView", 0.7854)
        self._min_range = _number(fields, "minRange", 0.01)
        self._max_range = _number(fields, "maxRange", 1.0)
        self._value = None

    def _read(self) -> list[float]:  # type: ignore[override]
        half = math.tan(self._fov / 2)
        offsets = (np.arange(self._width) + 0.5 - self._width / 2) / (self._width / 2) * half
        angles = -np.arctan(offsets)
        depth = self._rays.horizontal(angles)[0] * np.cos(angles)
        depth = np.where(depth > self._max_range, np.inf, depth)
        row = [float(d) for d in depth]
        return row * self._height

    def getRangeImage(self, data_type: str = "list") -> list[float] | None:  # type: ignore[override]
        """The depths (m), row after row; zeros before the first period."""
        return _range_image(self._reading("get_range_image"), self._width * self._height)

    def getWidth(self) -> int:
        """The node's ``width``."""
        return self._width

    def getHeight(self) -> int:
        """The node's ``height``."""
        return self._height

    def getFov(self) -> float:
        """The node's ``fieldOfView`` (rad)."""
        return self._fov

    def getMinRange(self) -> float:
        """The node's ``minRange`` (m)."""
        return self._min_range

    def getMaxRange(self) -> float:
        """The node's ``maxRange`` (m)."""
        return self._max_range
