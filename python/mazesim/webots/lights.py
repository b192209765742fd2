"""The world's lights, as the e-puck's light sensors see them.

A world file's ``PointLight``, ``SpotLight`` and ``DirectionalLight`` nodes are read from its
node tree, and so are the lights of two PROTOs that hold one (facts of Webots' R2023b-R2025a
PROTO files): a ``TexturedBackgroundLight`` is a DirectionalLight of ``ambientIntensity`` 1 whose
direction and intensity its ``texture`` sets (:data:`BACKGROUND_LIGHTS`; the ``factory``,
``noon_building_overcast`` and ``entrance_hall`` ones are off), times its ``luminosity``, which
counts as 0 when negative; a ``ConstructionLamp`` is a Solid scaled 5 times holding a SpotLight
at (0.0014, 0, 0.001) that shines along its +x axis (``attenuation 0 0 1``, ``cutOffAngle`` 1),
of the lamp's ``spotLightIntensity`` (2) and ``spotLightRadius`` (100), ``beamWidth`` 0.2. A light
sensor at a point, facing a heading along the floor, receives from each light that is on, as
Webots' LightSensor computes it (``WbLightSensor.cpp``)::

    E = (ambientIntensity + intensity * max(0, cos(a)) * spot) / attenuation * (r + g + b) / 3

where ``a`` is the angle between the sensor's direction and the way to the light, (r, g, b) the
light's ``color``, the attenuation of a point or spot light at distance ``d`` is
``a0 + a1 d + a2 d^2`` (its ``attenuation`` field; a directional light has none), and ``spot``
is 1 but for a spot light: 0 for a point farther from its direction than its ``cutOffAngle``,
falling linearly to 0 from its ``beamWidth`` to its ``cutOffAngle``. A point or spot light gives
nothing beyond its ``radius``. A light inside a ``Transform``, ``Pose``, ``Group``, ``Solid``
or any node with a ``translation`` and ``rotation`` (a robot's slot too) is placed by its
parents' poses composed (their ``scale`` is not applied), as Webots places it. A light that a
robot node holds (among its children or in a slot: a "beacon" e-puck that others follow by its
light) moves with the robot, as any node under a Solid does in Webots: :func:`carried` places it
where the robot stands now. Walls do not
shade (Webots' LightSensor ``occlusion`` defaults to FALSE). A world without any light node
gets :data:`DEFAULT_IRRADIANCE`; one whose lights are all off gets none.

A supervisor that sets a light's field (``location``, ``direction``, ``on``, ``intensity``,
``color``, ``attenuation``, ``radius``...; a lamp's ``spotLightIntensity``) or moves a node that
holds a light (its ``translation`` or ``rotation``) changes what every robot's light sensors
receive, as in Webots: the world file's light nodes are read once into :class:`LightSource`
records (the fields as the file gives them, the nodes that hold them), and the lights are made
of them and the fields a supervisor set since (:func:`lit`), by the line of each node.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

from mazesim.webots.frames import SLOT_ORIGINS, WORLD_FRAME, Frame, nue_to_enu, placed
from mazesim.webots.proto.syntax import Field, Node, first_value

__all__ = [
    "BACKGROUND_LIGHTS",
    "DEFAULT_IRRADIANCE",
    "LIGHT_TYPES",
    "Light",
    "LightSource",
    "carried",
    "irradiance",
    "light_sources",
    "lit",
    "read_lights",
]

#: Irradiance (W/m^2) of a world without light information: the middle of the e-puck light
#: sensors' table (1-2 W/m^2), a reading of 2047.5.
DEFAULT_IRRADIANCE = 1.5

_LIGHT_TYPES = ("PointLight", "SpotLight", "DirectionalLight")
#: The PROTOs that hold a light (see the module's docstring).
_LIGHT_PROTOS = ("TexturedBackgroundLight", "ConstructionLamp")
#: The node types whose fields make a light: a supervisor's edit of one changes the lights.
LIGHT_TYPES = frozenset(_LIGHT_TYPES + _LIGHT_PROTOS)
#: The fields of numbers a light is made of, with how many numbers each holds.
_LIGHT_FIELDS = {
    "location": 3,
    "direction": 3,
    "intensity": 1,
    "ambientIntensity": 1,
    "color": 3,
    "attenuation": 3,
    "radius": 1,
    "cutOffAngle": 1,
    "beamWidth": 1,
    "luminosity": 1,
    "translation": 3,
    "rotation": 4,
    "spotLightIntensity": 1,
    "spotLightRadius": 1,
}

#: The DirectionalLight of Webots' ``TexturedBackgroundLight`` PROTO for each ``texture``: its
#: direction as the PROTO writes it (y up; in an ENU world the PROTO turns (a, b, c) into
#: (c, a, b)), its intensity before ``luminosity``, the mean of its colour's components, and
#: whether it is on. Another texture: the PROTO's defaults, (0, -1, 0), 1, white.
BACKGROUND_LIGHTS: dict[str, tuple[tuple[float, float, float], float, float, bool]] = {
    "dawn_cloudy_empty": ((0.022, -0.12, -1.0), 0.8, 2.25 / 3, True),
    "dusk": ((-1.2, -0.3, -0.6), 0.5, 2.75 / 3, True),
    "empty_office": ((-0.2, -0.5, -0.9), 0.05, 1.0, True),
    "entrance_hall": ((0.0, -1.0, 0.0), 1.0, 1.0, False),
    "factory": ((0.0, -1.0, 0.0), 1.0, 1.0, False),
    "mars": ((0.0, -1.0, 0.0), 1.0, 2.41 / 3, True),
    "morning_cloudy_empty": ((1.0, -0.8, -0.1), 0.9, 2.25 / 3, True),
    "mountains": ((-0.6, -1.0, 0.55), 2.7, 1.0, True),
    "music_hall": ((-0.78, -0.6, -0.17), 0.5, 2.8 / 3, True),
    "noon_building_overcast": ((0.0, -1.0, 0.0), 1.0, 1.0, False),
    "noon_cloudy_countryside": ((-0.3, -1.0, -0.1), 3.0, 2.9 / 3, True),
    "noon_cloudy_empty": ((0.2, -1.0, 0.2), 1.0, 2.8 / 3, True),
    "noon_cloudy_mountains": ((0.0, -1.0, -0.5), 0.9, 2.8 / 3, True),
    "noon_park_empty": ((-0.023, -1.0, -0.08), 3.5, 2.916 / 3, True),
    "noon_stormy_empty": ((0.1, -1.0, 0.2), 0.8, 2.8 / 3, True),
    "noon_sunny_empty": ((0.9, -0.59, 0.28), 1.0, 1.0, True),
    "noon_sunny_garden": ((-0.1, -0.3, 0.3), 1.0, 2.8 / 3, True),
    "stadium": ((-2.1, -0.5, 2.1), 2.9, 2.9 / 3, True),
    "stadium_dry": ((-2.1, -0.5, 2.1), 2.9, 2.9 / 3, True),
    "twilight_cloudy_empty": ((1.0, -0.2, -0.7), 1.8, 2.25 / 3, True),
}
#: A ``ConstructionLamp``'s SpotLight in the lamp's frame (its Solid's ``scale 5 5 5`` applied).
_LAMP_LOCATION = (0.007, 0.0, 0.005)


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
        beam: A spot light's direction (unit vector), else None.
        cut_off: A spot light's ``cutOffAngle`` (rad).
        beam_width: A spot light's ``beamWidth`` (rad).
        color: The mean of its ``color``'s components.
        carrier: The line of the robot node that holds it (it moves with that robot; its
            position and directions are where the robot's pose in the file puts them), or None.
    """

    position: tuple[float, float, float] | None
    direction: tuple[float, float, float] | None
    intensity: float = 1.0
    ambient: float = 0.0
    attenuation: tuple[float, float, float] = (1.0, 0.0, 0.0)
    radius: float = 100.0
    beam: tuple[float, float, float] | None = None
    cut_off: float = math.pi
    beam_width: float = math.pi
    color: float = 1.0
    carrier: int | None = None


