"""mazesim's own PROTOs for stock Webots objects, used when the real file cannot be read (no
Webots installation, no cache, no network): the collision geometry that the Webots user guide
documents for each (its fields and their defaults), written here as procedural PROTOs. Webots'
own PROTO files are licensed for use with Webots only and are not shipped.

Sources: Webots user guide, "Floors" (``CircleArena``: radius 1, wallThickness 0.01, wallHeight
0.1, subdivision 48), "Kitchen" (``CerealBox``: size 0.08 x 0.3 x 0.2 with the height second in
the Y-up versions, mass 1 kg), "Balls" (``SoccerBall``: radius 0.113, mass 0.6 kg; ``Ball``:
radius 0.0325, mass 0.055 kg, ``color`` 1.0 0.54 0.08, the colour a camera sees and the
infra-red sensors read, as a ``PBRAppearance`` of roughness 0.3, metalness 0; the
``SoccerBall``'s black and white texture is not drawn: it is white, as any texture) and
"Obstacles" (``OilBarrel``: height 0.88, radius 0.305, centred on its translation, physics NULL
by default) and "Drinks" (``Can``: 0.03175 m radius, 0.1222 m high, 0.35 kg); the
robotbenchmark "Maze Runner" sample's ``MazeBlock`` (in a Y-up world of R2020a-R2021a its length
lies along the file's x, as the UNSW MTRN4110 course worlds' own map files give their mazes;
its PROTO interface: a wall block 0.015 m
thick, ``length`` long (default 0.1) and 0.065 m high, standing on its translation, of density
200 kg/m^3); "Kitchen" (``Fridge``: 0.7 x 0.7 x 1.8 m, standing on its translation, centred on
it across) and "Tables" (``Table``: ``size`` 1 x 1.8 x 0.74 m since R2022a, 1.8 x 0.74 x 1 with
the height second before; four ``feetSize`` legs, 0.1 x 0.1 m by default, in the corners,
``feetPadding`` in from the edges, under a top ``frameThickness`` thick, 0.05 m by default) and
"Cabinet" (``Cabinet``: a frame ``depth`` deep (0.5 m by default) from its origin forward,
``outerThickness`` (0.03) plus the ``columnsWidths`` (0.4, 0.17, 0.17) wide, centred across,
and ``outerThickness`` plus the ``rowsHeights`` (0.24, 0.2, 0.2, 0.4, 0.4) high on each side,
from the floor up, its doors, drawers and shelves inside that envelope); the ``Chair`` PROTO's
published collision shape (legs 0.06 x 0.06 x 0.4 m centred 0.22 m from its origin on both
horizontal axes, under a seat; kept static: at the default density its 40-odd kg is beyond an
e-puck's push); "Solids" (``SolidTorus``: majorRadius 2, minorRadius 1, subdivision 24, physics
NULL, enableBoundingObject TRUE; physically "a set of N spheres, where N is the subdivision
field", of the minor radius on the circle of the major radius, the ring lying about the up
axis); Webots 6 and 7's ``WoodBox`` (its PROTO of V7.2.5, ``projects/objects/.../WoodBox.proto``
as published copies of Webots 7 hold it: fields translation ``0 0.3 0``, rotation ``0 1 0 0``,
``boxSize`` 0.6 x 0.6 x 0.6, ``color`` 1 1 1, ``textureUrl``, ``locked``; a Solid whose
bounding object is a Box of ``boxSize`` centred on its translation, physics of density 100).
Recognition colours, as Webots' PROTO files write them on their Solid (cyberbotics/webots,
``projects/objects/drinks/protos/Can.proto`` R2022b-R2023a: 0.666667 0 0;
``projects/objects/obstacles/protos/OilBarrel.proto`` R2023a-R2023b: 0.4 0.1 0.1;
``projects/objects/balls/protos/SoccerBall.proto`` R2023a-R2023b: 1 1 1 and 0 0 0); the other
stand-ins' PROTOs write none.
"""

from __future__ import annotations

from dataclasses import dataclass

from .furniture import ARMCHAIR, DESK, SOFA, WINDOW, WOODEN_CHAIR
from .small_objects import SMALL_OBJECTS, stand_in_text

__all__ = ["STAND_INS", "StandIn"]


@dataclass(frozen=True)
class StandIn:
    """A stand-in PROTO: its text and what it models, as the warning says."""

    text: str
    description: str


