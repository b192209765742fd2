//! Visual-only shapes: a `Shape` that belongs to no `Solid` with a `boundingObject` collides
//! with nothing in Webots, but its infra-red distance sensors still see it (the reference
//! manual's DistanceSensor page: "infra-red rays collision detection uses the Solid nodes
//! themselves"; the sensor picks the colour of the first shape its ray meets: see
//! `appearance.rs` for its reflection factor). A line drawn on the floor as a thin `Box`, `Cylinder`, `IndexedFaceSet` or
//! `Mesh` (a Wavefront `.obj` file) is such a shape.
//!
//! Shapes whose top is below [`FLOOR_MARK_HEIGHT`] (the proximity rays' lowest point) become
//! floor paint of their colour's reflection factor, as seen from above (higher shapes over
//! lower ones, later over earlier where level), seen by the ground sensors and the camera; the
//! robot drives through them as in Webots. A mesh's triangles are read from its `.obj` file and painted cell by cell.
//! Primitives in the proximity sensors' rays are sensed-only obstacles (`sensed.rs`). Every other visual-only shape is named in a warning
//! (nothing of the world is lost without a word).

use super::floor_texture::equal_rects;
use super::frames::{tilt, Frame, Vec3};
use super::import::{Importer, TILT_TOLERANCE};
use super::sensed::PROXIMITY_RAYS_LOW;
use super::shapes::snap;
use super::tree::Node;
use super::WbtImport;
use crate::world::spec::PaintSpec;
use crate::world::values::{self, Finite, Positive, Reflectance};

/// A visual-only shape whose top is below this height (metres) is a mark on the floor, seen from
/// above: a line painted on it, a track modelled as a sheet a few millimetres above it (one
/// public course raises its track 7.5 mm), or a road slab 1.6 cm thick with lane marks on it
/// (one public lane follower's). The e-puck's proximity rays, 3.3 cm up at their lowest
/// (`sensed.rs`), pass over it; its ground sensors and a camera tilted at the floor see it.
pub const FLOOR_MARK_HEIGHT: f64 = PROXIMITY_RAYS_LOW;
/// Tolerance below the floor (metres) for the bottom of a floor mark.
const BELOW_FLOOR: f64 = 0.001;
/// Side of the cells a floor mesh is painted in (metres), at the finest.
pub const MARK_CELL: f64 = 0.002;
/// Most cells along one side of a mesh's painted area; a larger mesh gets larger cells.
const MAX_MARK_CELLS: usize = 1024;
/// Largest `.obj` file read, bytes.
pub const MAX_MESH_BYTES: u64 = 32 << 20;
/// Most triangles of one mesh (a `.obj` file, or an `IndexedFaceSet`'s faces once fanned): a
/// face of n corners is n - 2 triangles, so a short line could otherwise ask for millions.
pub const MAX_MESH_TRIANGLES: usize = 1 << 20;
/// Most cell tests painting one mesh may make (each triangle tests the cells of its bounding
/// box on the mark grid): a million large triangles would otherwise take hours.
const MAX_MARK_TESTS: usize = 1 << 26;

/// A `Mesh` of a visual-only shape, read after the walk (see [`WbtImport::paint_floor_meshes`]).
#[derive(Debug, Clone, PartialEq)]
pub struct FloorMesh {
    /// The `url` entries of the `Mesh`, in order.
    pub urls: Vec<String>,
    /// `line L: Mesh` for messages.
    pub owner: String,
    /// The shape's Z-up frame in the world.
    pub frame: Frame,
    /// The reflection factor of its colour.
    pub reflectance: f64,
    /// Its colour as a camera sees it (see `appearance.rs`).
    pub colour: Option<[f64; 3]>,
}

