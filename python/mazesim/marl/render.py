"""Top-down pictures of a multi-robot episode, drawn by the package's renderer
(:class:`mazesim.render.topdown.TopDownRenderer`): the world, every robot's goal disc, and every
robot with its heading and its distance-sensor rays (red while in contact)."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from mazesim._core import RobotProfile, World
from mazesim.render.topdown import TopDownRenderer

__all__ = ["SwarmRenderer"]


class SwarmRenderer:
    """Draws frames of one world and its robots.

    Args:
        world: The episode's world.
        robot: The robots' profile.
        goals: (R, 3) x, y, radius of each robot's goal (NaN rows: none).
        size: (width, height) of the frames in pixels.
    """

    def __init__(
        self,
        world: World,
        robot: RobotProfile,
        goals: npt.NDArray[np.float64],
        size: tuple[int, int] = (400, 400),
    ) -> None:
        self._renderer = TopDownRenderer(world, robot, size)
        self._background = self._renderer.background.copy()
        for x, y, radius in goals:
            if np.isfinite(radius):
                self._renderer.mark_disc(self._background, (float(x), float(y)), float(radius))

    def frame(
        self, poses: npt.NDArray[np.float32], colliding: npt.NDArray[np.bool_]
    ) -> npt.NDArray[np.uint8]:
        """A (height, width, 3) uint8 picture with the robots at ``poses`` (R, 3)."""
        image = self._background
        try:
            for pose, touching in zip(poses, colliding):
                self._renderer.background = image
                image = self._renderer.frame(
                    (float(pose[0]), float(pose[1]), float(pose[2])), bool(touching)
                )
        finally:
            self._renderer.background = self._background
        return image.copy() if image is self._background else image