_CIRCLE_ARENA = """#VRML_SIM R2023b utf8
# template language: javascript
PROTO CircleArena [
  field SFVec3f translation 0 0 0
  field SFRotation rotation 0 0 1 0
  field SFString name "circle arena"
  field SFFloat radius 1.0
  field SFString contactMaterial "default"
  field SFNode floorAppearance NULL
  field SFVec2f floorTileSize 0.5 0.5
  field SFFloat wallThickness 0.01
  field SFFloat wallHeight 0.1
  field SFNode wallAppearance NULL
  field SFInt32 subdivision 48
]
{
  %<
    const yUp = context.coordinate_system === 'NUE';
    const radius = fields.radius.value > 0 ? fields.radius.value : 1.0;
    const thickness = fields.wallThickness.value > 0 ? fields.wallThickness.value : 0.01;
    const height = fields.wallHeight.value > 0 ? fields.wallHeight.value : 0.1;
    const sides = Math.max(8, fields.subdivision.value);
    const centre = radius + thickness / 2;
    const length = 2 * (radius + thickness) * Math.tan(Math.PI / sides);
  >%
  Solid {
    translation IS translation
    rotation IS rotation
    name IS name
    boundingObject Group {
      children [
        %< for (let i = 0; i < sides; ++i) {
             const a = 2 * Math.PI * (i + 0.5) / sides;
             const c = Math.cos(a), s = Math.sin(a); >%
          Pose {
            %< if (yUp) { >%
              translation %<= centre * c >% %<= height / 2 >% %<= -centre * s >%
              rotation 0 1 0 %<= a >%
              children [ Box { size %<= thickness >% %<= height >% %<= length >% } ]
            %< } else { >%
              translation %<= centre * c >% %<= centre * s >% %<= height / 2 >%
              rotation 0 0 1 %<= a >%
              children [ Box { size %<= thickness >% %<= length >% %<= height >% } ]
            %< } >%
          }
        %< } >%
      ]
    }
  }
}
"""

_CEREAL_BOX = """#VRML_SIM R2023b utf8
# template language: javascript
PROTO CerealBox [
  field SFVec3f translation 0 0 0
  field SFRotation rotation 0 0 1 0
  field SFString name "cereal box"
  field SFVec3f size 0.08 0.2 0.3
  field MFString textureUrl []
  field SFFloat mass 1
]
{
  %< const yUp = context.coordinate_system === 'NUE'; const s = fields.size.value; >%
  Solid {
    translation IS translation
    rotation IS rotation
    name IS name
    children [
      Pose {
        translation %< if (yUp) { >% 0 %<= s.y / 2 >% 0 %< } else { >% 0 0 %<= s.z / 2 >% %< } >%
        children [
          Shape { geometry Box { size %<= s.x >% %<= s.y >% %<= s.z >% } }
        ]
      }
    ]
    boundingObject Pose {
      translation %< if (yUp) { >% 0 %<= s.y / 2 >% 0 %< } else { >% 0 0 %<= s.z / 2 >% %< } >%
      children [ Box { size %<= s.x >% %<= s.y >% %<= s.z >% } ]
    }
    physics Physics { density -1 mass IS mass }
  }
}
"""


def _ball(
    name: str,
    label: str,
    radius: float,
    mass: float,
    colour: str | None = None,
    recognition: str = "",
) -> str:
    """A ball PROTO; one of a ``colour`` (Webots' default of its ``color`` field) has a Shape
    of that colour, which a camera sees, and ``color`` changes it; one of ``recognition``
    colours is recognised by a camera's Recognition node."""
    field_colour = colour or "1 1 1"
    recognised = f"\n    recognitionColors [ {recognition} ]" if recognition else ""
    shape = ""
    if colour is not None:
        shape = """
    children [
      Shape {
        appearance PBRAppearance { baseColor IS color roughness 0.3 metalness 0 }
        geometry Sphere { radius IS radius }
      }
    ]"""
    return f"""#VRML_SIM R2023b utf8
PROTO {name} [
  field SFVec3f translation 0 0 {radius}
  field SFRotation rotation 0 0 1 0
  field SFString name "{label}"
  field SFColor color {field_colour}
  field SFFloat radius {radius}
  field SFFloat mass {mass}
  field MFVec3f centerOfMass []
  field SFFloat linearDamping 0.17
  field SFFloat angularDamping 0.33
  field SFString contactMaterial "default"
]
{{
  Solid {{
    translation IS translation
    rotation IS rotation
    name IS name{recognised}{shape}
    boundingObject Sphere {{ radius IS radius }}
    physics Physics {{ density -1 mass IS mass }}
  }}
}}
"""


