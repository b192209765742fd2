"""How a notebook shows a world and a simulator: a top-down picture, not a line of text.

Jupyter (and IPython's other front ends) shows an object's ``_repr_png_`` when it has one. A
:class:`~mazesim.World` left as the last line of a cell is drawn with its walls, floor paint,
checkpoints, start and goal; a :class:`~mazesim.Simulator` with its robot at its pose and its
distance-sensor rays, as the environments' ``render()`` draws them
(:class:`mazesim.render.topdown.TopDownRenderer`, numpy and Pillow only: no matplotlib figure
is made). ``repr()`` stays the one line it was.
"""

from __future__ import annotations

import io
from typing import Any

__all__ = ["install"]

#: The size of the picture in pixels, that of the environments' frames.
SIZE = (400, 400)


def _png(image: Any) -> bytes:
    from PIL import Image

    buffer = io.BytesIO()
    Image.fromarray(image).save(buffer, format="PNG")
    return buffer.getvalue()


def _renderer(world: Any, profile: Any) -> Any:
    from mazesim.render.topdown import TopDownRenderer

    return TopDownRenderer(world, profile, SIZE, profile.distance_sensor_range)


def world_png(world: Any) -> bytes:
    """The world drawn from above (walls, paint, checkpoints, start and goal), as PNG bytes."""
    from mazesim._core import RobotProfile

    return _png(_renderer(world, RobotProfile.builtin("e-puck")).background)


def simulator_png(simulator: Any) -> bytes:
    """The simulator's world with its robot at its pose and its sensor rays, as PNG bytes."""
    renderer = _renderer(simulator.world, simulator.robot_profile(0))
    return _png(renderer.frame(simulator.pose, colliding=bool(simulator.colliding)))


def install(world_class: type, simulator_class: type) -> None:
    """Gives the two classes of the compiled core their notebook picture (``_repr_png_``)."""
    world_class._repr_png_ = world_png  # type: ignore[attr-defined]
    simulator_class._repr_png_ = simulator_png  # type: ignore[attr-defined]