/// The three finite numbers `words` go on with: a vertex of a mesh file's line `line`, the
/// `number`th from 0; or why not.
pub(super) fn vertex(
    words: &mut std::str::SplitWhitespace<'_>,
    number: usize,
    line: &str,
) -> Result<Vec3, String> {
    let mut v = [0.0; 3];
    for c in &mut v {
        *c = words
            .next()
            .and_then(|w| w.parse::<f64>().ok())
            .filter(|x| x.is_finite())
            .ok_or_else(|| {
                format!(
                    "line {}: expected a vertex of three numbers, found {line:?}",
                    number + 1
                )
            })?;
    }
    Ok(v)
}

/// Triangles of a Wavefront `.obj` text (`v` and `f` lines; polygons fanned into triangles,
/// negative indices counted from the end), or why not, with the line.
pub fn obj_triangles(text: &str) -> Result<Vec<[Vec3; 3]>, String> {
    let mut vertices: Vec<Vec3> = Vec::new();
    let mut triangles = Vec::new();
    for (number, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => vertices.push(vertex(&mut words, number, line)?),
            Some("f") => {
                let mut corners = Vec::new();
                for word in words {
                    let index = word.split('/').next().unwrap_or("");
                    let resolved = index.parse::<i64>().ok().and_then(|i| match i {
                        i if i > 0 => usize::try_from(i - 1).ok(),
                        i if i < 0 => vertices.len().checked_sub(i.unsigned_abs() as usize),
                        _ => None,
                    });
                    match resolved.and_then(|i| vertices.get(i)) {
                        Some(v) => corners.push(*v),
                        None => {
                            return Err(format!(
                                "line {}: expected a vertex index from 1 to {}, found {word:?}",
                                number + 1,
                                vertices.len()
                            ))
                        }
                    }
                }
                if triangles.len() + corners.len().saturating_sub(2) > MAX_MESH_TRIANGLES {
                    return Err(format!(
                        "line {}: expected a mesh of at most {MAX_MESH_TRIANGLES} triangles, found more",
                        number + 1
                    ));
                }
                for k in 2..corners.len() {
                    triangles.push([corners[0], corners[k - 1], corners[k]]);
                }
            }
            _ => {}
        }
    }
    Ok(triangles)
}

