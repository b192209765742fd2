"""Stand-ins for the furniture and the window of Webots' apartment (``projects/objects/
living_room_furniture``, ``tables``, ``chairs`` and ``apartment_structure``), used as the other
stand-ins are when the real PROTO cannot be read. Each keeps only what stands in an e-puck's way
(below its 5 cm): a sofa's or an armchair's feet, not the seat the robot drives under; a desk's
and a wooden chair's legs; a window's wall below its sill.

Sources, the collision shapes the PROTOs publish (cyberbotics/webots, ``boundingObject``):
``Sofa`` (R2022b; 1 x 1.8 x 0.8 m): four feet 0.1 m cubes centred at (+-0.35, +-0.75), its body
0.1 m above the floor; ``Armchair`` (R2021c; 1 x 0.8 x 1.1 m): the same feet at (+-0.35, +-0.4);
``Desk`` (R2025b; 0.7 x 1.2 x 0.72 m): four legs, capsules of radius 0.023 m splayed by 0.152
rad, meeting the floor at (+-0.32, +-0.535), under a top 0.7 m up (the guide of the Y-up
releases gives the desk 1.2 m along x: there the legs stand at (+-0.535, +-0.32)); ``WoodenChair``
(R2021a, Y-up; 0.42 x 0.944 x 0.44 m): four legs 0.03 x 0.031 m at x = +-0.178 and z = 0.17 and
-0.185, turned into a Z-up file as Webots' R2022a converter turns a Y-up object (z to -y);
``Window`` (user guide, "Apartment Structure": "a customizable window including walls above and
below", ``size`` 0.8 2.4 0.2 as width, height and thickness in Y-up files, thickness, width and
height in Z-up ones as for ``Wall``, ``bottomWallHeight`` 0.7 m).
"""

from __future__ import annotations

__all__ = ["ARMCHAIR", "DESK", "SOFA", "WINDOW", "WOODEN_CHAIR"]

#: Posts (their horizontal positions) and the size of each, in a file's own axes.
_Posts = tuple[list[tuple[float, float]], tuple[float, float, float]]


def _posts(name: str, label: str, extra_fields: str, z_up: _Posts, y_up: _Posts) -> str:
    """A static stand-in of upright posts (feet or legs) standing on the floor: ``z_up`` for a
    Z-up file (posts at x and y), ``y_up`` for a Y-up one (posts at x and z)."""
    (z_posts, z_size), (y_posts, y_size) = z_up, y_up
    z_children = "\n".join(
        f"          Pose {{ translation {a} {b} {z_size[2] / 2} "
        f"children [ Box {{ size {z_size[0]} {z_size[1]} {z_size[2]} }} ] }}"
        for a, b in z_posts
    )
    y_children = "\n".join(
        f"          Pose {{ translation {a} {y_size[1] / 2} {b} "
        f"children [ Box {{ size {y_size[0]} {y_size[1]} {y_size[2]} }} ] }}"
        for a, b in y_posts
    )
    return f"""#VRML_SIM R2023b utf8
# template language: javascript
PROTO {name} [
  field SFVec3f translation 0 0 0
  field SFRotation rotation 0 0 1 0
  field SFString name "{label}"
{extra_fields}
]
{{
  %< const yUp = context.coordinate_system === 'NUE'; >%
  Solid {{
    translation IS translation
    rotation IS rotation
    name IS name
    boundingObject Group {{
      children [
        %< if (yUp) {{ >%
{y_children}
        %< }} else {{ >%
{z_children}
        %< }} >%
      ]
    }}
  }}
}}
"""


_UPHOLSTERY = """  field SFColor color 1 1 1
  field MFString textureUrl []
  field SFNode physics NULL"""


def _corners(a: float, b: float) -> list[tuple[float, float]]:
    return [(a, b), (-a, b), (a, -b), (-a, -b)]


_FOOT = (0.1, 0.1, 0.1)

#: A sofa's four feet (its seat, 0.1 m up, passes over an e-puck).
SOFA = _posts(
    "Sofa", "sofa", _UPHOLSTERY, (_corners(0.35, 0.75), _FOOT), (_corners(0.35, 0.75), _FOOT)
)
#: An armchair's four feet.
ARMCHAIR = _posts(
    "Armchair", "armchair", _UPHOLSTERY, (_corners(0.35, 0.4), _FOOT), (_corners(0.35, 0.4), _FOOT)
)
#: A desk's four legs where they meet the floor (0.046 m across, as the capsules), the long side
#: along y in a Z-up file, along x in a Y-up one.
DESK = _posts(
    "Desk",
    "desk",
    "  field SFColor color 1 1 1\n  field SFNode physics NULL",
    (_corners(0.32, 0.535), (0.046, 0.046, 0.1)),
    (_corners(0.535, 0.32), (0.046, 0.1, 0.046)),
)
#: A wooden chair's four legs, static (as the other chairs).
WOODEN_CHAIR = _posts(
    "WoodenChair",
    "wooden chair",
    _UPHOLSTERY,
    ([(0.178, -0.17), (-0.178, -0.17), (0.178, 0.185), (-0.178, 0.185)], (0.03, 0.031, 0.463)),
    ([(0.178, 0.17), (-0.178, 0.17), (0.178, -0.185), (-0.178, -0.185)], (0.03, 0.463, 0.031)),
)

WINDOW = """#VRML_SIM R2023b utf8
# template language: javascript
PROTO Window [
  field SFVec3f translation 0 0 0
  field SFRotation rotation 0 0 1 0
  field SFString name "window"
  field SFVec3f size 0.2 0.8 2.4
  field SFFloat windowThickness 0.05
  field SFFloat bottomWallHeight 0.7
  field SFFloat windowHeight 1.4
  field SFVec3f frameSize 0.05 0.05 0.02
  field SFVec2f windowSillSize 0.1 0.05
  field SFNode wallAppearance NULL
  field SFNode frameAppearance NULL
]
{
  %<
    const yUp = context.coordinate_system === 'NUE';
    const s = fields.size.value;
    // Thickness, width across the wall, and the wall below the sill (nothing when 0).
    const thick = yUp ? s.z : s.x;
    const wide = yUp ? s.x : s.y;
    const low = Math.min(fields.bottomWallHeight.value, yUp ? s.y : s.z);
  >%
  Solid {
    translation IS translation
    rotation IS rotation
    name IS name
    %< if (low > 0 && thick > 0 && wide > 0) { >%
      boundingObject Pose {
        %< if (yUp) { >%
          translation 0 %<= low / 2 >% 0
          children [ Box { size %<= wide >% %<= low >% %<= thick >% } ]
        %< } else { >%
          translation 0 0 %<= low / 2 >%
          children [ Box { size %<= thick >% %<= wide >% %<= low >% } ]
        %< } >%
      }
    %< } >%
  }
}
"""
