//! Walls modelled as meshes: a Solid's `boundingObject` that is an `IndexedFaceSet` or a `Mesh`
//! (a Wavefront `.obj` or an STL file beside the world): a maze modelled in Blender or a CAD
//! program and exported whole, or a course's walls given as faces. Webots collides with the
//! triangles themselves; mazesim, which simulates the floor's plane, cuts the mesh at
//! [`WALL_CUT_HEIGHT`] above the floor, where the e-puck's body and its proximity rays meet
//! it, and makes each edge of the cut a thin box wall [`WALL_SKIN`] thick, laid along the
//! inner side of the mesh's surface (the side its faces' normals point away from).

use super::floor_marks::{obj_triangles, vertex, world_point, MAX_MESH_BYTES, MAX_MESH_TRIANGLES};
use super::frames::{Frame, Vec3};
use super::import::Importer;
use super::tree::Node;
use super::Obstacle;

/// Height above the floor (metres) at which a mesh wall is cut: inside the e-puck's body
/// (0 to 5 cm up) and just under its proximity rays (3.3 to 4.4 cm): a wall the rays see
/// and the body meets is cut where both do.
pub const WALL_CUT_HEIGHT: f64 = 0.03;
/// Thickness (metres) of the box wall laid along each edge of a mesh's cut.
pub const WALL_SKIN: f64 = 0.002;
/// An edge of the cut shorter than this (metres) is left out: a sliver of a triangle.
const SHORTEST_EDGE: f64 = 1e-6;

/// One edge of a mesh's cut: its ends seen from above, and the horizontal unit vector pointing
/// out of the mesh there (from the face's normal; zero when the face stands edge-on).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CutEdge {
    pub from: [f64; 2],
    pub to: [f64; 2],
    pub outward: [f64; 2],
}

/// Triangles of an STL file: binary (an 80-byte header, a count, 50 bytes a triangle) or ASCII
/// (`vertex x y z` lines, three a facet); or why not.
pub fn stl_triangles(bytes: &[u8]) -> Result<Vec<[Vec3; 3]>, String> {
    if let Some(count) = binary_stl_count(bytes) {
        if count > MAX_MESH_TRIANGLES {
            return Err(format!(
                "expected a mesh of at most {MAX_MESH_TRIANGLES} triangles, found {count}"
            ));
        }
        let mut triangles = Vec::with_capacity(count);
        for record in bytes[84..].chunks_exact(50) {
            let number = |i: usize| {
                let at = 12 + 4 * i;
                f64::from(f32::from_le_bytes([
                    record[at],
                    record[at + 1],
                    record[at + 2],
                    record[at + 3],
                ]))
            };
            let corner = |k: usize| [number(3 * k), number(3 * k + 1), number(3 * k + 2)];
            let triangle = [corner(0), corner(1), corner(2)];
            if triangle.iter().flatten().any(|c| !c.is_finite()) {
                return Err(format!(
                    "triangle {}: expected finite coordinates",
                    triangles.len() + 1
                ));
            }
            triangles.push(triangle);
        }
        return Ok(triangles);
    }
    let text = std::str::from_utf8(bytes).map_err(|_| {
        "expected a binary STL (84 + 50 bytes a triangle) or ASCII STL text".to_string()
    })?;
    let mut corners: Vec<Vec3> = Vec::new();
    for (number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        if words.next() != Some("vertex") {
            continue;
        }
        let v = vertex(&mut words, number, line)?;
        if corners.len() >= 3 * MAX_MESH_TRIANGLES {
            return Err(format!(
                "line {}: expected a mesh of at most {MAX_MESH_TRIANGLES} triangles, found more",
                number + 1
            ));
        }
        corners.push(v);
    }
    if corners.len() % 3 != 0 {
        return Err(format!(
            "expected three vertices a facet, found {} vertices",
            corners.len()
        ));
    }
    Ok(corners
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect())
}

/// The triangle count of a binary STL whose length matches it exactly.
fn binary_stl_count(bytes: &[u8]) -> Option<usize> {
    let count = u32::from_le_bytes(bytes.get(80..84)?.try_into().ok()?) as usize;
    (count.checked_mul(50)?.checked_add(84)? == bytes.len()).then_some(count)
}

/// The edges where the plane `z = height` cuts the triangles (world frame, z up). A corner
/// exactly at the height counts as above it, so an edge through a vertex is cut once.
pub fn cut_at(triangles: &[[Vec3; 3]], height: f64) -> Vec<CutEdge> {
    let mut edges = Vec::new();
    for t in triangles {
        let mut ends: Vec<[f64; 2]> = Vec::with_capacity(2);
        for k in 0..3 {
            let (p, q) = (t[k], t[(k + 1) % 3]);
            if (p[2] < height) != (q[2] < height) {
                let s = (height - p[2]) / (q[2] - p[2]);
                ends.push([p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1])]);
            }
        }
        let [from, to] = match ends.as_slice() {
            [a, b] => [*a, *b],
            _ => continue,
        };
        if (to[0] - from[0]).hypot(to[1] - from[1]) < SHORTEST_EDGE {
            continue;
        }
        let (u, v) = (sub(t[1], t[0]), sub(t[2], t[0]));
        let normal = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2]];
        let across = normal[0].hypot(normal[1]);
        let outward = if across > 0.0 {
            [normal[0] / across, normal[1] / across]
        } else {
            [0.0, 0.0]
        };
        edges.push(CutEdge { from, to, outward });
    }
    edges
}

fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The thin box wall along one edge of a cut, on the mesh's inner side.
pub fn skin_box(edge: &CutEdge) -> Obstacle {
    let [dx, dy] = [edge.to[0] - edge.from[0], edge.to[1] - edge.from[1]];
    let inward = WALL_SKIN / 2.0;
    Obstacle::Box {
        center: [
            (edge.from[0] + edge.to[0]) / 2.0 - edge.outward[0] * inward,
            (edge.from[1] + edge.to[1]) / 2.0 - edge.outward[1] * inward,
        ],
        size: [dx.hypot(dy), WALL_SKIN],
        yaw: dy.atan2(dx),
    }
}

impl<'d> Importer<'d> {
    /// A mesh bounding object (`IndexedFaceSet` or `Mesh`, `node`, in `frame`): its cut at
    /// [`WALL_CUT_HEIGHT`] as thin box walls, or a warning saying why not.
    pub fn mesh_walls(&mut self, node: &'d Node, frame: &Frame, owner: &str) {
        let triangles = match node.type_name.as_str() {
            "IndexedFaceSet" => self.face_set_triangles(node, frame),
            _ => match self.mesh_file_triangles(node) {
                Ok(local) => local
                    .iter()
                    .map(|t| t.map(|p| world_point(frame, p)))
                    .collect(),
                Err(why) => {
                    return self.warn(format!(
                        "{owner}: a Mesh bounding object: {why}: not imported"
                    ))
                }
            },
        };
        if triangles.len() > MAX_MESH_TRIANGLES {
            return self.warn(format!(
                "{owner}: an {} bounding object of more than {MAX_MESH_TRIANGLES} triangles: not imported",
                node.type_name
            ));
        }
        let edges = cut_at(&triangles, WALL_CUT_HEIGHT);
        if edges.is_empty() {
            let heights = triangles.iter().flatten().map(|p| p[2]);
            let low = heights.clone().fold(f64::INFINITY, f64::min);
            let high = heights.fold(f64::NEG_INFINITY, f64::max);
            let place = if triangles.is_empty() {
                "without faces".to_string()
            } else if high < WALL_CUT_HEIGHT {
                format!("at most {high:.3} m high (a floor or a step under the robot's body)")
            } else {
                format!("from {low:.3} m above the floor (over the robot's body)")
            };
            return self.warn(format!(
                "{owner}: a {} bounding object of {} triangles {place}: no wall where mazesim cuts meshes, {WALL_CUT_HEIGHT} m above the floor",
                node.type_name,
                triangles.len()
            ));
        }
        self.warn(format!(
            "{owner}: a {} bounding object of {} triangles: imported as the {} walls, {} mm thick, of its cut {WALL_CUT_HEIGHT} m above the floor",
            node.type_name,
            triangles.len(),
            edges.len(),
            WALL_SKIN * 1000.0
        ));
        for edge in &edges {
            self.push(skin_box(edge), owner);
        }
    }