/// Paint covering the cells whose centres fall inside the triangles seen from above
/// (world frame, z up), at `reflectance`: rows of covered cells joined into rectangles; or why
/// not, when the mesh has more than [`MAX_MESH_TRIANGLES`] triangles or would take more than
/// [`MAX_MARK_TESTS`] cell tests.
pub fn triangles_paint(
    triangles: &[[Vec3; 3]],
    reflectance: f64,
    colour: Option<[f64; 3]>,
) -> Result<Vec<PaintSpec>, String> {
    if triangles.len() > MAX_MESH_TRIANGLES {
        return Err(format!(
            "with more than {MAX_MESH_TRIANGLES} triangles ({} found)",
            triangles.len()
        ));
    }
    let points = triangles.iter().flatten();
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for i in 0..2 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    if !(lo[0] < hi[0] && lo[1] < hi[1]) {
        return Ok(Vec::new());
    }
    let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    let cell = MARK_CELL.max(extent / MAX_MARK_CELLS as f64);
    let width = ((hi[0] - lo[0]) / cell).ceil() as usize + 1;
    let height = ((hi[1] - lo[1]) / cell).ceil() as usize + 1;
    let mut covered = vec![false; width * height];
    let centre = |i: usize, lo: f64| lo + (i as f64 + 0.5) * cell;
    let span = |a: f64, b: f64, c: f64| ((a.max(b).max(c) - a.min(b).min(c)) / cell) as usize + 2;
    let tests = triangles.iter().fold(0usize, |total, t| {
        let cells = span(t[0][0], t[1][0], t[2][0]).saturating_mul(span(t[0][1], t[1][1], t[2][1]));
        total.saturating_add(cells)
    });
    if tests > MAX_MARK_TESTS {
        return Err(format!(
            "too detailed to paint (its triangles cover {tests} cells of {cell:.4} m, at most {MAX_MARK_TESTS})"
        ));
    }
    for t in triangles {
        let [a, b, c] = t.map(|p| [p[0], p[1]]);
        let cross = |o: [f64; 2], p: [f64; 2], q: [f64; 2]| {
            (p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0])
        };
        let area = cross(a, b, c);
        if area.abs() < 1e-18 {
            continue;
        }
        let index =
            |v: f64, lo: f64, n: usize| (((v - lo) / cell).floor().max(0.0) as usize).min(n - 1);
        let (c0, c1) = (
            index(a[0].min(b[0]).min(c[0]), lo[0], width),
            index(a[0].max(b[0]).max(c[0]), lo[0], width),
        );
        let (r0, r1) = (
            index(a[1].min(b[1]).min(c[1]), lo[1], height),
            index(a[1].max(b[1]).max(c[1]), lo[1], height),
        );
        for r in r0..=r1 {
            for col in c0..=c1 {
                let p = [centre(col, lo[0]), centre(r, lo[1])];
                let s = area.signum();
                let inside = s * cross(a, b, p) >= 0.0
                    && s * cross(b, c, p) >= 0.0
                    && s * cross(c, a, p) >= 0.0;
                if inside {
                    covered[r * width + col] = true;
                }
            }
        }
    }
    Ok(equal_rects(&covered, width, height)
        .into_iter()
        .filter(|&(_, inside)| inside)
        .map(|([c0, c1, r0, r1], _)| PaintSpec::Rect {
            center: [
                Finite(snap(lo[0] + (c0 + c1) as f64 * cell / 2.0)),
                Finite(snap(lo[1] + (r0 + r1) as f64 * cell / 2.0)),
            ],
            size: [
                Positive((c1 - c0) as f64 * cell),
                Positive((r1 - r0) as f64 * cell),
            ],
            yaw: Finite(0.0),
            reflectance: Reflectance(reflectance),
            colour: colour.map(values::colour),
        })
        .collect())
}

impl<'d> Importer<'d> {
    /// Warns that a visual-only shape is not imported.
    fn drop_visual(&mut self, shape: &'d Node, geometry: &'d Node, why: &str) {
        let label = self.label(shape);
        self.warn(format!(
            "{label}: a {} shape outside any Solid with a boundingObject (nothing collides with it in Webots, but its infra-red sensors see it) {why}: not imported",
            geometry.type_name
        ));
    }

    /// A visual-only primitive above the floor: a sensed-only obstacle when it stands in the
    /// proximity rays' way (`sensed.rs`), otherwise named in a warning.
    fn sensed_or_dropped(&mut self, shape: &'d Node, geometry: &'d Node, parent: &Frame) {
        if !self.sensed_shape(shape, parent) {
            self.drop_visual(
                shape,
                geometry,
                "above the floor, out of the proximity sensors' rays (3.3 to 4.4 cm up)",
            );
        }
    }