_CAN = """#VRML_SIM R2023b utf8
PROTO Can [
  field SFVec3f translation 0 0 0.0611
  field SFRotation rotation 0 0 1 0
  field SFString name "can"
  field SFColor color 1 1 1
  field MFString textureUrl []
  field SFFloat mass 0.35
]
{
  Solid {
    translation IS translation
    rotation IS rotation
    name IS name
    recognitionColors [ 0.666667 0 0 ]
    boundingObject Cylinder { height 0.1222 radius 0.03175 }
    physics Physics { density -1 mass IS mass }
  }
}
"""

_OIL_BARREL = """#VRML_SIM R2023b utf8
PROTO OilBarrel [
  field SFVec3f translation 0 0 0.44
  field SFRotation rotation 0 0 1 0
  field SFString name "oil barrel"
  field SFFloat height 0.88
  field SFFloat radius 0.305
  field SFNode physics NULL
  field MFNode immersionProperties []
]
{
  Solid {
    translation IS translation
    rotation IS rotation
    name IS name
    recognitionColors [ 0.4 0.1 0.1 ]
    boundingObject Cylinder { height IS height radius IS radius }
    physics IS physics
  }
}
"""


def _standing_box(across: str, along: str, height: float) -> str:
    """A boundingObject: a box standing on its Solid's origin, ``across`` x ``along`` wide (values
    or template expressions) and ``height`` high, in a Y-up or a Z-up file (the template's
    ``yUp``)."""
    return f"""boundingObject Pose {{
      %< if (yUp) {{ >%
        translation 0 {height / 2} 0
        children [ Box {{ size {across} {height} {along} }} ]
      %< }} else {{ >%
        translation 0 0 {height / 2}
        children [ Box {{ size {across} {along} {height} }} ]
      %< }} >%
    }}"""


_MAZE_BLOCK = """#VRML_SIM R2023b utf8
# template language: javascript
PROTO MazeBlock [
  field SFVec3f translation 0 0 0
  field SFRotation rotation 0 0 1 0
  field SFString name "maze block"
  field SFFloat length 0.1
]
{
  %< const yUp = context.coordinate_system === 'NUE'; const l = fields.length.value; >%
  Solid {
    translation IS translation
    rotation IS rotation
    name IS name
    %< if (yUp) { >%
    boundingObject Pose {
      translation 0 0.0325 0
      children [ Box { size %<= l >% 0.065 0.015 } ]
    }
    %< } else { >%
    BOUNDING_OBJECT
    %< } >%
    physics Physics { density 200 }
  }
}
""".replace("BOUNDING_OBJECT", _standing_box("0.015", "%<= l >%", 0.065))

_WOOD_BOX = """#VRML_SIM R2023b utf8
PROTO WoodBox [
  field SFVec3f translation 0 0.3 0
  field SFRotation rotation 0 1 0 0
  field SFVec3f boxSize 0.6 0.6 0.6
  field SFColor color 1 1 1
  field MFString textureUrl "textures/wood_box.png"
  field SFBool locked FALSE
]
{
  Solid {
    translation IS translation
    rotation IS rotation
    children [
      Shape {
        appearance Appearance { material Material { diffuseColor IS color } }
        geometry Box { size IS boxSize }
      }
    ]
    boundingObject Box { size IS boxSize }
    physics Physics { density 100 }
    locked IS locked
  }
}
"""

_FRIDGE = """#VRML_SIM R2023b utf8
# template language: javascript
PROTO Fridge [
  field SFVec3f translation 0 0 0
  field SFRotation rotation 0 0 1 0
  field SFString name "fridge"
  field SFColor mainColor 1 1 1
]
{
  %< const yUp = context.coordinate_system === 'NUE'; >%
  Solid {
    translation IS translation
    rotation IS rotation
    name IS name
    BOUNDING_OBJECT
  }
}
""".replace("BOUNDING_OBJECT", _standing_box("0.7", "0.7", 1.8))

