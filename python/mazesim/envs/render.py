"""A fast top-down picture of a world and its robot, drawn with numpy alone.

The static part of a world (floor paint in grey levels equal to its reflectance, walls, checkpoint
outlines and the goal) is rasterised once into a background image; each frame copies it and draws
the robot's body, its heading and its distance-sensor rays, each ray cut where it meets a wall.
Colours follow :mod:`mazesim.plotting`. At the default 400 x 400 pixels a frame takes well under a
millisecond, fast enough to record videos of training.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    from mazesim._core import RobotProfile, World

__all__ = ["TopDownRenderer"]

WALL_RGB = (0x8C, 0x3B, 0x1F)
GOAL_RGB = (0x2C, 0xA0, 0x2C)
CHECKPOINT_RGB = (0xFF, 0xD9, 0x2F)
ROBOT_RGB = (0x1F, 0x77, 0xB4)
COLLIDING_RGB = (0xD6, 0x27, 0x28)
HEADING_RGB = (0xFF, 0xFF, 0xFF)
RAY_RGB = (0xFF, 0x7F, 0x0E)
GOAL_ALPHA = 0.45
#: Length of a barcode along the direction of travel: five bars of 1.7 cm.
BARCODE_LENGTH = 5 * 0.017
#: Blank border round the world, in pixels.
BORDER = 4

Mask = Callable[[npt.NDArray[np.float64], npt.NDArray[np.float64]], npt.NDArray[np.bool_]]


class TopDownRenderer:
    """Draws top-down RGB frames of one world.

    Args:
        world: The world to draw.
        robot: The robot profile (body radius, sensor poses).
        size: (width, height) of the frames in pixels.
        ray_length: Range of the distance sensors in metres.
    """

    def __init__(
        self,
        world: World,
        robot: RobotProfile,
        size: tuple[int, int] = (400, 400),
        ray_length: float = 0.07,
    ) -> None:
        self.width, self.height = size
        xmin, ymin, xmax, ymax = world.bounds
        span_x, span_y = max(xmax - xmin, 1e-3), max(ymax - ymin, 1e-3)
        self.scale = min((self.width - 2 * BORDER) / span_x, (self.height - 2 * BORDER) / span_y)
        # Pixel (column, row) of the world point (x, y) is (x0 + x * scale, y0 - y * scale).
        self._x0 = (self.width - span_x * self.scale) / 2 - xmin * self.scale
        self._y0 = (self.height + span_y * self.scale) / 2 + ymin * self.scale
        boxes = np.asarray(world.wall_boxes(), dtype=np.float64).reshape(-1, 6)
        self._boxes = boxes
        # Per wall box, as (1, B) rows: centre, half sizes, cos and sin of its yaw.
        self._box_center = (boxes[:, 0][None, :], boxes[:, 1][None, :])
        self._box_half = (boxes[:, 2][None, :] / 2, boxes[:, 3][None, :] / 2)
        self._box_turn = (np.cos(boxes[:, 4])[None, :], np.sin(boxes[:, 4])[None, :])
        self._body_radius = robot.body_radius
        sensors = np.asarray(robot.distance_sensor_poses(), dtype=np.float64).reshape(-1, 3)
        # The heading mark is one more "ray" from the centre to the rim, never cut by walls.
        self._spokes = np.vstack((sensors, [[0.0, 0.0, 0.0]]))
        self._ray_length = ray_length
        self._reach = np.full(len(self._spokes), self._body_radius)
        self._stamp = _disc_offsets(self._body_radius * self.scale)
        self._spoke_rgb = np.array([RAY_RGB] * len(sensors) + [HEADING_RGB], dtype=np.uint8)
        self.background = self._draw_world(world)

    def frame(
        self, pose: tuple[float, float, float], colliding: bool = False
    ) -> npt.NDArray[np.uint8]:
        """A new (height, width, 3) uint8 image of the world with the robot at ``pose``."""
        image = self.background.copy()
        x, y, yaw = (float(v) for v in pose)
        rows = int(self._y0 - y * self.scale) + self._stamp[0]
        cols = int(self._x0 + x * self.scale) + self._stamp[1]
        keep = (rows >= 0) & (rows < self.height) & (cols >= 0) & (cols < self.width)
        image[rows[keep], cols[keep]] = COLLIDING_RGB if colliding else ROBOT_RGB
        cos_yaw, sin_yaw = math.cos(yaw), math.sin(yaw)
        local_x, local_y, heading = self._spokes.T
        origins_x = x + cos_yaw * local_x - sin_yaw * local_y
        origins_y = y + sin_yaw * local_x + cos_yaw * local_y
        angles = yaw + heading
        cos_a, sin_a = np.cos(angles), np.sin(angles)
        reach = self._reach.copy()
        reach[:-1] = self._ray_hits(origins_x[:-1], origins_y[:-1], cos_a[:-1], sin_a[:-1])
        self._segments(
            image,
            (origins_x, origins_y),
            (origins_x + cos_a * reach, origins_y + sin_a * reach),
            self._spoke_rgb,
        )
        return image

    # -- geometry ------------------------------------------------------------------------------

    def _pixel_box(
        self, extent: tuple[float, float, float, float]
    ) -> tuple[slice, slice, npt.NDArray[np.float64], npt.NDArray[np.float64]] | None:
        """Rows, columns and the world coordinates of the pixel centres covering ``extent``."""
        xmin, ymin, xmax, ymax = extent
        col0 = max(int(math.floor(self._x0 + xmin * self.scale)), 0)
        col1 = min(int(math.ceil(self._x0 + xmax * self.scale)) + 1, self.width)
        row0 = max(int(math.floor(self._y0 - ymax * self.scale)), 0)
        row1 = min(int(math.ceil(self._y0 - ymin * self.scale)) + 1, self.height)
        if col0 >= col1 or row0 >= row1:
            return None
        xs = (np.arange(col0, col1) + 0.5 - self._x0) / self.scale
        ys = (self._y0 - np.arange(row0, row1) - 0.5) / self.scale
        return slice(row0, row1), slice(col0, col1), xs[None, :], ys[:, None]  # type: ignore[return-value]

    def _fill(
        self,
        image: npt.NDArray[np.uint8],
        extent: tuple[float, float, float, float],
        inside: Mask,
        rgb: tuple[int, int, int],
        alpha: float = 1.0,
    ) -> None:
        """Paints the pixels whose centres satisfy ``inside`` within ``extent``."""
        box = self._pixel_box(extent)
        if box is None:
            return
        rows, cols, xs, ys = box
        mask = inside(xs, ys)
        region = image[rows, cols]
        if alpha >= 1.0:
            region[mask] = rgb
        else:
            blended = region[mask] * (1.0 - alpha) + np.asarray(rgb) * alpha
            region[mask] = np.round(blended).astype(np.uint8)

    def _segments(
        self,
        image: npt.NDArray[np.uint8],
        starts: tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]],
        ends: tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]],
        rgb: npt.NDArray[np.uint8],
    ) -> None:
        """Draws one-pixel lines from each start (xs, ys) to its end, line i in ``rgb[i]``."""
        col0, row0 = self._x0 + starts[0] * self.scale, self._y0 - starts[1] * self.scale
        col1, row1 = self._x0 + ends[0] * self.scale, self._y0 - ends[1] * self.scale
        longest = max(float(np.abs(col1 - col0).max()), float(np.abs(row1 - row0).max()))
        t = np.linspace(0.0, 1.0, int(longest * 1.5) + 2)[None, :]
        cols = (col0[:, None] + (col1 - col0)[:, None] * t).astype(np.intp)
        rows = (row0[:, None] + (row1 - row0)[:, None] * t).astype(np.intp)
        keep = (cols >= 0) & (cols < self.width) & (rows >= 0) & (rows < self.height)
        colours = np.broadcast_to(rgb[:, None, :], (*cols.shape, 3))
        image[rows[keep], cols[keep]] = colours[keep]

    def _ray_hits(
        self,
        origin_x: npt.NDArray[np.float64],
        origin_y: npt.NDArray[np.float64],
        cos_ray: npt.NDArray[np.float64],
        sin_ray: npt.NDArray[np.float64],
    ) -> npt.NDArray[np.float64]:
        """Distance along each ray to the first wall (slab test), capped at the sensor range."""
        length = self._ray_length
        if not len(self._boxes):
            return np.full(len(origin_x), length)
        (cx, cy), (half_x, half_y), (cos_b, sin_b) = (
            self._box_center,
            self._box_half,
            self._box_turn,
        )
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

    # -- the static world ----------------------------------------------------------------------

    def _draw_world(self, world: World) -> npt.NDArray[np.uint8]:
        grey = int(round(255 * min(max(world.floor_background, 0.0), 1.0)))
        image = np.full((self.height, self.width, 3), grey, dtype=np.uint8)
        for region in world.paint_regions():
            level = int(round(255 * min(max(_number(region["reflectance"]), 0.0), 1.0)))
            self._paint_region(image, region, (level, level, level))
        pixel = 1.0 / self.scale
        for cx, cy, sx, sy, yaw, _ in self._boxes:
            # Half a pixel more on each side, so walls thinner than a pixel still show.
            self._box(image, (cx, cy), (sx + pixel, sy + pixel), yaw, WALL_RGB)
        for checkpoint in world.checkpoints():
            center = _pair(checkpoint["center"])
            yaw = _number(checkpoint["yaw"])
            width = _number(checkpoint["width"])
            outer = (BARCODE_LENGTH + 2 * pixel, width)
            inner = (BARCODE_LENGTH - 2 * pixel, width - 4 * pixel)
            self._box(image, center, outer, yaw, CHECKPOINT_RGB, hollow=inner)
        if world.goal is not None:
            gx, gy, radius = world.goal
            self._fill(
                image,
                (gx - radius, gy - radius, gx + radius, gy + radius),
                lambda px, py: (px - gx) ** 2 + (py - gy) ** 2 <= radius * radius,
                GOAL_RGB,
                GOAL_ALPHA,
            )
        image.flags.writeable = False
        return image

    def _paint_region(
        self, image: npt.NDArray[np.uint8], region: dict[str, object], rgb: tuple[int, int, int]
    ) -> None:
        shape = region["shape"]
        if shape == "rect":
            center, size = _pair(region["center"]), _pair(region["size"])
            self._box(image, center, size, _number(region.get("yaw", 0.0)), rgb)
        elif shape == "circle":
            cx, cy = _pair(region["center"])
            radius = _number(region["radius"])
            self._fill(
                image,
                (cx - radius, cy - radius, cx + radius, cy + radius),
                lambda px, py: (px - cx) ** 2 + (py - cy) ** 2 <= radius * radius,
                rgb,
            )
        elif shape == "capsule":
            (ax, ay), (bx, by) = _pair(region["a"]), _pair(region["b"])
            radius = _number(region["radius"])
            length2 = max((bx - ax) ** 2 + (by - ay) ** 2, 1e-18)

            def inside(
                px: npt.NDArray[np.float64], py: npt.NDArray[np.float64]
            ) -> npt.NDArray[np.bool_]:
                t = np.clip(((px - ax) * (bx - ax) + (py - ay) * (by - ay)) / length2, 0.0, 1.0)
                return (px - ax - t * (bx - ax)) ** 2 + (py - ay - t * (by - ay)) ** 2 <= radius**2

            extent = (
                min(ax, bx) - radius,
                min(ay, by) - radius,
                max(ax, bx) + radius,
                max(ay, by) + radius,
            )
            self._fill(image, extent, inside, rgb)

    def _box(
        self,
        image: npt.NDArray[np.uint8],
        center: tuple[float, float],
        size: tuple[float, float],
        yaw: float,
        rgb: tuple[int, int, int],
        hollow: tuple[float, float] | None = None,
    ) -> None:
        """Fills a rotated rectangle, or only its rim outside ``hollow`` when given."""
        cx, cy = (float(v) for v in center)
        half_x, half_y = float(size[0]) / 2, float(size[1]) / 2
        cos_yaw, sin_yaw = math.cos(yaw), math.sin(yaw)
        reach_x = abs(cos_yaw) * half_x + abs(sin_yaw) * half_y
        reach_y = abs(sin_yaw) * half_x + abs(cos_yaw) * half_y

        def inside(
            px: npt.NDArray[np.float64], py: npt.NDArray[np.float64]
        ) -> npt.NDArray[np.bool_]:
            along = (px - cx) * cos_yaw + (py - cy) * sin_yaw
            across = -(px - cx) * sin_yaw + (py - cy) * cos_yaw
            mask = (np.abs(along) <= half_x) & (np.abs(across) <= half_y)
            if hollow is not None:
                mask &= ~((np.abs(along) <= hollow[0] / 2) & (np.abs(across) <= hollow[1] / 2))
            return mask

        self._fill(image, (cx - reach_x, cy - reach_y, cx + reach_x, cy + reach_y), inside, rgb)


def _disc_offsets(radius_px: float) -> tuple[npt.NDArray[np.intp], npt.NDArray[np.intp]]:
    """(rows, cols) offsets of the pixels of a disc of ``radius_px`` round its centre pixel."""
    reach = int(math.ceil(radius_px))
    rows, cols = np.mgrid[-reach : reach + 1, -reach : reach + 1]
    inside = rows**2 + cols**2 <= radius_px**2
    return rows[inside].astype(np.intp), cols[inside].astype(np.intp)


def _number(value: object) -> float:
    """A number from the core's description of a world."""
    return float(value)  # type: ignore[arg-type]


def _pair(value: object) -> tuple[float, float]:
    """An (x, y) pair from the core's description of a world."""
    first, second = (float(v) for v in value)  # type: ignore[attr-defined]
    return first, second