    /// A `Shape` of the scene that no `Solid` with a `boundingObject` owns (`frame` is its
    /// parent's): a floor texture, a floor mark, or a warning.
    pub fn visual_shape(&mut self, node: &'d Node, frame: &Frame) {
        let Some(&geometry) = self.nodes(node, "geometry").first() else {
            return; // a Shape without geometry draws nothing
        };
        let geometry = self.node(geometry);
        let parent = *frame;
        // Primitives are defined Z-up (turned in Y-up files); points are taken as written.
        let frame = self.z_up(frame);
        let reflectance = self.shape_reflectance(node);
        let colour = self.field_colour(node, "appearance");
        match geometry.type_name.as_str() {
            "Plane" => {
                if self.has_texture(node) {
                    self.textured_shape(node, &parent);
                } else {
                    self.plain_plane(node, geometry, &frame, reflectance, colour);
                }
            }
            "Box" => {
                let mut size = self.vector(geometry, "size", [2.0; 3]);
                if self.y_up {
                    size = super::frames::y_up_size(size);
                }
                let half = [0, 1, 2].map(|i| frame.axis(i).map(|c| c * size[i] / 2.0));
                let top = frame.origin[2] + half.iter().map(|a| a[2].abs()).sum::<f64>();
                if under_floor(top) {
                    return self.drop_visual(node, geometry, UNDER_FLOOR);
                }
                // Whichever of its axes stands up (a box turned a quarter turn about x, as a
                // world of coordinateSystem "NUE" writes one, stands on its y axis); the other
                // two span the mark.
                let up = (0..3)
                    .min_by(|&i, &j| tilt(frame.axis(i)).total_cmp(&tilt(frame.axis(j))))
                    .unwrap_or(2);
                if !on_floor(top) || tilt(frame.axis(up)) > TILT_TOLERANCE {
                    return self.sensed_or_dropped(node, geometry, &parent);
                }
                let [along, across] = match up {
                    0 => [half[1], half[2]],
                    1 => [half[2], half[0]],
                    _ => [half[0], half[1]],
                };
                let width = along[0].hypot(along[1]) * 2.0;
                let depth = across[0].hypot(across[1]) * 2.0;
                self.mark(
                    PaintSpec::Rect {
                        center: [Finite(snap(frame.origin[0])), Finite(snap(frame.origin[1]))],
                        size: [Positive(width), Positive(depth)],
                        yaw: Finite(snap(along[1].atan2(along[0]))),
                        reflectance: Reflectance(reflectance),
                        colour: colour.map(values::colour),
                    },
                    top,
                );
            }
            "Cylinder" => {
                let radius = self.number(geometry, "radius", 1.0);
                let height = self.number(geometry, "height", 2.0);
                let axis = frame.axis(2);
                let top = frame.origin[2] + (axis[2] * height / 2.0).abs();
                let scale = frame.axis(0)[0].hypot(frame.axis(0)[1]);
                if under_floor(top) {
                    return self.drop_visual(node, geometry, UNDER_FLOOR);
                }
                if !on_floor(top) || tilt(axis) > TILT_TOLERANCE {
                    return self.sensed_or_dropped(node, geometry, &parent);
                }
                self.mark(
                    PaintSpec::Circle {
                        center: [Finite(snap(frame.origin[0])), Finite(snap(frame.origin[1]))],
                        radius: Positive(radius * scale),
                        reflectance: Reflectance(reflectance),
                        colour: colour.map(values::colour),
                    },
                    top,
                );
            }
            "IndexedFaceSet" => {
                if self.has_texture(node) && self.textured_face_set(node, geometry, &parent) {
                    return;
                }
                let triangles = self.face_set_triangles(geometry, &parent);
                self.mark_triangles(node, geometry, &triangles, reflectance, colour);
            }
            "Mesh" => {
                let label = self.label(geometry);
                let urls = self.strings(geometry, "url").to_vec();
                self.floor_meshes.push(FloorMesh {
                    urls,
                    owner: label,
                    frame: parent,
                    reflectance,
                    colour,
                });
            }
            "Sphere" | "Capsule" => self.sensed_or_dropped(node, geometry, &parent),
            _ => self.drop_visual(
                node,
                geometry,
                "(only Plane, Box, Cylinder, IndexedFaceSet and Mesh marks on the floor are read)",
            ),
        }
    }

    /// Whether a Shape's appearance holds an `ImageTexture` (a `PBRAppearance`'s `baseColorMap`,
    /// an `Appearance`'s `texture`).
    fn has_texture(&self, shape: &'d Node) -> bool {
        self.nodes(shape, "appearance").iter().any(|&a| {
            let appearance = self.node(a);
            ["baseColorMap", "texture"]
                .iter()
                .flat_map(|field| self.nodes(appearance, field))
                .any(|&t| self.node(t).type_name == "ImageTexture")
        })
    }

