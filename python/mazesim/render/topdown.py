"""A fast top-down picture of a world and its robot, drawn with numpy alone.

The static part of a world (floor paint in grey levels equal to its reflectance, walls, checkpoint
outlines, the goal and the start pose) is rasterised once into a background image; each frame
copies it and draws the robot's trail, its body, a bold heading mark and its distance-sensor rays,
each ray cut where it meets a wall (:class:`mazesim.sensor_rays.SensorRays`). Optional text lines
(time, step, reward, the last event...) go in a box at the top left (:func:`overlay_text`, with
Pillow, which matplotlib already needs). Other robots of the world are drawn too, each body and
trail in a colour of its own. Colours follow :mod:`mazesim.plotting`. At the default 400 x 400
pixels a frame takes about a millisecond, fast enough to record videos of training.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    from mazesim._core import RobotProfile, World

from mazesim._sizes import number_array
from mazesim.sensor_rays import SensorRays

__all__ = ["TopDownRenderer", "overlay_text"]

WALL_RGB = (0x8C, 0x3B, 0x1F)
GOAL_RGB = (0x2C, 0xA0, 0x2C)
CHECKPOINT_RGB = (0xFF, 0xD9, 0x2F)
ROBOT_RGB = (0x1F, 0x77, 0xB4)
COLLIDING_RGB = (0xD6, 0x27, 0x28)
HEADING_RGB = (0xFF, 0xFF, 0xFF)
RAY_RGB = (0xFF, 0x7F, 0x0E)
START_RGB = (0x1F, 0x77, 0xB4)
TRAIL_RGB = (0xD6, 0x27, 0x28)
#: The bodies and trails of the other robots of a world, in turn (as the HTML replay's).
OTHER_ROBOT_RGB = (
    (0xFF, 0x7F, 0x0E),
    (0x94, 0x67, 0xBD),
    (0x8C, 0x56, 0x4B),
    (0xE3, 0x77, 0xC2),
    (0x17, 0xBE, 0xCF),
    (0xBC, 0xBD, 0x22),
    (0x7F, 0x7F, 0x7F),
)
#: Another robot: its pose, whether it touches something, and its trail ((K, 2) positions).
OtherRobot = tuple[tuple[float, float, float], bool, npt.ArrayLike]
#: Thickness of the heading mark, in pixels.
HEADING_WIDTH = 3
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
        start: The start pose (x, y, yaw) drawn, instead of the world's.
        goal: The goal disc (x, y, radius) drawn, instead of the world's.
        walls: The wall boxes drawn (N, 5 or more: centre x, y, size x, y, yaw), instead of
            the world's (the walls as a supervisor changed them in a recorded run).
    """

    def __init__(
        self,
        world: World,
        robot: RobotProfile,
        size: tuple[int, int] = (400, 400),
        ray_length: float = 0.07,
        start: tuple[float, float, float] | None = None,
        goal: tuple[float, float, float] | None = None,
        walls: npt.ArrayLike | None = None,
    ) -> None:
        self.width, self.height = size
        xmin, ymin, xmax, ymax = world.bounds
        span_x, span_y = max(xmax - xmin, 1e-3), max(ymax - ymin, 1e-3)
        self.scale = min((self.width - 2 * BORDER) / span_x, (self.height - 2 * BORDER) / span_y)
        # Pixel (column, row) of the world point (x, y) is (x0 + x * scale, y0 - y * scale).
        self._x0 = (self.width - span_x * self.scale) / 2 - xmin * self.scale
        self._y0 = (self.height + span_y * self.scale) / 2 + ymin * self.scale
        given = np.asarray(world.wall_boxes() if walls is None else walls, dtype=np.float64)
        self._boxes = given.reshape(-1, given.shape[-1] if given.ndim == 2 else 6)[:, :5]
        self._body_radius = robot.body_radius
        self.rays = SensorRays(world, robot, ray_length, self._boxes)
        self._stamp = _disc_offsets(self._body_radius * self.scale)
        self._start = world.start if start is None else start
        self._goal = world.goal if goal is None else goal
        self.background = self._draw_world(world)

    def frame(
        self,
        pose: tuple[float, float, float],
        colliding: bool = False,
        trail: npt.ArrayLike | None = None,
        overlay: list[str] | None = None,
        others: list[OtherRobot] | None = None,
    ) -> npt.NDArray[np.uint8]:
        """A new (height, width, 3) uint8 image of the world with the robot at ``pose``.

        Args:
            pose: The robot's x, y (m) and yaw (rad).
            colliding: Draws the body red when True.
            trail: (K, 2) positions the robot passed, drawn as a line under it.
            overlay: Text lines shown at the top left (see :func:`overlay_text`).
            others: The world's other robots (drawn with this robot's body radius).
        """
        image = self.background.copy()
        for index, (other, touching, path) in enumerate(others or []):
            rgb = OTHER_ROBOT_RGB[index % len(OTHER_ROBOT_RGB)]
            self._draw_trail(image, path, rgb)
            self._draw_disc(image, other, COLLIDING_RGB if touching else rgb)
            self._draw_heading(image, other)
        if trail is not None:
            self._draw_trail(image, trail, TRAIL_RGB)
        x, y, yaw = (float(v) for v in pose)
        self._draw_disc(image, (x, y, yaw), COLLIDING_RGB if colliding else ROBOT_RGB)
        origins_x, origins_y, angles = self.rays.origins((x, y, yaw))
        cos_a, sin_a = np.cos(angles), np.sin(angles)
        reach = self.rays.hits(origins_x, origins_y, cos_a, sin_a)
        ray_colour = np.array([RAY_RGB] * len(reach), dtype=np.uint8)
        self._segments(
            image,
            (origins_x, origins_y),
            (origins_x + cos_a * reach, origins_y + sin_a * reach),
            ray_colour,
        )
        self._draw_heading(image, (x, y, yaw))
        if overlay:
            image = overlay_text(image, overlay)
        return image

    def _draw_trail(
        self, image: npt.NDArray[np.uint8], trail: npt.ArrayLike, rgb: tuple[int, int, int]
    ) -> None:
        """Draws the line through a robot's past positions ((K, 2))."""
        points = number_array(trail, "trail", nan_means="a gap in the trail").reshape(-1, 2)
        if len(points) > 1:
            colour = np.array([rgb] * (len(points) - 1), dtype=np.uint8)
            self._segments(
                image, (points[:-1, 0], points[:-1, 1]), (points[1:, 0], points[1:, 1]), colour
            )

    def _draw_disc(
        self,
        image: npt.NDArray[np.uint8],
        pose: tuple[float, float, float],
        rgb: tuple[int, int, int],
    ) -> None:
        """Draws a robot's body at ``pose``."""
        x, y, _ = pose
        rows = int(self._y0 - y * self.scale) + self._stamp[0]
        cols = int(self._x0 + x * self.scale) + self._stamp[1]
        keep = (rows >= 0) & (rows < self.height) & (cols >= 0) & (cols < self.width)
        image[rows[keep], cols[keep]] = rgb

    def _draw_heading(self, image: npt.NDArray[np.uint8], pose: tuple[float, float, float]) -> None:
        """Draws a robot's heading mark, from its centre to its rim."""
        x, y, yaw = (float(v) for v in pose)
        rim = np.array([self._body_radius])
        self._segments(
            image,
            (np.array([x]), np.array([y])),
            (x + math.cos(yaw) * rim, y + math.sin(yaw) * rim),
            np.array([HEADING_RGB], dtype=np.uint8),
            width=HEADING_WIDTH,
        )

    def mark_disc(
        self,
        image: npt.NDArray[np.uint8],
        centre: tuple[float, float],
        radius: float,
        rgb: tuple[int, int, int] = GOAL_RGB,
        alpha: float = GOAL_ALPHA,
    ) -> None:
        """Paints a disc of ``radius`` metres round ``centre`` (x, y) into ``image`` (a goal of
        one of several robots), blended with ``alpha``."""
        x, y = centre
        r2 = radius * radius

        def inside(
            xs: npt.NDArray[np.float64], ys: npt.NDArray[np.float64]
        ) -> npt.NDArray[np.bool_]:
            return (xs - x) ** 2 + (ys - y) ** 2 <= r2

        self._fill(image, (x - radius, y - radius, x + radius, y + radius), inside, rgb, alpha)

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
        width: int = 1,
    ) -> None:
        """Draws lines ``width`` pixels thick from each start (xs, ys) to its end, line i in
        ``rgb[i]``."""
        col0, row0 = self._x0 + starts[0] * self.scale, self._y0 - starts[1] * self.scale
        col1, row1 = self._x0 + ends[0] * self.scale, self._y0 - ends[1] * self.scale
        longest = max(float(np.abs(col1 - col0).max()), float(np.abs(row1 - row0).max()))
        t = np.linspace(0.0, 1.0, int(longest * 1.5) + 2)[None, :]
        base_cols = col0[:, None] + (col1 - col0)[:, None] * t
        base_rows = row0[:, None] + (row1 - row0)[:, None] * t
        colours = np.broadcast_to(rgb[:, None, :], (*base_cols.shape, 3))
        for shift in range(-(width // 2), width - width // 2):
            for cols, rows in ((base_cols + shift, base_rows), (base_cols, base_rows + shift)):
                cols, rows = cols.astype(np.intp), rows.astype(np.intp)
                keep = (cols >= 0) & (cols < self.width) & (rows >= 0) & (rows < self.height)
                image[rows[keep], cols[keep]] = colours[keep]

    # -- the static world ----------------------------------------------------------------------

    def _draw_world(self, world: World) -> npt.NDArray[np.uint8]:
        grey = int(round(255 * min(max(world.floor_background, 0.0), 1.0)))
        image = np.full((self.height, self.width, 3), grey, dtype=np.uint8)
        for region in world.paint_regions():
            level = int(round(255 * min(max(_number(region["reflectance"]), 0.0), 1.0)))
            self._paint_region(image, region, (level, level, level))
        pixel = 1.0 / self.scale
        for cx, cy, sx, sy, yaw in self._boxes:
            # Half a pixel more on each side, so walls thinner than a pixel still show.
            self._box(image, (cx, cy), (sx + pixel, sy + pixel), yaw, WALL_RGB)
        for checkpoint in world.checkpoints():
            center = _pair(checkpoint["center"])
            yaw = _number(checkpoint["yaw"])
            width = _number(checkpoint["width"])
            outer = (BARCODE_LENGTH + 2 * pixel, width)
            inner = (BARCODE_LENGTH - 2 * pixel, width - 4 * pixel)
            self._box(image, center, outer, yaw, CHECKPOINT_RGB, hollow=inner)
        if self._goal is not None:
            gx, gy, radius = self._goal
            self._fill(
                image,
                (gx - radius, gy - radius, gx + radius, gy + radius),
                lambda px, py: (px - gx) ** 2 + (py - gy) ** 2 <= radius * radius,
                GOAL_RGB,
                GOAL_ALPHA,
            )
        self._draw_start(image)
        image.flags.writeable = False
        return image

    def _draw_start(self, image: npt.NDArray[np.uint8]) -> None:
        """The start pose: a ring of the robot's size and a line along its heading."""
        sx, sy, syaw = self._start
        outer, inner = self._body_radius, self._body_radius - 2.0 / self.scale
        self._fill(
            image,
            (sx - outer, sy - outer, sx + outer, sy + outer),
            lambda px, py: (
                ((px - sx) ** 2 + (py - sy) ** 2 <= outer**2)
                & ((px - sx) ** 2 + (py - sy) ** 2 >= inner**2)
            ),
            START_RGB,
        )
        reach = np.array([1.6 * self._body_radius])
        self._segments(
            image,
            (np.array([sx]), np.array([sy])),
            (sx + math.cos(syaw) * reach, sy + math.sin(syaw) * reach),
            np.array([START_RGB], dtype=np.uint8),
            width=2,
        )

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


def overlay_text(image: npt.NDArray[np.uint8], lines: list[str]) -> npt.NDArray[np.uint8]:
    """A copy of ``image`` with ``lines`` of text in a dark box at its top left."""
    from PIL import Image, ImageDraw, ImageFont

    picture = Image.fromarray(np.ascontiguousarray(image))
    draw = ImageDraw.Draw(picture, "RGBA")
    font = ImageFont.load_default()
    text = "\n".join(lines)
    left, top, right, bottom = draw.multiline_textbbox((6, 4), text, font=font, spacing=2)
    draw.rectangle((left - 3, top - 2, right + 3, bottom + 3), fill=(0, 0, 0, 150))
    draw.multiline_text((6, 4), text, fill=(255, 255, 255, 255), font=font, spacing=2)
    return np.asarray(picture, dtype=np.uint8).copy()


def _disc_offsets(radius_px: float) -> tuple[npt.NDArray[np.intp], npt.NDArray[np.intp]]:
    """(rows, cols) offsets of the pixels of a disc of ``radius_px`` round its centre pixel."""
    reach = int(math.ceil(radius_px))
    rows, cols = np.mgrid[-reach : reach + 1, -reach : reach + 1]
    inside = rows**2 + cols**2 <= radius_px**2
    return rows[inside].astype(np.intp), cols[inside].astype(np.intp)


def _number(value: object) -> float:
    """A number from the core's description of a world (its paint, checkpoints and bodies)."""
    return float(value)  # type: ignore[arg-type]


def _pair(value: object) -> tuple[float, float]:
    """An (x, y) pair from the core's description of a world."""
    first, second = (float(v) for v in value)  # type: ignore[attr-defined]
    return first, second
