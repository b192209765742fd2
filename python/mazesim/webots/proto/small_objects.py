"""Stand-ins for Webots' small stock objects, written as data: each object's collision shapes
(boxes, upright cylinders, spheres), the colour a camera sees, its recognition colours and its
physics by default, from which :func:`stand_in_text` writes a procedural PROTO.

The facts are read from the objects' PROTO files in Webots' repository (cyberbotics/webots,
``projects/objects/**/protos/NAME.proto``, R2023a-R2025a; each entry names its file); no PROTO
text is kept. Sizes are metres in the Z-up frame of those files (a Y-up world gets the same
shapes stood up, as the other stand-ins do). Where a file's collision shape is a mesh (a rock)
or a group of many parts, the stand-in keeps the parts an e-puck can meet, near the floor, and
says so in its description. The colour a camera sees is the object's first recognition colour
where its file gives one (the colour its authors chose to stand for it), else its base colour,
else, for a textured surface, the texture's main colour as estimated here (marked "estimate").
Where the real PROTO file can be read (``WEBOTS_HOME``, the cache, the network) it is used
instead. A ``PingPongBall`` (2.8 g, ``projects/objects/balls/protos/PingPongBall.proto``) has
none: an e-puck pushes it aside in Webots, where mazesim, which moves at most one body, would
hold it still in the robot's way (a course's supervisor moves one to each next waypoint as a
marker).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Union

from mazesim.errors import InvalidArgumentError, _shown

__all__ = ["SMALL_OBJECTS", "Part", "SmallObject", "stand_in_text"]

#: A number of a part: a float, or a JavaScript expression of the PROTO's fields and ``k``, the
#: object's ``scale`` (1 for an object without one).
Number = Union[float, str]


@dataclass(frozen=True)
class Part:
    """One collision shape, seen by the camera too: ``kind`` ``box`` (``size`` x, y, z),
    ``cylinder`` (radius, height, upright) or ``sphere`` (radius), centred at ``centre`` from
    the object's origin."""

    kind: str
    size: tuple[Number, ...]
    centre: tuple[Number, Number, Number] = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class SmallObject:
    """A stock object: its default ``name`` and ``translation`` height, its ``parts``, the
    ``colour`` (red, green, blue, or a field's name) a camera sees, its ``recognition`` colours,
    its physics (``physics``: a JavaScript expression giving its mass in kg, 0 for none;
    ``"density:EXPRESSION"``, its density in kg/m^3; or ``"field"``, its ``physics`` field,
    NULL by default), the fields it declares beyond translation, rotation and name (VRML
    declarations; ``scaled``: a ``scale`` field multiplies every size), what the stand-in models
    and the file the facts come from."""

    label: str
    parts: tuple[Part, ...]
    colour: tuple[float, float, float] | str
    description: str
    source: str
    lift: float = 0.0
    recognition: tuple[tuple[float, float, float], ...] = ()
    physics: str = "0"
    fields: tuple[str, ...] = ()
    scaled: bool = False


def _js(value: Number) -> str:
    return value if isinstance(value, str) else repr(float(value))


def _scaled(value: Number, scaled: bool) -> str:
    return f"({_js(value)}) * k" if scaled else f"({_js(value)})"


def _part_text(part: Part, scaled: bool, colour: str = "") -> str:
    """The part as a Pose around its geometry; around a Shape of ``colour`` (a base colour or
    ``IS field``) when one is given."""
    x, y, z = (_scaled(v, scaled) for v in part.centre)
    size = [_scaled(v, scaled) for v in part.size]
    if part.kind == "box":
        sx, sy, sz = size
        geometry = (
            f"Box {{ size %<= yUp ? `${{{sx}}} ${{{sz}}} ${{{sy}}}` "
            f": `${{{sx}}} ${{{sy}}} ${{{sz}}}` >% }}"
        )
    elif part.kind == "cylinder":
        geometry = f"Cylinder {{ radius %<= {size[0]} >% height %<= {size[1]} >% }}"
    elif part.kind == "sphere":
        geometry = f"Sphere {{ radius %<= {size[0]} >% }}"
    else:
        raise InvalidArgumentError(
            f"part kind {_shown(part.kind)}: expected box, cylinder or sphere"
        )
    if colour:
        look = f"PBRAppearance {{ baseColor {colour} roughness 1 metalness 0 }}"
        geometry = f"Shape {{ appearance {look} geometry {geometry} }}"
    where = f"%<= yUp ? `${{{x}}} ${{{z}}} ${{{y}}}` : `${{{x}}} ${{{y}}} ${{{z}}}` >%"
    return f"Pose {{ translation {where} children [ {geometry} ] }}"