_TABLE = """#VRML_SIM R2023b utf8
# template language: javascript
PROTO Table [
  field SFVec3f translation 0 0 0
  field SFRotation rotation 0 0 1 0
  field SFString name "table"
  field SFVec3f size 1 1.8 0.74
  field SFVec2f feetSize 0.1 0.1
  field SFFloat feetPadding 0
  field SFFloat frameThickness 0.05
  field SFNode trayAppearance NULL
  field SFNode legAppearance NULL
]
{
  %<
    const yUp = context.coordinate_system === 'NUE';
    const given = fields.size.value;
    const unset = given.x === 1 && given.y === 1.8 && given.z === 0.74;
    // Across, along and up, whichever axis is up in the file.
    const size = yUp
      ? (unset ? {a: 1.8, b: 1, h: 0.74} : {a: given.x, b: given.z, h: given.y})
      : {a: given.x, b: given.y, h: given.z};
    const feet = fields.feetSize.value;
    const pad = fields.feetPadding.value;
    const frame = fields.frameThickness.value > 0 ? fields.frameThickness.value : 0.05;
    const legHeight = size.h - frame;
    const fa = 0.5 * size.a - pad - 0.5 * feet.x;
    const fb = 0.5 * size.b - pad - 0.5 * feet.y;
    const corners = feet.x > 0 && feet.y > 0 ? [[fa, fb], [-fa, fb], [fa, -fb], [-fa, -fb]] : [];
  >%
  Solid {
    translation IS translation
    rotation IS rotation
    name IS name
    boundingObject Group {
      children [
        %< if (yUp) { >%
          Pose {
            translation 0 %<= size.h - 0.5 * frame >% 0
            children [ Box { size %<= size.a >% %<= frame >% %<= size.b >% } ]
          }
          %< for (const [a, b] of corners) { >%
            Pose {
              translation %<= a >% %<= 0.5 * legHeight >% %<= b >%
              children [ Box { size %<= feet.x >% %<= legHeight >% %<= feet.y >% } ]
            }
          %< } >%
        %< } else { >%
          Pose {
            translation 0 0 %<= size.h - 0.5 * frame >%
            children [ Box { size %<= size.a >% %<= size.b >% %<= frame >% } ]
          }
          %< for (const [a, b] of corners) { >%
            Pose {
              translation %<= a >% %<= b >% %<= 0.5 * legHeight >%
              children [ Box { size %<= feet.x >% %<= feet.y >% %<= legHeight >% } ]
            }
          %< } >%
        %< } >%
      ]
    }
  }
}
"""

_CABINET = """#VRML_SIM R2023b utf8
# template language: javascript
PROTO Cabinet [
  field SFVec3f translation 0 0 0
  field SFRotation rotation 0 0 1 0
  field SFString name "cabinet"
  field SFFloat depth 0.5
  field SFFloat innerThickness 0.02
  field SFFloat outerThickness 0.03
  field MFFloat rowsHeights [ 0.24 0.2 0.2 0.4 0.4 ]
  field MFFloat columnsWidths [ 0.4 0.17 0.17 ]
  field MFString layout []
  field SFNode handle NULL
  field SFNode primaryAppearance NULL
  field SFNode secondaryAppearance NULL
]
{
  %<
    const yUp = context.coordinate_system === 'NUE';
    const outer = fields.outerThickness.value > 0 ? fields.outerThickness.value : 0.03;
    const depth = fields.depth.value > 0 ? fields.depth.value : 0.5;
    const sum = (values) => values.reduce((total, value) => total + value, 0);
    const width = 2 * outer + sum(fields.columnsWidths.value);
    const height = 2 * outer + sum(fields.rowsHeights.value);
  >%
  Solid {
    translation IS translation
    rotation IS rotation
    name IS name
    boundingObject Pose {
      %< if (yUp) { >%
        translation %<= depth / 2 >% %<= height / 2 >% 0
        children [ Box { size %<= depth >% %<= height >% %<= width >% } ]
      %< } else { >%
        translation %<= depth / 2 >% 0 %<= height / 2 >%
        children [ Box { size %<= depth >% %<= width >% %<= height >% } ]
      %< } >%
    }
  }
}
"""

_CHAIR = """#VRML_SIM R2023b utf8
# template language: javascript
PROTO Chair [
  field SFVec3f translation 0 0 0
  field SFRotation rotation 0 0 1 0
  field SFString name "chair"
  field SFColor color 1 1 1
  field SFNode physics NULL
]
{
  %< const yUp = context.coordinate_system === 'NUE'; >%
  Solid {
    translation IS translation
    rotation IS rotation
    name IS name
    boundingObject Group {
      children [
        %< for (const [a, b] of [[0.22, 0.22], [-0.22, 0.22], [0.22, -0.22], [-0.22, -0.22]]) { >%
          Pose {
            %< if (yUp) { >%
              translation %<= a >% 0.2 %<= b >%
              children [ Box { size 0.06 0.4 0.06 } ]
            %< } else { >%
              translation %<= a >% %<= b >% 0.2
              children [ Box { size 0.06 0.06 0.4 } ]
            %< } >%
          }
        %< } >%
      ]
    }
  }
}
"""