def _unit(x: float, y: float, z: float) -> tuple[float, float, float]:
    norm = math.sqrt(x * x + y * y + z * z) or 1.0
    return x / norm, y / norm, z / norm


def _given_numbers(node: Node, name: str, count: int) -> tuple[float, ...] | None:
    """A node's field of ``count`` numbers as the file gives it, None where it gives none."""
    found = first_value([node], name, lambda item: item.numbers(count))
    return None if found is None else tuple(found)


@dataclass(frozen=True)
class _Step:
    """A node above a light: its line, its ``translation`` and ``rotation`` (None: none given)
    as the file gives them, and where the slot holding the light is in it (None: no slot)."""

    line: int
    offset: tuple[float, ...]
    turn: tuple[float, ...] | None
    slot: tuple[float, float, float] | None


@dataclass(frozen=True)
class LightSource:
    """A light node of the world file, as :func:`lit` makes a :class:`Light` of it.

    Attributes:
        line: The line of its node type in the world file (a supervisor's node names it so).
        type_name: ``PointLight``, ``SpotLight``, ``DirectionalLight`` or a PROTO holding one.
        holder: The frame of the node that holds it (its parents' poses composed).
        carrier: The line of the robot node that holds it, or None.
        numbers: Its fields of numbers (:data:`_LIGHT_FIELDS`) the file gives.
        on: Its ``on`` field as the file gives it, or None.
        texture: A ``TexturedBackgroundLight``'s ``texture``, or None.
        chain: The nodes that hold it, outermost first (``holder`` is their poses composed):
            a supervisor that moves one (its ``translation`` or ``rotation``) moves the light.
    """

    line: int
    type_name: str
    holder: Frame
    carrier: int | None = None
    numbers: Mapping[str, tuple[float, ...]] = field(default_factory=dict)
    on: bool | None = None
    texture: str | None = None
    chain: tuple[_Step, ...] = ()

    @property
    def holders(self) -> set[int]:
        """The lines of the nodes that hold it."""
        return {step.line for step in self.chain if step.line}