def stand_in_text(name: str, thing: SmallObject) -> str:
    """The stand-in PROTO of the stock object ``name``."""
    colour = (
        f"IS {thing.colour}"
        if isinstance(thing.colour, str)
        else " ".join(repr(c) for c in thing.colour)
    )
    declared = "\n".join(f"  {line}" for line in thing.fields)
    shapes = "\n".join(f"      {_part_text(p, thing.scaled, colour)}" for p in thing.parts)
    bounds = "\n".join(f"        {_part_text(p, thing.scaled)}" for p in thing.parts)
    recognition = " ".join(" ".join(repr(c) for c in rgb) for rgb in thing.recognition)
    if thing.physics == "field":
        physics = "    physics IS physics"
    else:
        kind, _, expression = thing.physics.rpartition(":")
        given = "density %<= amount >%" if kind == "density" else "density -1 mass %<= amount >%"
        physics = (
            f"    %< const amount = {expression}; if (amount > 0) {{ >%\n"
            f"    physics Physics {{ {given} }}\n"
            "    %< } >%"
        )
    scale = "fields.scale.value > 0 ? fields.scale.value : 1" if thing.scaled else "1"
    return f"""#VRML_SIM R2023b utf8
# template language: javascript
PROTO {name} [
  field SFVec3f translation 0 0 {repr(thing.lift)}
  field SFRotation rotation 0 0 1 0
  field SFString name "{thing.label}"
{declared}
]
{{
  %< const yUp = context.coordinate_system === 'NUE'; const k = {scale}; >%
  Solid {{
    translation IS translation
    rotation IS rotation
    name IS name
    recognitionColors [ {recognition} ]
    children [
{shapes}
    ]
    boundingObject Group {{
      children [
{bounds}
      ]
    }}
{physics}
  }}
}}
"""


def _box(x: Number, y: Number, z: Number, at: tuple[Number, Number, Number]) -> Part:
    return Part("box", (x, y, z), at)


def _cylinder(radius: Number, height: Number, at: tuple[Number, Number, Number]) -> Part:
    return Part("cylinder", (radius, height), at)


_MASS = "field SFFloat mass {}"
_JAR = _cylinder(0.045, 0.115, (0.0, 0.0, 0.058))
#: A size field's box standing on the object's origin.
_SIZED_BOX = _box(
    "fields.size.value.x", "fields.size.value.y", "fields.size.value.z",
    (0.0, 0.0, "fields.size.value.z / 2"),
)  # fmt: skip
#: A FIFA ball's radius by its size field (1 to 5), and its mass.
_FIFA_RADIUS = (
    "[0.07, 0.085, 0.095, 0.1025, 0.1125][Math.min(5, Math.max(1, fields.size.value)) - 1]"
)
_FIFA_MASS = "[0.205, 0.25, 0.31, 0.37, 0.43][Math.min(5, Math.max(1, fields.size.value)) - 1]"
_PALLETS = "Math.max(0, fields.palletNumber.value)"
_BOARD_HEIGHT = "fields.displayHeight.value + 0.2"