    /// Records the paint of a mark whose top is `top` metres up (see [`Importer::marks_from_below`]).
    fn mark(&mut self, paint: PaintSpec, top: f64) {
        let valid = match &paint {
            PaintSpec::Rect { size, .. } => size.iter().all(|s| s.0 > 0.0 && s.0.is_finite()),
            PaintSpec::Circle { radius, .. } => radius.0 > 0.0 && radius.0.is_finite(),
            PaintSpec::Polyline { .. } => true,
        };
        if valid {
            self.floor_marks.push(paint);
            self.floor_mark_owners.push(self.owners());
            self.floor_mark_tops.push(top);
        }
    }

    /// Paints `triangles` (world frame) when they lie on the floor; warns otherwise.
    pub fn mark_triangles(
        &mut self,
        shape: &'d Node,
        geometry: &'d Node,
        triangles: &[[Vec3; 3]],
        reflectance: f64,
        colour: Option<[f64; 3]>,
    ) {
        let high = triangles
            .iter()
            .flatten()
            .fold(f64::NEG_INFINITY, |h, p| h.max(p[2]));
        if triangles.is_empty() {
            return self.drop_visual(shape, geometry, "without faces");
        }
        if under_floor(high) {
            return self.drop_visual(shape, geometry, UNDER_FLOOR);
        }
        if !on_floor(high) {
            let why = format!("reaching {high:.3} m above the floor");
            return self.drop_visual(shape, geometry, &why);
        }
        match triangles_paint(triangles, reflectance, colour) {
            Ok(paint) => {
                let owners = self.owners();
                self.floor_mark_owners
                    .extend(std::iter::repeat_n(owners, paint.len()));
                self.floor_mark_tops
                    .extend(std::iter::repeat_n(high, paint.len()));
                self.floor_marks.extend(paint);
            }
            Err(why) => self.drop_visual(shape, geometry, &why),
        }
    }

    /// The triangles of an `IndexedFaceSet` (its `Coordinate.point` and `coordIndex`, faces
    /// ended by -1 and fanned), in the world frame `frame`.
    pub(super) fn face_set_triangles(
        &mut self,
        geometry: &'d Node,
        frame: &Frame,
    ) -> Vec<[Vec3; 3]> {
        let Some(&coord) = self.nodes(geometry, "coord").first() else {
            return Vec::new();
        };
        let points: Vec<Vec3> = self
            .numbers(self.node(coord), "point")
            .unwrap_or(&[])
            .chunks_exact(3)
            .map(|p| world_point(frame, [p[0], p[1], p[2]]))
            .collect();
        let indices = self.numbers(geometry, "coordIndex").unwrap_or(&[]);
        let mut triangles = Vec::new();
        for face in indices.split(|&i| i < 0.0) {
            let corners: Vec<Vec3> = face
                .iter()
                .filter_map(|&i| points.get(i as usize).copied())
                .collect();
            if triangles.len() + corners.len().saturating_sub(2) > MAX_MESH_TRIANGLES {
                triangles.push(triangles.first().copied().unwrap_or([corners[0]; 3]));
                break; // one more than the bound: refused by `triangles_paint`, with a warning
            }
            for k in 2..corners.len() {
                triangles.push([corners[0], corners[k - 1], corners[k]]);
            }
        }
        triangles
    }

    /// A horizontal `Plane` at floor level without a texture: paint of its colour (white paints
    /// nothing: the floor is white already).
    fn plain_plane(
        &mut self,
        shape: &'d Node,
        geometry: &'d Node,
        frame: &Frame,
        reflectance: f64,
        colour: Option<[f64; 3]>,
    ) {
        if tilt(frame.axis(2)) > TILT_TOLERANCE || frame.origin[2].abs() > FLOOR_MARK_HEIGHT {
            return self.drop_visual(shape, geometry, "not lying on the floor");
        }
        if reflectance >= 1.0 && colour.is_none_or(|c| c == [1.0; 3]) {
            return;
        }
        let mut size = self.vector(geometry, "size", [1.0, 1.0]);
        if self.y_up {
            size = [size[1], size[0]];
        }
        self.mark_rectangle(frame, size, reflectance, colour);
    }

