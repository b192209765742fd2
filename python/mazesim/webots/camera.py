"""The e-puck's camera: a forward view rendered from the 2D world.

Each pixel is a ray from the camera (0.03 m ahead of the axle, 0.028 m above the floor, level,
field of view 0.84 rad, 52 x 39 pixels as in Webots' E-puck PROTO). A ray that meets a wall below
the wall's height sees the wall (grey from its reflectance); a ray going down that meets the floor
first sees the floor paint, grey from its reflectance factor ``f`` (``(f - 0.2) / 0.8``, so a white
floor is 255 and black paint 0, the inverse of the infra-red model); anything else sees the sky.
Images are BGRA bytes, as Webots gives them.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from mazesim.webots.devices import _print_error, _Sensor, webots_property
from mazesim.webots.node_types import node_type
from mazesim.webots.rays import FloorPaint, WallBoxes

if TYPE_CHECKING:
    from mazesim.webots.simulation import RobotSimulation

__all__ = ["Camera", "CameraRecognitionObject", "CameraView", "render"]

#: Image size and field of view of Webots' E-puck PROTO camera.
DEFAULT_WIDTH = 52
DEFAULT_HEIGHT = 39
DEFAULT_FOV = 0.84
#: The camera's position on the robot (m): ahead of the wheel axle, above the floor.
CAMERA_X = 0.03
CAMERA_Z = 0.028
#: Wall height (m) when the world gives none: the e-puck worlds' usual walls.
WALL_HEIGHT = 0.1
#: Grey of a wall of reflectance 1 (walls are drawn a little darker than a white floor).
WALL_SHADE = 0.8
#: Colour of the sky (RGB).
SKY = (150, 180, 210)


@dataclass(frozen=True)
class CameraView:
    """Where a camera sits and what it sees: pose on the robot, image size, field of view."""

    width: int = DEFAULT_WIDTH
    height: int = DEFAULT_HEIGHT
    fov: float = DEFAULT_FOV
    x: float = CAMERA_X
    z: float = CAMERA_Z
    pitch: float = 0.0
    wall_height: float = WALL_HEIGHT


def render(
    view: CameraView, walls: WallBoxes, floor: FloorPaint, pose: tuple[float, float, float]
) -> npt.NDArray[np.uint8]:
    """Renders the view from a robot pose.

    Args:
        view: The camera.
        walls: The world's walls.
        floor: The world's floor paint.
        pose: The robot's x, y, yaw.

    Returns:
        A (height, width, 4) array of B, G, R, A.
    """
    x, y, yaw = pose
    focal = (view.width / 2.0) / math.tan(view.fov / 2.0)
    left = (view.width / 2.0 - (np.arange(view.width) + 0.5)) / focal
    up = (view.height / 2.0 - (np.arange(view.height) + 0.5)) / focal
    # Pitch (down positive) turns each ray about the camera's left axis.
    cos_p, sin_p = math.cos(view.pitch), math.sin(view.pitch)
    forward = cos_p + sin_p * up[:, None] * np.ones_like(left)[None, :]
    rise = up[:, None] * cos_p - sin_p * np.ones_like(left)[None, :]
    cos_y, sin_y = math.cos(yaw), math.sin(yaw)
    ox = x + cos_y * view.x
    oy = y + sin_y * view.x
    dx = cos_y * forward - sin_y * left[None, :]
    dy = sin_y * forward + cos_y * left[None, :]
    if view.pitch == 0.0:
        # A level camera: every row of a column casts the same ray along the floor.
        column_t, column_reflectance = walls.cast((ox, oy), np.stack([dx[0], dy[0]], axis=1))
        wall_t = np.broadcast_to(column_t, rise.shape)
        wall_reflectance = np.broadcast_to(column_reflectance, rise.shape)
    else:
        directions = np.stack([dx.ravel(), dy.ravel()], axis=1)
        wall_t, wall_reflectance = walls.cast((ox, oy), directions)
        wall_t = wall_t.reshape(rise.shape)
        wall_reflectance = wall_reflectance.reshape(rise.shape)
    with np.errstate(divide="ignore", invalid="ignore"):
        floor_t = np.where(rise < 0.0, view.z / -rise, np.inf)
    sees_wall = np.isfinite(wall_t) & (wall_t <= floor_t)
    # A ray that meets no wall (an open side of the world) has no height to compare.
    hit_height = view.z + np.where(np.isfinite(wall_t), wall_t, 0.0) * rise
    sees_wall &= hit_height <= view.wall_height
    sees_floor = ~sees_wall & np.isfinite(floor_t)
    image = np.empty(rise.shape + (4,), dtype=np.uint8)
    image[...] = (SKY[2], SKY[1], SKY[0], 255)
    if sees_floor.any():
        t = floor_t[sees_floor]
        reflectance = floor.reflectance(ox + t * dx[sees_floor], oy + t * dy[sees_floor])
        grey = _grey(reflectance, 1.0)
        image[sees_floor, :3] = grey[:, None]
    if sees_wall.any():
        image[sees_wall, :3] = _grey(wall_reflectance[sees_wall], WALL_SHADE)[:, None]
    return image


def _grey(reflectance: npt.NDArray[np.float64], shade: float) -> npt.NDArray[np.uint8]:
    level = np.clip((reflectance - 0.2) / 0.8, 0.0, 1.0) * 255.0 * shade
    return np.asarray(np.rint(level), dtype=np.uint8)


class CameraRecognitionObject:
    """An object the camera recognises (the e-puck's camera has no Recognition node)."""

    def __init__(self) -> None:
        self.id = -1
        self.position = [math.nan] * 3
        self.orientation = [math.nan] * 4
        self.size = [math.nan] * 2
        self.position_on_image = [0, 0]
        self.size_on_image = [0, 0]
        self.number_of_colors = 0
        self.colors: list[float] = []
        self.model = ""

    def getId(self) -> int:
        """The object's id."""
        return self.id

    def getPosition(self) -> list[float]:
        """The object's position relative to the camera."""
        return self.position

    def getOrientation(self) -> list[float]:
        """The object's orientation relative to the camera (axis-angle)."""
        return self.orientation

    def getSize(self) -> list[float]:
        """The object's size."""
        return self.size

    def getPositionOnImage(self) -> list[int]:
        """The object's position on the image (pixels)."""
        return self.position_on_image

    def getSizeOnImage(self) -> list[int]:
        """The object's size on the image (pixels)."""
        return self.size_on_image

    def getNumberOfColors(self) -> int:
        """How many colours the object has."""
        return self.number_of_colors

    def getColors(self) -> list[float]:
        """The object's colours."""
        return self.colors

    def getModel(self) -> str:
        """The object's model."""
        return self.model


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
        self._walls: WallBoxes | None = None
        self._floor: FloorPaint | None = None
        self._pixels: npt.NDArray[np.uint8] | None = None
        self._bytes: bytes | None = None
        self._value = None

    def _read(self) -> Any:
        if self._walls is None or self._floor is None:
            self._walls = WallBoxes(self._simulation.world)
            self._floor = FloorPaint(self._simulation.world)
        self._bytes = None
        self._pixels = render(self._view, self._walls, self._floor, self._simulation.simulator.pose)
        return True

    def _image(self) -> npt.NDArray[np.uint8] | None:
        if self._period_ms == 0 and self._pixels is None:
            self._warn_disabled("get_image")
        if self._pixels is None and self._period_ms and self._simulation.steps > self._enabled_at:
            # Webots' wb_camera_get_image returns an enabled camera's image buffer, set up at
            # the first step after the camera is enabled and drawn when its first sampling
            # period ends (src/controller/c/camera.c, WbSensor.cpp): black until then.
            return np.zeros((self._view.height, self._view.width, 4), dtype=np.uint8)
        return self._pixels

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

    image = webots_property("getImage")

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

    width = webots_property("getWidth")
    height = webots_property("getHeight")

    def getFov(self) -> float:
        """Horizontal field of view in radians."""
        return self._view.fov

    fov = webots_property("getFov")

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

    def hasRecognition(self) -> bool:
        """False: the e-puck's camera has no Recognition node."""
        return False

    def recognitionEnable(self, samplingPeriod: int) -> None:
        """Webots' error: no Recognition node."""
        _print_error(
            "Error: wb_camera_recognition_enable() called on a Camera without Recognition node."
        )

    def recognitionDisable(self) -> None:
        """Nothing to disable."""

    def getRecognitionSamplingPeriod(self) -> int:
        """0: recognition is never enabled."""
        return 0

    def getRecognitionNumberOfObjects(self) -> int:
        """0: nothing is recognised."""
        return 0

    def getRecognitionObjects(self) -> list[CameraRecognitionObject]:
        """The empty list: nothing is recognised."""
        return []

    def hasRecognitionSegmentation(self) -> bool:
        """False: no segmentation."""
        return False

    def enableRecognitionSegmentation(self) -> None:
        """Webots' error: no Recognition node."""
        _print_error(
            "Error: wb_camera_recognition_enable_segmentation() called on a Camera without "
            "Recognition node."
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

    def saveImage(self, filename: str, quality: int = 100) -> int:
        """Saves the last image as PNG or JPEG (by the file's extension).

        Returns:
            0 on success, -1 on failure (no image yet, unknown extension, unwritable file).
        """
        pixels = self._pixels
        extension = os.path.splitext(filename)[1].lower()
        if pixels is None or extension not in (".png", ".jpg", ".jpeg"):
            _print_error(f"Error: wb_camera_save_image() cannot save {filename!r}.")
            return -1
        from matplotlib import image as images

        rgb = np.ascontiguousarray(pixels[:, :, 2::-1])
        try:
            images.imsave(filename, rgb)
        except (OSError, ValueError):
            return -1
        return 0

    @staticmethod
    def imageGetRed(image: bytes, width: int, x: int, y: int) -> int:
        """The red level (0-255) of pixel (x, y) of a BGRA image."""
        return image[4 * (y * width + x) + 2]

    @staticmethod
    def imageGetGreen(image: bytes, width: int, x: int, y: int) -> int:
        """The green level (0-255) of pixel (x, y) of a BGRA image."""
        return image[4 * (y * width + x) + 1]

    @staticmethod
    def imageGetBlue(image: bytes, width: int, x: int, y: int) -> int:
        """The blue level (0-255) of pixel (x, y) of a BGRA image."""
        return image[4 * (y * width + x)]

    @staticmethod
    def imageGetGray(image: bytes, width: int, x: int, y: int) -> int:
        """The grey level (0-255, the mean of red, green and blue) of pixel (x, y)."""
        base = 4 * (y * width + x)
        return (image[base] + image[base + 1] + image[base + 2]) // 3

    @staticmethod
    def imageGetGrey(image: bytes, width: int, x: int, y: int) -> int:
        """Same as :meth:`imageGetGray`."""
        return Camera.imageGetGray(image, width, x, y)
