"""Walls whose Solid's boundingObject is a mesh (an STL or .obj file beside the world, or an
IndexedFaceSet): a maze modelled in a CAD program is cut 3 cm above the floor into thin walls
along its outline, on the mesh's inner side."""

from __future__ import annotations

import struct
from pathlib import Path
from typing import Any

import pytest

from mazesim.webots import import_wbt

SKIN = 0.002
#: A wall block from (0.2, -0.01) to (0.4, 0.01), 0.1 m high.
LOW, HIGH = (0.2, -0.01, 0.0), (0.4, 0.01, 0.1)

Vec = tuple[float, float, float]


def block_triangles(low: Vec, high: Vec) -> list[tuple[Vec, Vec, Vec]]:
    """The twelve triangles of an axis-aligned block, wound so their normals point out."""
    (x0, y0, z0), (x1, y1, z1) = low, high

    def quad(a: Vec, b: Vec, c: Vec, d: Vec) -> list[tuple[Vec, Vec, Vec]]:
        return [(a, b, c), (a, c, d)]

    return [
        *quad((x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)),
        *quad((x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)),
        *quad((x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)),
        *quad((x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)),
        *quad((x1, y1, z0), (x0, y1, z0), (x0, y1, z1), (x1, y1, z1)),
        *quad((x0, y1, z0), (x0, y0, z0), (x0, y0, z1), (x0, y1, z1)),
    ]


def binary_stl(triangles: list[tuple[Vec, Vec, Vec]]) -> bytes:
    out = b"solid exported by a CAD program".ljust(80) + struct.pack("<I", len(triangles))
    for t in triangles:
        out += struct.pack("<3f", 0.0, 0.0, 0.0)
        out += struct.pack("<9f", *(c for corner in t for c in corner)) + b"\0\0"
    return out


def world_text(bounding: str, solid_rotation: str = "0 0 1 0") -> str:
    return f"""#VRML_SIM R2023b utf8
EXTERNPROTO "https://raw.githubusercontent.com/cyberbotics/webots/R2023b/projects/robots/gctronic/e-puck/protos/E-puck.proto"
WorldInfo {{
}}
Solid {{
  rotation {solid_rotation}
  children [
    Shape {{
      geometry DEF WALL_GEO {bounding}
    }}
  ]
  name "maze"
  boundingObject USE WALL_GEO
}}
E-puck {{
  controller "<none>"
}}
"""


def import_world(tmp_path: Path, text: str) -> tuple[Any, Any]:
    path = tmp_path / "worlds" / "maze.wbt"
    path.parent.mkdir(exist_ok=True)
    path.write_text(text)
    return import_wbt(path)


def assert_block_outline(report: Any) -> None:
    boxes = [o for o in report["obstacles"] if o["kind"] == "box"]
    assert len(boxes) == 8, report["obstacles"]
    (x0, y0, _), (x1, y1, _) = LOW, HIGH
    for box in boxes:
        cx, cy = box["center"]
        assert x0 < cx < x1 and y0 < cy < y1, f"{box} lies outside the wall"
        assert box["size"][1] == pytest.approx(SKIN)
    perimeter = sum(box["size"][0] for box in boxes)
    assert perimeter == pytest.approx(2 * ((x1 - x0) + (y1 - y0)))
    assert any("imported as the 8 walls" in w for w in report["warnings"]), report["warnings"]


def test_an_stl_mesh_bounding_object_is_cut_into_walls(tmp_path: Path) -> None:
    (tmp_path / "worlds").mkdir()
    (tmp_path / "wall.stl").write_bytes(binary_stl(block_triangles(LOW, HIGH)))
    world, report = import_world(tmp_path, world_text('Mesh { url [ "../wall.stl" ] }'))
    assert_block_outline(report)
    assert len(world.wall_boxes()) == 8


def test_a_y_up_stl_turned_upright_by_its_solid_is_cut_in_the_world_frame(
    tmp_path: Path,
) -> None:
    # CAD programs export Y-up: the Solid turns it by +90 degrees about x (y -> z, z -> -y).
    y_up = [tuple((x, z, -y) for x, y, z in t) for t in block_triangles(LOW, HIGH)]
    (tmp_path / "worlds").mkdir()
    (tmp_path / "wall.stl").write_bytes(binary_stl(y_up))  # type: ignore[arg-type]
    _, report = import_world(
        tmp_path, world_text('Mesh { url [ "../wall.stl" ] }', "1 0 0 1.5707963")
    )
    assert_block_outline(report)


def test_an_indexed_face_set_bounding_object_is_cut_into_walls(tmp_path: Path) -> None:
    corners: list[Vec] = []
    indices: list[int] = []
    for t in block_triangles(LOW, HIGH):
        for corner in t:
            indices.append(len(corners))
            corners.append(corner)
        indices.append(-1)
    points = ", ".join(" ".join(str(c) for c in p) for p in corners)
    index = ", ".join(map(str, indices))
    face_set = (
        f"IndexedFaceSet {{ coord Coordinate {{ point [ {points} ] }} coordIndex [ {index} ] }}"
    )
    _, report = import_world(tmp_path, world_text(face_set))
    assert_block_outline(report)


def test_a_flat_mesh_on_the_floor_is_no_wall_and_says_so(tmp_path: Path) -> None:
    flat = (
        "IndexedFaceSet { coord Coordinate { point [ -1 -1 0, 1 -1 0, 1 1 0, -1 1 0 ] }"
        " coordIndex [ 0, 1, 2, 3, -1 ] }"
    )
    _, report = import_world(tmp_path, world_text(flat))
    assert report["obstacles"] == []
    assert any("at most 0.000 m high" in w for w in report["warnings"]), report["warnings"]


def test_a_mesh_file_that_cannot_be_read_is_named_in_a_warning(tmp_path: Path) -> None:
    _, report = import_world(tmp_path, world_text('Mesh { url [ "../missing.stl" ] }'))
    assert report["obstacles"] == []
    assert any(
        "a Mesh bounding object" in w and "missing.stl" in w and "not imported" in w
        for w in report["warnings"]
    ), report["warnings"]
    (tmp_path / "maze.dae").write_text("<COLLADA/>")
    _, report = import_world(tmp_path, world_text('Mesh { url [ "../maze.dae" ] }'))
    assert any("only Wavefront .obj and STL meshes are read" in w for w in report["warnings"])