class _Fields:
    """A light's fields: those a supervisor set (``edits``, by field name), else the file's."""

    def __init__(self, source: LightSource, edits: Mapping[str, Any]) -> None:
        self._source = source
        self._edits = edits

    def numbers(self, name: str, default: tuple[float, ...]) -> tuple[float, ...]:
        edited = self._edits.get(name)
        if isinstance(edited, (list, tuple)) and len(edited) >= len(default):
            return tuple(float(v) for v in edited[: len(default)])
        return self._source.numbers.get(name, default)

    def on(self) -> bool:
        edited = self._edits.get("on")
        if isinstance(edited, bool):
            return edited
        return self._source.on is not False


def _background_light(fields: _Fields, texture: str | None, nue: bool) -> Light | None:
    """The DirectionalLight of a ``TexturedBackgroundLight``, or None when it is off."""
    default = ((0.0, -1.0, 0.0), 1.0, 1.0, True)
    (x, y, z), intensity, color, on = BACKGROUND_LIGHTS.get(texture or "mountains", default)
    (luminosity,) = fields.numbers("luminosity", (1.0,))
    if not on:
        return None
    direction = nue_to_enu(x, y, z) if nue else (z, x, y)
    intensity *= max(luminosity, 0.0)
    return Light(None, _unit(*direction), intensity=intensity, ambient=1.0, color=color)


def _point(frame: Frame, p: tuple[float, ...]) -> tuple[float, float, float]:
    """A point of a node placed in ``frame``, in the world file's frame."""
    x, y, z = placed(frame, p)[0]
    return x, y, z


def _direction(frame: Frame, d: tuple[float, ...]) -> tuple[float, float, float]:
    """A direction of a node placed in ``frame``, in the world file's frame."""
    m = frame[1]
    x, y, z = (sum(m[3 * i + k] * d[k] for k in range(3)) for i in range(3))
    return x, y, z


def _construction_lamp(fields: _Fields, holder: Frame, nue: bool) -> Light:
    """The SpotLight of a ``ConstructionLamp`` placed in ``holder``, by the lamp's own pose."""
    frame = placed(
        holder,
        fields.numbers("translation", (0.0, 0.0, 0.07)),
        fields.numbers("rotation", (0.0, 0.0, 1.0, 0.0)),
    )
    location = _point(frame, _LAMP_LOCATION)
    beam = _direction(frame, (1.0, 0.0, 0.0))
    (intensity,) = fields.numbers("spotLightIntensity", (2.0,))
    (radius,) = fields.numbers("spotLightRadius", (100.0,))
    return Light(
        nue_to_enu(*location) if nue else location,
        None,
        intensity=intensity,
        attenuation=(0.0, 0.0, 1.0),
        radius=radius,
        beam=_unit(*(nue_to_enu(*beam) if nue else beam)),
        cut_off=1.0,
        beam_width=0.2,
    )