#: The stand-ins, by PROTO name.
SMALL_OBJECTS: dict[str, SmallObject] = {
    "HoneyJar": SmallObject(
        "honey jar",
        (_JAR,),
        "color",
        "an upright cylinder of the documented size, mass and colour",
        "projects/objects/kitchen/breakfast/protos/HoneyJar.proto@f09e7bfc",
        fields=(_MASS.format(0.5), "field SFColor color 0.839216 0.572549 0.105882"),
        physics="fields.mass.value",
    ),
    "JamJar": SmallObject(
        "jam jar",
        (_JAR,),
        (0.55, 0.06, 0.06),
        "an upright cylinder of the documented size and mass, of its recognition colour",
        "projects/objects/kitchen/breakfast/protos/JamJar.proto@6c0f3ebe",
        recognition=((0.55, 0.06, 0.06), (0.86, 0.88, 0.9)),
        fields=(_MASS.format(0.5),),
        physics="fields.mass.value",
    ),
    "BiscuitBox": SmallObject(
        "biscuit box",
        (_SIZED_BOX,),
        (0.92, 0.76, 0.3),
        "a box of the given size and mass, of its recognition colour",
        "projects/objects/kitchen/breakfast/protos/BiscuitBox.proto@6c0f3ebe",
        recognition=((0.92, 0.76, 0.3),),
        fields=("field SFVec3f size 0.08 0.24 0.04", _MASS.format(0.4)),
        physics="fields.mass.value",
    ),
    "PlasticCrate": SmallObject(
        "plastic crate",
        (_SIZED_BOX,),
        "color",
        "a box of the given size (its open top aside), of the given colour and mass",
        "projects/objects/factory/containers/protos/PlasticCrate.proto@272f7b51",
        fields=(
            "field SFVec3f size 0.6 0.6 0.6",
            "field SFColor color 0.9 0.2 0.2",
            _MASS.format(0),
        ),
        physics="fields.mass.value",
    ),
    "RubberDuck": SmallObject(
        "rubber duck",
        (_box(0.1, 0.076, 0.104, (0.0, 0.0, 0.032)),),
        "bodyColor",
        "a box of the duck's extent (0.1 x 0.076 x 0.104 m times its scale), of density 400",
        "projects/objects/toys/protos/RubberDuck.proto@d2bde645",
        lift=0.02,
        recognition=((0.875, 0.757, 0.114),),
        fields=(
            "field SFFloat scale 1",
            "field SFColor bodyColor 1 0.8 0",
            "field SFFloat density 400",
        ),
        physics="density:fields.density.value",
        scaled=True,
    ),
    "WaterBottle": SmallObject(
        "water bottle",
        (_cylinder(0.044, 0.306, (0.0, 0.0, 0.153)),),
        (0.9, 0.9, 0.9),
        "an upright cylinder of the bottle's radius and height; white (estimate: a clear label)",
        "projects/objects/drinks/protos/WaterBottle.proto@f09e7bfc",
        fields=(_MASS.format(1),),
        physics="fields.mass.value",
    ),
    "BeerBottle": SmallObject(
        "beer bottle",
        (_cylinder(0.031, 0.232, (0.0, 0.0, 0.116)),),
        (0.15, 0.4, 0.15),
        "an upright cylinder of the bottle's radius and height; green (estimate: its glass)",
        "projects/objects/drinks/protos/BeerBottle.proto@6c0f3ebe",
        fields=(_MASS.format(0.4),),
        physics="fields.mass.value",
    ),
    "Carafe": SmallObject(
        "carafe",
        (_cylinder(0.066, 0.176, (0.036, 0.0, 0.088)),),
        (1.0, 1.0, 1.0),
        "an upright cylinder of the carafe's body (its handle left out)",
        "projects/objects/kitchen/utensils/protos/Carafe.proto@b3d1e3be",
        fields=(_MASS.format(1),),
        physics="fields.mass.value",
    ),
    "Plate": SmallObject(
        "plate",
        (
            _cylinder(
                "0.7 * fields.radius.value",
                "0.4 * fields.height.value",
                (0.0, 0.0, "0.2 * fields.height.value"),
            ),
            _cylinder(
                "fields.radius.value",
                "0.6 * fields.height.value",
                (0.0, 0.0, "0.8 * fields.height.value"),
            ),
        ),
        (1.0, 1.0, 1.0),
        "its foot and rim: two cylinders of the given radius and height",
        "projects/objects/kitchen/utensils/protos/Plate.proto@5756c6c5",
        fields=("field SFFloat height 0.01", "field SFFloat radius 0.11", _MASS.format(0.3)),
        physics="fields.mass.value",
    ),
    "Rock": SmallObject(
        "rock",
        (
            _box(
                "fields.type.value === 'flat' ? 0.394 : 0.133",
                "fields.type.value === 'flat' ? 0.258 : 0.111",
                "fields.type.value === 'flat' ? 0.176 : 0.105",
                (
                    "fields.type.value === 'flat' ? 0.023 : -0.0005",
                    "fields.type.value === 'flat' ? 0.001 : 0.0015",
                    "fields.type.value === 'flat' ? 0.088 : -0.0035",
                ),
            ),
        ),
        (0.5, 0.5, 0.5),
        "a box of its mesh's extent (regular or flat) times its scale; grey (estimate)",
        "projects/objects/rocks/protos/Rock.proto@df6f4e11",
        fields=(
            'field SFString type "regular"',
            "field SFFloat scale 1",
            "field SFColor color 1 1 1",
            "field SFNode physics NULL",
            "field SFBool locked FALSE",
        ),
        physics="field",
        scaled=True,
    ),
    "Rock10cm": SmallObject(
        "rock",
        (_box(0.134, 0.112, 0.106, (0.0, 0.0, 0.0)),),
        (0.5, 0.5, 0.5),
        "a box of its mesh's extent; grey (estimate: its texture)",
        "projects/objects/rocks/protos/Rock10cm.proto@7a52dd1f (R2021b, Y-up)",
        lift=0.05,
        fields=(
            "field SFColor color 1 1 1",
            "field SFNode physics NULL",
            "field SFBool locked FALSE",
        ),
        physics="field",
    ),
    "PipeSection": SmallObject(
        "pipe section",
        (_cylinder("fields.radius.value", "fields.height.value", (0, 0, 0)),),
        (0.6, 0.6, 0.6),
        "an upright cylinder of the given radius and height; grey (estimate)",
        "projects/objects/factory/pipes/protos/PipeSection.proto@229efdbc",
        lift=0.25,
        fields=("field SFFloat height 0.5", "field SFFloat radius 0.03"),
    ),
    "TrafficCone": SmallObject(
        "traffic cone",
        (
            _box(0.5, 0.5, 0.015, (-0.01, -0.005, 0.015)),
            _cylinder(0.1, 0.37, (-0.01, -0.005, 0.22)),
        ),
        (0.94, 0.54, 0.11),
        "its square base and its body, times its scale",
        "projects/objects/traffic/protos/TrafficCone.proto@0a183438",
        recognition=((0.94, 0.54, 0.11), (1.0, 1.0, 1.0)),
        fields=("field SFFloat scale 1", "field SFNode physics NULL"),
        physics="field",
        scaled=True,
    ),
    "WoodenPalletStack": SmallObject(
        "wooden pallet stack",
        (
            _box(
                "fields.palletSize.value.x + fields.lateralMisalignment.value",
                "fields.palletSize.value.y + fields.longitudinalMisalignment.value",
                f"fields.palletSize.value.z * {_PALLETS}",
                (0.0, 0.0, f"fields.palletSize.value.z * {_PALLETS} / 2"),
            ),
        ),
        (0.6, 0.45, 0.3),
        "a box of the stack's extent; wood (estimate)",
        "projects/objects/factory/pallet/protos/WoodenPalletStack.proto@846e15b6",
        fields=(
            "field SFInt32 palletNumber 8",
            "field SFVec3f palletSize 1.2 0.8 0.14",
            "field SFFloat lateralMisalignment 0.1",
            "field SFFloat longitudinalMisalignment 0.05",
            "field SFFloat palletMass 0",
        ),
        physics=f"fields.palletMass.value * {_PALLETS}",
    ),
    "FireExtinguisher": SmallObject(
        "fire extinguisher",
        (_cylinder(0.1, 0.66, (0.0, 0.0, 0.33)),),
        (0.7, 0.1, 0.1),
        "an upright cylinder of its body (its hose left out); red (estimate: its texture)",
        "projects/objects/factory/fire_extinguisher/protos/FireExtinguisher.proto@229efdbc",
        fields=("field SFBool enablePhysics TRUE",),
        physics="fields.enablePhysics.value ? 12 : 0",
    ),
    "FifaSoccerBall": SmallObject(
        "fifa soccer ball",
        (Part("sphere", (_FIFA_RADIUS,)),),
        (1.0, 1.0, 1.0),
        "a ball of the radius and mass of its size (1 to 5)",
        "projects/objects/balls/protos/FifaSoccerBall.proto@234898f4",
        lift=0.12,
        recognition=((1.0, 1.0, 1.0), (0.0, 0.0, 0.0)),
        fields=("field SFInt32 size 5",),
        physics=_FIFA_MASS,
    ),
    "Gnome": SmallObject(
        "gnome",
        (_cylinder(0.15, 0.8, (0.0, 0.0, 0.4)),),
        (0.325, 0.353, 0.757),
        "an upright cylinder of the documented size, of its first recognition colour",
        "projects/objects/garden/protos/Gnome.proto@7e9af36d",
        recognition=((0.325, 0.353, 0.757), (0.733, 0.106, 0.106), (0.192, 0.306, 0.22)),
        fields=("field SFBool enablePhysics FALSE",),
        physics="fields.enablePhysics.value ? 1 : 0",
    ),
    "PottedTree": SmallObject(
        "potted tree",
        (_cylinder(0.17, 0.27, (0.0, 0.0, 0.14)),),
        (0.6, 0.35, 0.2),
        "its pot (the trunk and crown pass over the robot); terracotta (estimate)",
        "projects/objects/plants/protos/PottedTree.proto@5756c6c5",
        fields=("field SFNode physics NULL",),
        physics="field",
    ),
    "SimpleBench": SmallObject(
        "simple bench",
        (_box(0.54, 0.1, 0.46, (0.0, 0.59, 0.23)), _box(0.54, 0.1, 0.46, (0.0, -0.59, 0.23))),
        (0.498, 0.447, 0.322),
        "its two legs (the seat passes over the robot)",
        "projects/objects/street_furniture/protos/SimpleBench.proto@5b100835",
        recognition=((0.498, 0.447, 0.322), (0.114, 0.114, 0.114)),
    ),
    "Blackboard": SmallObject(
        "blackboard",
        (
            _box(0.08, 2.63, 1.384, (0.0, 0.0, -0.018)),
            _box(0.163, 2.63, 0.034, (0.125, 0.0, -0.693)),
        ),
        (0.15, 0.2, 0.15),
        "its board and ledge; dark green (estimate: its texture)",
        "projects/objects/school_furniture/protos/Blackboard.proto@7b09dd47",
        lift=0.72,
    ),
    "AdvertisingBoard": SmallObject(
        "advertising board",
        (
            _box(
                "fields.frameThickness.value",
                "fields.displayWidth.value + 0.2",
                _BOARD_HEIGHT,
                (
                    0.0,
                    0.0,
                    f"fields.poleNumber.value > 0 ? fields.poleHeight.value - 0.6 * "
                    f"fields.displayHeight.value - 0.2 : ({_BOARD_HEIGHT}) / 2",
                ),
            ),
        ),
        "frameColor",
        "its board, on the ground without poles (its poles, if any, are left out)",
        "projects/objects/advertising_board/protos/AdvertisingBoard.proto@00178ce2",
        recognition=((1.0, 1.0, 1.0), (0.75, 0.0, 0.0)),
        fields=(
            "field SFFloat displayWidth 4",
            "field SFFloat displayHeight 3",
            "field SFFloat frameThickness 0.6",
            "field SFColor frameColor 0.886 0.886 0.886",
            "field SFInt32 poleNumber 0",
            "field SFFloat poleHeight 5",
        ),
    ),
    "Rabbit": SmallObject(
        "rabbit",
        (_box(0.12, 0.09, 0.05, (0.055, 0.0, 0.025)),),
        (0.827, 0.827, 0.827),
        "its paws, times its scale (its body is above them)",
        "projects/objects/animals/protos/Rabbit.proto@7b09dd47",
        recognition=((0.827, 0.827, 0.827),),
        fields=("field SFFloat scale 1", "field SFColor color 1 1 1"),
        scaled=True,
    ),
    "Dog": SmallObject(
        "dog",
        tuple(_cylinder(0.05, 0.3, (x, y, 0.15)) for x in (0.23, -0.23) for y in (0.08, -0.08)),
        (0.937, 0.921, 0.862),
        "its four legs, times its scale (its body passes over the robot)",
        "projects/objects/animals/protos/Dog.proto@0a183438",
        recognition=((0.937, 0.921, 0.862),),
        fields=("field SFFloat scale 1", "field SFColor color 1 1 1"),
        scaled=True,
    ),
    "Sheep": SmallObject(
        "sheep",
        tuple(_cylinder(0.04, 0.3, (x, y, 0.15)) for x in (0.21, -0.21) for y in (0.07, -0.07)),
        (0.937, 0.921, 0.862),
        "its four legs, times its scale (its body passes over the robot)",
        "projects/objects/animals/protos/Sheep.proto@229efdbc",
        recognition=((0.937, 0.921, 0.862),),
        fields=("field SFFloat scale 1", "field SFColor color 1 1 1"),
        scaled=True,
    ),
}
