"""The world's lights, as the e-puck's light sensors see them.

A world file's ``PointLight``, ``SpotLight`` and ``DirectionalLight`` nodes are read from its
node tree; a light sensor at a point, facing a heading along the floor, receives from each light
that is on::

    E = intensity * (ambientIntensity + max(0, cos(a))) / attenuation

where ``a`` is the angle between the sensor's direction and the way to the light, and the
attenuation of a point or spot light at distance ``d`` is ``a0 + a1 d + a2 d^2`` (its
``attenuation`` field; a directional light has none). Walls do not shade (Webots' LightSensor
``occlusion`` defaults to FALSE). A world without such lights gets
:data:`DEFAULT_IRRADIANCE`.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

from mazesim.webots.frames import nue_to_enu
from mazesim.webots.proto.syntax import Field, Node, first_value

__all__ = ["DEFAULT_IRRADIANCE", "Light", "irradiance", "read_lights"]

#: Irradiance (W/m^2) of a world without light information: the middle of the e-puck light
#: sensors' table (1-2 W/m^2), a reading of 2047.5.
DEFAULT_IRRADIANCE = 1.5

_LIGHT_TYPES = ("PointLight", "SpotLight", "DirectionalLight")


@dataclass(frozen=True)
class Light:
    """A light of the world, in the world frame (ENU).

    Attributes:
        position: Where a point or spot light is (m), or None for a directional light.
        direction: Where a directional light shines to (unit vector), else None.
        intensity: Its ``intensity``.
        ambient: Its ``ambientIntensity``.
        attenuation: Its ``attenuation`` coefficients (constant, linear, quadratic).
        radius: Its ``radius`` (m): beyond it a point or spot light gives nothing.
    """

    position: tuple[float, float, float] | None
    direction: tuple[float, float, float] | None
    intensity: float = 1.0
    ambient: float = 0.0
    attenuation: tuple[float, float, float] = (1.0, 0.0, 0.0)
    radius: float = 100.0


def _numbers(light: Node, name: str, default: tuple[float, ...]) -> tuple[float, ...]:
    """A light's field of ``len(default)`` numbers, ``default`` where the file gives none."""
    return first_value([light], name, lambda item: item.numbers(len(default))) or default


def read_lights(nodes: Iterable[Node], nue: bool = False) -> list[Light]:
    """The lights among a world file's nodes that are on.

    Args:
        nodes: Every node of the world file (:func:`~mazesim.webots.proto.syntax.nodes_in_order`).
        nue: Whether the file is in Webots' old NUE frame (y up); positions are converted.
    """
    lights = []
    for light in nodes:
        if light.type_name not in _LIGHT_TYPES or first_value([light], "on", Field.flag) is False:
            continue
        (intensity,) = _numbers(light, "intensity", (1.0,))
        (ambient,) = _numbers(light, "ambientIntensity", (0.0,))
        if light.type_name == "DirectionalLight":
            x, y, z = _numbers(light, "direction", (0.0, 0.0, -1.0))
            x, y, z = nue_to_enu(x, y, z) if nue else (x, y, z)
            norm = math.sqrt(x * x + y * y + z * z) or 1.0
            lights.append(
                Light(None, (x / norm, y / norm, z / norm), intensity=intensity, ambient=ambient)
            )
            continue
        x, y, z = _numbers(light, "location", (0.0, 0.0, 0.0))
        a0, a1, a2 = _numbers(light, "attenuation", (1.0, 0.0, 0.0))
        (radius,) = _numbers(light, "radius", (100.0,))
        lights.append(
            Light(
                nue_to_enu(x, y, z) if nue else (x, y, z),
                None,
                intensity=intensity,
                ambient=ambient,
                attenuation=(a0, a1, a2),
                radius=radius,
            )
        )
    return lights


def irradiance(
    lights: list[Light] | None, point: tuple[float, float, float], heading: float
) -> float:
    """The irradiance (W/m^2) a sensor at ``point`` facing ``heading`` (along the floor)
    receives; :data:`DEFAULT_IRRADIANCE` when ``lights`` is None or empty."""
    if not lights:
        return DEFAULT_IRRADIANCE
    facing = (math.cos(heading), math.sin(heading), 0.0)
    total = 0.0
    for light in lights:
        if light.position is None:
            assert light.direction is not None
            towards = tuple(-v for v in light.direction)
            attenuation = 1.0
        else:
            offset = [light.position[i] - point[i] for i in range(3)]
            distance = math.sqrt(sum(v * v for v in offset))
            if distance > light.radius:
                continue
            towards = tuple(v / distance for v in offset) if distance > 0 else facing
            a0, a1, a2 = light.attenuation
            attenuation = max(a0 + a1 * distance + a2 * distance * distance, 1e-9)
        cosine = max(0.0, sum(f * t for f, t in zip(facing, towards)))
        total += light.intensity * (light.ambient + cosine) / attenuation
    return total