    /// Paints the rectangle `size` along `frame`'s x and y (scaled as the frame scales them),
    /// centred on its origin, in a reflection factor and a colour.
    pub(super) fn mark_rectangle(
        &mut self,
        frame: &Frame,
        size: [f64; 2],
        reflectance: f64,
        colour: Option<[f64; 3]>,
    ) {
        let (x, y) = (frame.axis(0), frame.axis(1));
        self.mark(
            PaintSpec::Rect {
                center: [Finite(snap(frame.origin[0])), Finite(snap(frame.origin[1]))],
                size: [
                    Positive(size[0] * x[0].hypot(x[1])),
                    Positive(size[1] * y[0].hypot(y[1])),
                ],
                yaw: Finite(snap(x[1].atan2(x[0]))),
                reflectance: Reflectance(reflectance),
                colour: colour.map(values::colour),
            },
            frame.origin[2],
        );
    }

    /// The floor marks in the order they are painted: the lower under the higher (seen from
    /// above, a line 0.5 mm up lies on a floor slab whose top is at 0 whichever the world
    /// writes first), and in the world's order where their tops are level; with the lines of
    /// the nodes that hold each.
    pub(super) fn marks_from_below(&mut self) -> (Vec<PaintSpec>, Vec<Vec<usize>>) {
        let mut marks: Vec<(f64, PaintSpec, Vec<usize>)> =
            std::mem::take(&mut self.floor_mark_tops)
                .into_iter()
                .zip(std::mem::take(&mut self.floor_marks))
                .zip(std::mem::take(&mut self.floor_mark_owners))
                .map(|((top, paint), owners)| (top, paint, owners))
                .collect();
        marks.sort_by(|a, b| a.0.total_cmp(&b.0)); // stable: level marks keep the world's order
        marks
            .into_iter()
            .map(|(_, paint, owners)| (paint, owners))
            .unzip()
    }
}

/// Whether a shape whose top is at `top` (metres) is a mark on the floor.
fn on_floor(top: f64) -> bool {
    (-BELOW_FLOOR..FLOOR_MARK_HEIGHT).contains(&top)
}

/// Why a shape [`under_floor`] is not imported.
const UNDER_FLOOR: &str =
    "under the floor (inside a slab the floor is made of, or buried), where nothing above the floor sees it";

/// Whether a shape whose top is at `top` (metres) lies under the floor: nothing above the floor
/// sees it (a supervisor that raises it later finds no mark; the warning says so).
fn under_floor(top: f64) -> bool {
    top < -BELOW_FLOOR
}

/// A point of a shape's local frame in the world.
pub(super) fn world_point(frame: &Frame, p: Vec3) -> Vec3 {
    let v = frame.vector(p);
    [0, 1, 2].map(|i| v[i] + frame.origin[i])
}

