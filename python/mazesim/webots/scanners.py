"""A lidar and a range finder a Webots world adds to a robot (a ``Lidar`` or ``RangeFinder``
node in an extension slot, or among a plain robot's children), measured by casting rays against
the walls as they stand, from where the device sits on the robot.

Webots renders both from OpenGL depth (reference manual, Lidar and RangeFinder). In mazesim's
2-D world walls have no height and there is no ceiling: a ray tilted up or down by ``e`` meets a
wall at horizontal distance ``h`` after ``h / cos(e)``, and a ray tilted down from height ``z``
meets the floor ``z / sin(e)`` along it. A lidar's points go from the left of its field of view
to the right (``fieldOfView / 2`` down to ``-fieldOfView / 2 + step`` about its z axis), its
layers from the top; a range finder's pixels give the depth along its axis (a flat wall ahead
reads the same depth across the image), its rows the same as its middle row. Distances beyond
``maxRange`` read ``inf``, as in Webots.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from mazesim.errors import _shown
from mazesim.webots.devices import device_side
from mazesim.webots.inert import Lidar, RangeFinder
from mazesim.webots.sensors import DeviceMount
from mazesim.webots.walls_now import WallsNow

if TYPE_CHECKING:
    from mazesim.webots.simulation import RobotSimulation

__all__ = ["RayLidar", "RayRangeFinder"]


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
    """Horizontal distances to the walls along rays turned ``angles`` (rad) from a mount."""

    def __init__(self, simulation: RobotSimulation, mount: DeviceMount) -> None:
        self._simulation = simulation
        self._mount = mount
        self._walls = WallsNow(simulation)

    def horizontal(self, angles: np.ndarray) -> np.ndarray:
        x, y, heading = self._mount.world_pose(self._simulation.simulator.pose)
        directions = np.stack([np.cos(heading + angles), np.sin(heading + angles)], axis=1)
        distance, _ = self._walls.walls().cast((x, y), directions)
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
        self._height = mount.z
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

    def _elevations(self) -> list[float]:
        if self._layers <= 1:
            return [0.0] * self._layers
        step = self._vertical_fov / (self._layers - 1)
        return [self._vertical_fov / 2 - k * step for k in range(self._layers)]

    def _read(self) -> list[float]:  # type: ignore[override]
        step = self._fov / self._points if self._points else 0.0
        angles = self._fov / 2 - step * np.arange(self._points)
        flat = self._rays.horizontal(angles)
        ranges: list[float] = []
        for elevation in self._elevations():
            along = flat / math.cos(elevation)
            if elevation < 0.0 and self._height > 0.0:
                along = np.minimum(along, self._height / math.sin(-elevation))
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
        depth = self._rays.horizontal(angles) * np.cos(angles)
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
