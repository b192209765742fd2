"""Where the distance sensors' rays meet the walls: the geometry the pictures draw.

:class:`SensorRays` casts each distance sensor's ray from its pose on the robot against a world's
wall boxes (a slab test per box, in numpy) and returns how far each ray reaches, capped at the
sensor's range. The renderer draws the rays this long, and recorded runs store these lengths so
the replay can draw them without the walls' geometry in the browser.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from mazesim.errors import _bounded_number

if TYPE_CHECKING:
    from mazesim._core import RobotProfile, World

__all__ = ["SensorRays"]


class SensorRays:
    """The distance sensors' rays of one robot in one world.

    Args:
        world: The world whose wall boxes stop the rays.
        robot: The robot profile (the sensors' poses on the body).
        ray_length: Range of the sensors in metres.
        walls: The wall boxes (N, 5 or more: centre x, y, size x, y, yaw) instead of the
            world's (the walls as a supervisor changed them in a recorded run).
    """

    def __init__(
        self,
        world: World,
        robot: RobotProfile,
        ray_length: float,
        walls: npt.ArrayLike | None = None,
    ) -> None:
        given = world.wall_boxes() if walls is None else walls
        array = np.asarray(given, dtype=np.float64)
        boxes = array.reshape(-1, array.shape[-1] if array.ndim == 2 else 6)
        self.num_boxes = len(boxes)
        # Per wall box, as (1, B) rows: centre, half sizes, cos and sin of its yaw.
        self._center = (boxes[:, 0][None, :], boxes[:, 1][None, :])
        self._half = (boxes[:, 2][None, :] / 2, boxes[:, 3][None, :] / 2)
        self._turn = (np.cos(boxes[:, 4])[None, :], np.sin(boxes[:, 4])[None, :])
        self.sensor_poses = np.asarray(robot.distance_sensor_poses(), dtype=np.float64).reshape(
            -1, 3
        )
        self.ray_length = _bounded_number("ray_length", ray_length, above=0.0)

    def origins(
        self, pose: tuple[float, float, float]
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """World x, y and heading of each sensor of a robot at ``pose``."""
        x, y, yaw = (float(v) for v in pose)
        cos_yaw, sin_yaw = math.cos(yaw), math.sin(yaw)
        local_x, local_y, heading = self.sensor_poses.T
        return (
            x + cos_yaw * local_x - sin_yaw * local_y,
            y + sin_yaw * local_x + cos_yaw * local_y,
            yaw + heading,
        )

    def lengths(self, pose: tuple[float, float, float]) -> npt.NDArray[np.float64]:
        """How far each sensor's ray reaches from a robot at ``pose`` (m, at most the range)."""
        origin_x, origin_y, angles = self.origins(pose)
        return self.hits(origin_x, origin_y, np.cos(angles), np.sin(angles))

    def hits(
        self,
        origin_x: npt.NDArray[np.float64],
        origin_y: npt.NDArray[np.float64],
        cos_ray: npt.NDArray[np.float64],
        sin_ray: npt.NDArray[np.float64],
    ) -> npt.NDArray[np.float64]:
        """Distance along each ray to the first wall (slab test), capped at the sensor range."""
        length = self.ray_length
        if not self.num_boxes:
            return np.full(len(origin_x), length)
        (cx, cy), (half_x, half_y), (cos_b, sin_b) = self._center, self._half, self._turn
        rel_x, rel_y = origin_x[:, None] - cx, origin_y[:, None] - cy
        cos_r, sin_r = cos_ray[:, None], sin_ray[:, None]
        # Ray origins and directions in each box's frame; a direction never exactly 0, so a ray
        # parallel to a slab gets huge slab distances of the right sign.
        ox, oy = cos_b * rel_x + sin_b * rel_y, cos_b * rel_y - sin_b * rel_x
        dx = cos_b * cos_r + sin_b * sin_r
        dy = cos_b * sin_r - sin_b * cos_r
        dx = np.where(np.abs(dx) < 1e-12, 1e-12, dx)
        dy = np.where(np.abs(dy) < 1e-12, 1e-12, dy)
        tx1, tx2 = (-half_x - ox) / dx, (half_x - ox) / dx
        ty1, ty2 = (-half_y - oy) / dy, (half_y - oy) / dy
        near = np.maximum(np.minimum(tx1, tx2), np.minimum(ty1, ty2))
        far = np.minimum(np.maximum(tx1, tx2), np.maximum(ty1, ty2))
        near = np.maximum(near, 0.0)
        distance = np.where(far >= near, near, length)
        return np.minimum(distance.min(axis=1), length)