impl WbtImport {
    /// Reads the `.obj` files of the visual-only meshes (urls relative to `dir`) and paints
    /// those lying on the floor; each mesh that cannot be read or does not lie on the floor
    /// gets a warning.
    pub(super) fn paint_floor_meshes(&mut self, dir: &std::path::Path) {
        for mesh in std::mem::take(&mut self.floor_meshes) {
            let url = mesh.urls.first().cloned().unwrap_or_default();
            let owner = &mesh.owner;
            if url.contains("://") {
                self.warnings.push(format!(
                    "{owner}: mesh {url:?}: only files beside the world are read, not URLs: not imported"
                ));
                continue;
            }
            if !url.to_ascii_lowercase().ends_with(".obj") {
                self.warnings.push(format!(
                    "{owner}: mesh {url:?}: only Wavefront .obj meshes are read: not imported"
                ));
                continue;
            }
            let path = dir.join(&url);
            let text = crate::io::read_limited(&path, MAX_MESH_BYTES, "the mesh")
                .map_err(|e| e.to_string())
                .and_then(|bytes| {
                    String::from_utf8(bytes).map_err(|_| "expected UTF-8 text".to_string())
                })
                .and_then(|text| obj_triangles(&text));
            let triangles = match text {
                Ok(t) => t,
                Err(why) => {
                    self.warnings.push(format!(
                        "{owner}: mesh {}: {why}: not imported",
                        path.display()
                    ));
                    continue;
                }
            };
            let world: Vec<[Vec3; 3]> = triangles
                .iter()
                .map(|t| t.map(|p| world_point(&mesh.frame, p)))
                .collect();
            let high = world
                .iter()
                .flatten()
                .fold(f64::NEG_INFINITY, |h, p| h.max(p[2]));
            if world.is_empty() || !on_floor(high) {
                self.warnings.push(format!(
                    "{owner}: mesh {url:?} outside any Solid with a boundingObject (nothing collides with it in Webots, but its infra-red sensors see it) reaching {high:.3} m above the floor: not imported"
                ));
                continue;
            }
            match triangles_paint(&world, mesh.reflectance, mesh.colour) {
                Ok(paint) => {
                    // A mesh read after the walk: held by no node a supervisor moves.
                    self.paint_owners
                        .resize(self.paint.len() + paint.len(), Vec::new());
                    self.paint.extend(paint);
                }
                Err(why) => self.warnings.push(format!(
                    "{owner}: mesh {}: {why}: not imported",
                    path.display()
                )),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mesh_that_fans_into_too_many_triangles_or_cell_tests_is_refused() {
        // One face of MAX_MESH_TRIANGLES + 5 corners: MAX_MESH_TRIANGLES + 3 triangles.
        let face: String = " 1 2 3".repeat(MAX_MESH_TRIANGLES / 3 + 2);
        let text = format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nf{face}\n");
        let refused = obj_triangles(&text).expect_err("a refusal");
        assert!(refused.contains("at most 1048576 triangles"), "{refused}");
        let large = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let refused = triangles_paint(&[large; 2000], 0.2, None).unwrap_err();
        assert!(refused.contains("too detailed"), "{refused}");
        assert!(triangles_paint(&[large; 20], 0.2, None).is_ok());
    }

    #[test]
    fn obj_faces_fan_into_triangles_with_relative_indices() {
        let text = "# a square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1 -1\n";
        let triangles = obj_triangles(text).unwrap();
        assert_eq!(triangles.len(), 2);
        assert_eq!(triangles[1][2], [0.0, 1.0, 0.0]);
        let bad = obj_triangles("v 0 0 0\nf 1 2 3\n").unwrap_err();
        assert!(
            bad.contains("line 2") && bad.contains("from 1 to 1"),
            "{bad}"
        );
        assert!(obj_triangles("v 0 x 0\n").unwrap_err().contains("line 1"));
    }

    #[test]
    fn a_painted_triangle_covers_its_half_of_the_square() {
        let t = [[0.0, 0.0, 0.0], [0.1, 0.0, 0.0], [0.0, 0.1, 0.0]];
        let paint = triangles_paint(&[t], 0.2, None).unwrap();
        let area: f64 = paint
            .iter()
            .map(|p| match p {
                PaintSpec::Rect { size, .. } => size[0].0 * size[1].0,
                _ => 0.0,
            })
            .sum();
        // Half of 0.01 m^2, to the cells along the 0.14 m hypotenuse.
        assert!((area - 0.005).abs() < 0.15 * MARK_CELL, "{area}");
        let inside = |x: f64, y: f64| {
            paint.iter().any(|p| match p {
                PaintSpec::Rect { center, size, .. } => {
                    (x - center[0].0).abs() < size[0].0 / 2.0
                        && (y - center[1].0).abs() < size[1].0 / 2.0
                }
                _ => false,
            })
        };
        assert!(inside(0.021, 0.021));
        assert!(!inside(0.08, 0.08));
    }
}