def _frame_of(chain: Sequence[_Step], edits: Mapping[int, Mapping[str, Any]]) -> Frame:
    """The frame the nodes of ``chain`` (outermost first) place a node in, each node's
    ``translation`` and ``rotation`` as a supervisor set them (``edits``) or as the file gives
    them."""
    frame = WORLD_FRAME
    for step in chain:
        moved = edits.get(step.line, {})
        offset = moved.get("translation", step.offset)
        turn = moved.get("rotation", step.turn)
        frame = placed(frame, offset, turn)
        if step.slot is not None:
            frame = placed(frame, step.slot)
    return frame


def _placed_nodes(
    tree: Iterable[Node],
    carrier_of: Callable[[Node], int | None],
    slots: bool = True,
    line_of: Callable[[Node], int] = lambda node: 0,
) -> Iterator[tuple[Node, tuple[_Step, ...], int | None]]:
    """Every node of the trees ``tree`` (``USE`` ones left out) with the nodes that hold it
    (outermost first: :func:`_frame_of` composes their poses) and the robot that holds it
    (``carrier_of`` a robot node: its line; None for another node), in file order (a stack,
    not recursion, so at any depth); with ``slots``, an E-puck's slots are where its PROTO
    mounts them since R2022a (Z-up)."""
    pending: list[tuple[Node, tuple[_Step, ...], int | None]] = [
        (node, (), None) for node in reversed(list(tree))
    ]
    while pending:
        node, chain, carrier = pending.pop()
        if node.use_name is not None:
            continue
        yield node, chain, carrier
        offset = _given_numbers(node, "translation", 3) or (0.0, 0.0, 0.0)
        turn = _given_numbers(node, "rotation", 4)
        held = carrier if carrier is not None else carrier_of(node)
        line = line_of(node)
        inner = [
            (
                n,
                (
                    *chain,
                    _Step(
                        line,
                        offset,
                        turn,
                        SLOT_ORIGINS.get((node.type_name, item.name)) if slots else None,
                    ),
                ),
                held,
            )
            for item in node.fields
            for n in item.nodes
        ]
        pending.extend(reversed(inner))


def light_sources(
    tree: Iterable[Node],
    nue: bool = False,
    carrier_of: Callable[[Node], int | None] = lambda node: None,
    line_of: Callable[[Node], int] = lambda node: 0,
) -> list[LightSource] | None:
    """The light nodes of a world file, each with the frame its parents' poses place it in;
    None when it has no light node.

    Args:
        tree: The nodes at the top of the world file (their children are walked).
        nue: Whether the file is in Webots' old NUE frame (y up): an E-puck's slots are then
            where its node puts them.
        carrier_of: The line of a robot node (the lights it holds move with it), None for
            any other node.
        line_of: The line of a node's type in the world file.
    """
    sources: list[LightSource] = []
    for light, chain, carrier in _placed_nodes(tree, carrier_of, not nue, line_of):
        if light.type_name not in LIGHT_TYPES:
            continue
        numbers = {
            name: found
            for name, count in _LIGHT_FIELDS.items()
            if (found := _given_numbers(light, name, count)) is not None
        }
        sources.append(
            LightSource(
                line_of(light),
                light.type_name,
                _frame_of(chain, {}),
                carrier,
                numbers,
                first_value([light], "on", Field.flag),
                first_value([light], "texture", Field.string),
                chain,
            )
        )
    return sources if sources else None


def lit(
    sources: Sequence[LightSource] | None,
    nue: bool = False,
    edits: Mapping[int, Mapping[str, Any]] | None = None,
) -> list[Light] | None:
    """The lights of ``sources`` that are on, their fields as a supervisor set them
    (``edits``: by the line of the light's node, each field's value by name) or else as the
    file gives them; None when there is no light node (``sources`` None)."""
    if sources is None:
        return None
    lights: list[Light] = []
    edits = edits or {}
    for source in sources:
        fields = _Fields(source, edits.get(source.line, {}))
        if any(step.line in edits for step in source.chain):
            source = replace(source, holder=_frame_of(source.chain, edits))
        made = _light(source, fields, nue)
        if made is not None:
            lights.append(made)
    return lights