_SOLID_TORUS = """#VRML_SIM R2023b utf8
# template language: javascript
PROTO SolidTorus [
  field SFVec3f translation 0 0 0
  field SFRotation rotation 0 0 1 0
  field SFString name "torus"
  field SFFloat majorRadius 2
  field SFFloat minorRadius 1
  field SFInt32 subdivision 24
  field SFString contactMaterial "default"
  field SFNode appearance NULL
  field SFNode physics NULL
  field SFBool enableBoundingObject TRUE
  field MFColor recognitionColors []
]
{
  %<
    const yUp = context.coordinate_system === 'NUE';
    const major = fields.majorRadius.value;
    const minor = fields.minorRadius.value > 0 ? fields.minorRadius.value : 1;
    const spheres = Math.max(1, fields.subdivision.value);
  >%
  Solid {
    translation IS translation
    rotation IS rotation
    name IS name
    %< if (fields.enableBoundingObject.value) { >%
    boundingObject Group {
      children [
        %< for (let i = 0; i < spheres; ++i) {
             const a = 2 * Math.PI * i / spheres;
             const c = major * Math.cos(a), s = major * Math.sin(a); >%
          Pose {
            %< if (yUp) { >%
              translation %<= c >% 0 %<= s >%
            %< } else { >%
              translation %<= c >% %<= s >% 0
            %< } >%
            children [ Sphere { radius %<= minor >% } ]
          }
        %< } >%
      ]
    }
    %< } >%
    physics IS physics
  }
}
"""

#: The stand-ins, by PROTO name.
STAND_INS: dict[str, StandIn] = {
    "CircleArena": StandIn(
        _CIRCLE_ARENA,
        "a ring of `subdivision` wall boxes of the documented radius, thickness and height",
    ),
    "CerealBox": StandIn(_CEREAL_BOX, "a box of the documented size and mass"),
    "SoccerBall": StandIn(
        _ball("SoccerBall", "soccer ball", 0.113, 0.6, recognition="1 1 1, 0 0 0"),
        "a ball of the documented radius and mass",
    ),
    "Ball": StandIn(
        _ball("Ball", "ball", 0.0325, 0.055, "1.0 0.54 0.08"),
        "a ball of the documented radius, mass and colour",
    ),
    "OilBarrel": StandIn(_OIL_BARREL, "an upright cylinder of the documented height and radius"),
    "Can": StandIn(_CAN, "an upright cylinder of the documented size and mass"),
    "MazeBlock": StandIn(
        _MAZE_BLOCK, "a wall block 0.015 m thick and 0.065 m high of the given length"
    ),
    "WoodBox": StandIn(
        _WOOD_BOX, "Webots 6 and 7's wood box: a box of the given boxSize, of density 100"
    ),
    "Fridge": StandIn(_FRIDGE, "a box of the documented 0.7 x 0.7 x 1.8 m"),
    "Table": StandIn(_TABLE, "its top and four legs of the given size, feet and padding"),
    "Chair": StandIn(_CHAIR, "its four legs, static"),
    "Cabinet": StandIn(
        _CABINET, "a box of its frame's envelope: depth, rows' heights and columns' widths"
    ),
    "Sofa": StandIn(SOFA, "its four published feet; its seat passes over the robot"),
    "Armchair": StandIn(ARMCHAIR, "its four published feet; its seat passes over the robot"),
    "Desk": StandIn(DESK, "its four published legs where they meet the floor"),
    "WoodenChair": StandIn(WOODEN_CHAIR, "its four published legs, static"),
    "Window": StandIn(WINDOW, "the wall below its sill, of the given size"),
    "SolidTorus": StandIn(
        _SOLID_TORUS,
        "a ring of `subdivision` spheres of the minor radius on the circle of the major radius",
    ),
    # Webots' small stock objects, written as data (small_objects.py).
    **{
        name: StandIn(stand_in_text(name, thing), thing.description)
        for name, thing in SMALL_OBJECTS.items()
    },
}