    /// The triangles of a `Mesh` node's first url, a `.obj` or `.stl` file beside the world, in
    /// the mesh's own frame.
    fn mesh_file_triangles(&self, node: &'d Node) -> Result<Vec<[Vec3; 3]>, String> {
        let url = self
            .strings(node, "url")
            .first()
            .cloned()
            .unwrap_or_default();
        if url.is_empty() {
            return Err("expected a url, found none".into());
        }
        if url.contains("://") {
            return Err(format!(
                "{url:?}: only files beside the world are read, not URLs"
            ));
        }
        let lower = url.to_ascii_lowercase();
        let is_obj = lower.ends_with(".obj");
        if !is_obj && !lower.ends_with(".stl") {
            return Err(format!(
                "{url:?}: only Wavefront .obj and STL meshes are read"
            ));
        }
        let path = self.world_dir.join(&url);
        let bytes = crate::io::read_limited(&path, MAX_MESH_BYTES, "the mesh")
            .map_err(|e| e.to_string())?;
        let read = if is_obj {
            String::from_utf8(bytes)
                .map_err(|_| "expected UTF-8 text".to_string())
                .and_then(|text| obj_triangles(&text))
        } else {
            stl_triangles(&bytes)
        };
        read.map_err(|why| format!("{}: {why}", path.display()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A closed box from (0, 0, 0) to (1, 0.5, 0.1), its faces wound outward.
    fn block() -> Vec<[Vec3; 3]> {
        let c = |x: f64, y: f64, z: f64| [x, y, z * 0.1];
        let (x, y) = (1.0, 0.5);
        let quad = |a: Vec3, b: Vec3, cc: Vec3, d: Vec3| [[a, b, cc], [a, cc, d]];
        [
            quad(c(0., 0., 0.), c(0., y, 0.), c(x, y, 0.), c(x, 0., 0.)), // bottom, down
            quad(c(0., 0., 1.), c(x, 0., 1.), c(x, y, 1.), c(0., y, 1.)), // top, up
            quad(c(0., 0., 0.), c(x, 0., 0.), c(x, 0., 1.), c(0., 0., 1.)), // y = 0, -y
            quad(c(x, 0., 0.), c(x, y, 0.), c(x, y, 1.), c(x, 0., 1.)),   // x = 1, +x
            quad(c(x, y, 0.), c(0., y, 0.), c(0., y, 1.), c(x, y, 1.)),   // y = 0.5, +y
            quad(c(0., y, 0.), c(0., 0., 0.), c(0., 0., 1.), c(0., y, 1.)), // x = 0, -x
        ]
        .concat()
    }

    #[test]
    fn a_closed_block_cuts_into_its_outline_with_outward_normals() {
        let edges = cut_at(&block(), WALL_CUT_HEIGHT);
        assert_eq!(edges.len(), 8, "two triangles a side face: {edges:?}");
        let length: f64 = edges
            .iter()
            .map(|e| (e.to[0] - e.from[0]).hypot(e.to[1] - e.from[1]))
            .sum();
        assert!((length - 3.0).abs() < 1e-12, "perimeter {length}");
        for e in &edges {
            let mid = [(e.from[0] + e.to[0]) / 2.0, (e.from[1] + e.to[1]) / 2.0];
            let probe = [mid[0] + e.outward[0] * 0.01, mid[1] + e.outward[1] * 0.01];
            let inside = (0.0..=1.0).contains(&probe[0]) && (0.0..=0.5).contains(&probe[1]);
            assert!(!inside, "{e:?} points into the block");
        }
    }

    #[test]
    fn the_skin_lies_inside_the_surface() {
        let edge = CutEdge {
            from: [0.0, 0.0],
            to: [1.0, 0.0],
            outward: [0.0, -1.0],
        };
        match skin_box(&edge) {
            Obstacle::Box { center, size, yaw } => {
                assert!((center[1] - WALL_SKIN / 2.0).abs() < 1e-12);
                assert!((size[0] - 1.0).abs() < 1e-12 && (size[1] - WALL_SKIN).abs() < 1e-12);
                assert!(yaw.abs() < 1e-12);
            }
            other => panic!("expected a box, found {other:?}"),
        }
    }

    #[test]
    fn a_mesh_under_the_cut_gives_no_edge() {
        let low: Vec<[Vec3; 3]> = block()
            .iter()
            .map(|t| t.map(|p| [p[0], p[1], p[2] / 10.0]))
            .collect();
        assert!(cut_at(&low, WALL_CUT_HEIGHT).is_empty());
    }

    fn binary_stl(triangles: &[[Vec3; 3]]) -> Vec<u8> {
        let mut bytes = vec![b' '; 80];
        bytes.extend((triangles.len() as u32).to_le_bytes());
        for t in triangles {
            bytes.extend([0u8; 12]);
            for c in t.iter().flatten() {
                bytes.extend((*c as f32).to_le_bytes());
            }
            bytes.extend([0u8; 2]);
        }
        bytes
    }

    #[test]
    fn binary_and_ascii_stl_read_the_same_triangles() {
        let triangles = [[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.5, 0.25]]];
        // A binary header may begin with "solid" like ASCII text: its length decides.
        let mut binary = binary_stl(&triangles);
        binary[..5].copy_from_slice(b"solid");
        assert_eq!(stl_triangles(&binary).unwrap(), triangles);
        let ascii = "solid t\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 0.5 0.25\n  endloop\n endfacet\nendsolid t\n";
        assert_eq!(stl_triangles(ascii.as_bytes()).unwrap(), triangles);
    }

    #[test]
    fn a_broken_stl_is_refused_with_why() {
        let why = stl_triangles(b"solid t\n vertex 0 0 0\n vertex 1 0\n").unwrap_err();
        assert!(
            why.contains("line 3: expected a vertex of three numbers"),
            "{why}"
        );
        let why = stl_triangles(b"solid t\n vertex 0 0 0\n").unwrap_err();
        assert!(
            why.contains("expected three vertices a facet, found 1"),
            "{why}"
        );
        let why = stl_triangles(&[0xff; 90]).unwrap_err();
        assert!(why.contains("expected a binary STL"), "{why}");
    }
}