def _light(source: LightSource, fields: _Fields, nue: bool) -> Light | None:
    """The light a source makes with ``fields``, None when it is off."""
    holder, carrier = source.holder, source.carrier
    if source.type_name == "TexturedBackgroundLight":
        return _background_light(fields, source.texture, nue)
    if source.type_name == "ConstructionLamp":
        return replace(_construction_lamp(fields, holder, nue), carrier=carrier)
    if not fields.on():
        return None
    (intensity,) = fields.numbers("intensity", (1.0,))
    (ambient,) = fields.numbers("ambientIntensity", (0.0,))
    color = sum(fields.numbers("color", (1.0, 1.0, 1.0))) / 3.0
    if source.type_name == "DirectionalLight":
        x, y, z = _direction(holder, fields.numbers("direction", (0.0, 0.0, -1.0)))
        direction = _unit(*(nue_to_enu(x, y, z) if nue else (x, y, z)))
        return Light(None, direction, intensity, ambient, color=color, carrier=carrier)
    x, y, z = _point(holder, fields.numbers("location", (0.0, 0.0, 0.0)))
    a0, a1, a2 = fields.numbers("attenuation", (1.0, 0.0, 0.0))
    (radius,) = fields.numbers("radius", (100.0,))
    beam, cut_off, beam_width = None, math.pi, math.pi
    if source.type_name == "SpotLight":
        bx, by, bz = _direction(holder, fields.numbers("direction", (0.0, 0.0, -1.0)))
        beam = _unit(*(nue_to_enu(bx, by, bz) if nue else (bx, by, bz)))
        (cut_off,) = fields.numbers("cutOffAngle", (math.pi / 4,))
        (beam_width,) = fields.numbers("beamWidth", (math.pi / 2,))
    return Light(
        nue_to_enu(x, y, z) if nue else (x, y, z),
        None,
        intensity=intensity,
        ambient=ambient,
        attenuation=(a0, a1, a2),
        radius=radius,
        beam=beam,
        cut_off=cut_off,
        beam_width=beam_width,
        color=color,
        carrier=carrier,
    )


def read_lights(
    tree: Iterable[Node],
    nue: bool = False,
    carrier_of: Callable[[Node], int | None] = lambda node: None,
) -> list[Light] | None:
    """The lights of a world file that are on, each placed by its parents' poses; None when
    it has no light node (:func:`light_sources` made into lights by :func:`lit`)."""
    return lit(light_sources(tree, nue, carrier_of), nue)


def carried(light: Light, start: Sequence[float], now: Sequence[float]) -> Light:
    """``light`` as its carrier robot, whose pose (x, y, yaw) in the world file is ``start``,
    now standing at ``now`` holds it: its position and directions turned about the vertical by
    the robot's turn since, and moved with it."""
    turn = float(now[2]) - float(start[2])
    cos, sin = math.cos(turn), math.sin(turn)

    def turned(v: tuple[float, float, float] | None) -> tuple[float, float, float] | None:
        return None if v is None else (cos * v[0] - sin * v[1], sin * v[0] + cos * v[1], v[2])

    position = None
    if light.position is not None:
        dx, dy, z = light.position[0] - start[0], light.position[1] - start[1], light.position[2]
        x, y, _ = turned((dx, dy, z))  # type: ignore[misc]
        position = (x + float(now[0]), y + float(now[1]), z)
    return replace(
        light, position=position, direction=turned(light.direction), beam=turned(light.beam)
    )


def irradiance(
    lights: list[Light] | None, point: tuple[float, float, float], heading: float
) -> float:
    """The irradiance (W/m^2) a sensor at ``point`` facing ``heading`` (along the floor)
    receives; :data:`DEFAULT_IRRADIANCE` when ``lights`` is None (a world without light nodes),
    0 when it is empty (every light off)."""
    if lights is None:
        return DEFAULT_IRRADIANCE
    facing = (math.cos(heading), math.sin(heading), 0.0)
    total = 0.0
    for light in lights:
        spot = 1.0
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
            if light.beam is not None:
                spot = _spot_factor(light, towards)
        cosine = max(0.0, sum(f * t for f, t in zip(facing, towards)))
        total += (light.ambient + light.intensity * cosine * spot) / attenuation * light.color
    return total


def _spot_factor(light: Light, towards: tuple[float, ...]) -> float:
    """How much of a spot light's intensity reaches a point the unit vector ``towards`` leads
    from to the light: 1 within its beam width, 0 beyond its cut-off angle, linear between."""
    assert light.beam is not None
    along = -sum(b * t for b, t in zip(light.beam, towards))
    angle = math.acos(max(-1.0, min(1.0, along)))
    if angle > light.cut_off:
        return 0.0
    if angle <= light.beam_width:
        return 1.0
    return (angle - light.cut_off) / (light.beam_width - light.cut_off)
