//! Floor textures: an `ImageTexture` on the floor (a `RectangleArena`'s `floorAppearance`, a
//! `Floor`'s `appearance`, or a textured `Shape` whose `Plane` lies on the ground) becomes floor
//! paint whose reflectance follows the image's grey level.
//!
//! The import only finds the textures and where they lie; the image files are read by the caller
//! (the Python package decodes PNG and JPEG) and handed to [`WbtImport::paint_floor`] as grey
//! levels. The image is laid on the floor rectangle as Webots tiles it: one copy of the image per
//! tile (`floorTileSize` of a `RectangleArena`, `tileSize` of a `Floor`, the whole plane of a
//! `Shape`), divided by the appearance's `textureTransform` scale, tiles starting at the
//! rectangle's (-x, -y) corner, the image's top row towards +y and its left column towards -x;
//! the Y-up `Floor` PROTO of worlds before R2022a starts them at its (-x, +z) corner, the top row
//! towards -z, a quarter turn from the Z-up one's.
//! An `ImageTexture` with `repeatS FALSE` (or `repeatT FALSE`) is not repeated along the image's
//! x (or y): Webots clamps the texture coordinates to [0, 1] (reference manual, ImageTexture),
//! so one copy lies in the first tile and its last column (top row) stretches to the floor's
//! edge.
//! A grey level `g` in [0, 1] paints the reflection factor `0.2 + 0.8 g` of Webots' infra-red
//! model (white 1, black 0.2), in steps of 1/255 of the grey scale; of an appearance whose red
//! (a `PBRAppearance`'s `baseColor`, times `1 - transparency`) is not 1 or whose `roughness`
//! is not 0, `0.2 + 0.8 g red (1 - 0.5 roughness)` (a white pixel of the usual `roughness 1`
//! reflects 0.6), that paint keeping the grey a camera sees as its colour. A texture's paint fits what
//! the world's paint regions leave ([`MAX_PAINT_REGIONS`] with the paint before it), its image
//! averaged down until it does.

use std::collections::BTreeMap;
use std::path::Path;

use super::appearance::reflection_factor;
use super::floor_marks::world_point;
use super::frames::{tilt, Frame, Vec3};
use super::import::{Importer, TILT_TOLERANCE};
use super::shapes::{snap, wrap_angle, FLOOR_LEVEL};
use super::tree::Node;
use super::WbtImport;
use crate::limits::MAX_PAINT_REGIONS;
use crate::world::spec::{paint_regions, PaintSpec};
use crate::world::values::{self, Finite, Positive, Reflectance};

/// Largest image side read, in pixels: larger images are averaged down to it (by area) first.
pub const MAX_TEXTURE_SIDE: usize = 2048;
/// Smallest side an image is averaged down to so that its paint fits [`MAX_TEXTURE_PAINT`].
pub const MIN_TEXTURE_SIDE: usize = 256;
/// Most paint rectangles one texture may give; beyond it the texture is left out, with a warning.
pub const MAX_TEXTURE_PAINT: usize = 200_000;
/// Reflection factor of black in Webots' infra-red model; white is 1.
const BLACK_REFLECTANCE: f64 = 0.2;

/// A texture image as grey levels in [0, 1], row-major, the top row first.
#[derive(Debug, Clone, PartialEq)]
pub struct GreyImage {
    /// Pixels per row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// `width * height` grey levels.
    pub levels: Vec<f64>,
}

/// An image texture lying on the floor, as found in the world.
#[derive(Debug, Clone, PartialEq)]
pub struct FloorTexture {
    /// The `url` entries of the `ImageTexture`, in order.
    pub urls: Vec<String>,
    /// `line L: Type "name"` of the node the floor belongs to.
    pub owner: String,
    /// Centre of the textured rectangle (world frame, metres).
    pub center: [f64; 2],
    /// Its size along its own x and y.
    pub size: [f64; 2],
    /// Its rotation about z.
    pub yaw: f64,
    /// Size on the floor of one copy of the image.
    pub tile: [f64; 2],
    /// Whether the image repeats along its x and y (the `ImageTexture`'s `repeatS` and
    /// `repeatT`); one that does not is laid once, its edge stretched to the floor's.
    pub repeat: [bool; 2],
    /// Files to look for, in order: each url beside the world file, then in `textures/` beside it.
    pub candidates: Vec<String>,
    /// The red the appearance gives a white pixel (its colour's red times `1 -
    /// transparency`) and its roughness, which set the paint's reflection factor with the
    /// pixel's level (see the module).
    pub red_roughness: (f64, f64),
}

/// The reflection factor painted for a grey level, quantised to 1/255 of the grey scale.
pub fn grey_reflectance(level: f64) -> f64 {
    let q = (level.clamp(0.0, 1.0) * 255.0).round() / 255.0;
    BLACK_REFLECTANCE + (1.0 - BLACK_REFLECTANCE) * q
}

impl GreyImage {
    /// The image averaged down to at most `side` pixels a side: each pixel of the result is the
    /// mean of the image over the area it covers, so that a line thinner than a pixel of the
    /// result stays a connected band, lighter than the line by the share of the pixel it covers.
    fn averaged(&self, side: usize) -> GreyImage {
        let (w, h) = (self.width.min(side), self.height.min(side));
        if (w, h) == (self.width, self.height) {
            return self.clone();
        }
        let (columns, rows) = (area_shares(self.width, w), area_shares(self.height, h));
        // Along the rows first (height x w), then down the columns.
        let mut narrow = Vec::with_capacity(w * self.height);
        for row in self.levels.chunks_exact(self.width) {
            narrow.extend(columns.iter().map(|shares| mean_of(shares, |k| row[k])));
        }
        let mut levels = Vec::with_capacity(w * h);
        for shares in &rows {
            levels.extend((0..w).map(|c| mean_of(shares, |k| narrow[k * w + c])));
        }
        GreyImage {
            width: w,
            height: h,
            levels,
        }
    }
}

/// For each of `to` equal cells laid over `from` pixels in a line: the pixels it covers and the
/// share of the cell each covers (the shares of a cell sum to 1; whole when `to == from`).
fn area_shares(from: usize, to: usize) -> Vec<Vec<(usize, f64)>> {
    // In units of 1 / `to` of a pixel, cell i spans [i * from, (i + 1) * from) and pixel k
    // spans [k * to, (k + 1) * to).
    (0..to)
        .map(|i| {
            let (start, end) = (i * from, (i + 1) * from);
            (start / to..end.div_ceil(to))
                .map(|k| {
                    let overlap = end.min((k + 1) * to) - start.max(k * to);
                    (k, overlap as f64 / from as f64)
                })
                .collect()
        })
        .collect()
}

/// The sum of `level(k) * share` over `shares`.
fn mean_of(shares: &[(usize, f64)], level: impl Fn(usize) -> f64) -> f64 {
    shares.iter().map(|&(k, share)| level(k) * share).sum()
}

/// Rectangles `[c0, c1, r0, r1]` (columns `c0..c1`, rows `r0..r1`) of equal cells of a grid,
/// row-major, with the value of each: runs along each row joined with the same run of the row
/// before.
pub(super) fn equal_rects<T: Copy + Ord>(
    cells: &[T],
    width: usize,
    height: usize,
) -> Vec<([usize; 4], T)> {
    let mut done = Vec::new();
    // Open rectangles keyed by (c0, c1, value), still growing downwards.
    let mut open: BTreeMap<(usize, usize, T), usize> = BTreeMap::new();
    for r in 0..=height {
        let mut next = BTreeMap::new();
        if r < height {
            let row = &cells[r * width..(r + 1) * width];
            let mut c0 = 0;
            while c0 < width {
                let value = row[c0];
                let c1 = c0 + row[c0..].iter().take_while(|&&v| v == value).count();
                let r0 = open.remove(&(c0, c1, value)).unwrap_or(r);
                next.insert((c0, c1, value), r0);
                c0 = c1;
            }
        }
        for ((c0, c1, value), r0) in std::mem::replace(&mut open, next) {
            done.push(([c0, c1, r0, r], value));
        }
    }
    done
}

/// A rectangle `[c0, c1, r0, r1]` of an image's pixels and their grey level in 0..=255.
type GreyRect = ([usize; 4], u8);

/// The image as rectangles of equal grey, in pixel units of one tile, with the grey level of
/// each in 0..=255.
fn pixel_rects(image: &GreyImage) -> Vec<GreyRect> {
    let quantised: Vec<u8> = image
        .levels
        .iter()
        .map(|g| (g.clamp(0.0, 1.0) * 255.0).round() as u8)
        .collect();
    equal_rects(&quantised, image.width, image.height)
}

/// The image as painted over `tile_count` tiles, with its rectangles: at its own size (up to
/// [`MAX_TEXTURE_SIDE`]), halved while its paint does not fit [`MAX_TEXTURE_PAINT`], down to
/// [`MIN_TEXTURE_SIDE`]; or why it does not fit even then.
fn fitted(image: &GreyImage, tile_count: usize) -> Result<(GreyImage, Vec<GreyRect>), String> {
    halved_until(image.averaged(MAX_TEXTURE_SIDE), |image, rects| {
        if tile_count.saturating_mul(rects.len()) <= MAX_TEXTURE_PAINT {
            Ok((image.clone(), rects))
        } else {
            Err(format!(
                "expected at most {MAX_TEXTURE_PAINT} paint rectangles, found {tile_count} tiles of {} rectangles",
                rects.len()
            ))
        }
    })
}

/// What `fits` makes of `image` and its rectangles, the image halved (averaged by area, down to
/// [`MIN_TEXTURE_SIDE`]) while `fits` refuses it; or its refusal of the smallest.
fn halved_until<T>(
    mut image: GreyImage,
    mut fits: impl FnMut(&GreyImage, Vec<GreyRect>) -> Result<T, String>,
) -> Result<T, String> {
    loop {
        let refusal = match fits(&image, pixel_rects(&image)) {
            Ok(done) => return Ok(done),
            Err(why) => why,
        };
        let side = image.width.max(image.height);
        if side <= MIN_TEXTURE_SIDE {
            return Err(refusal);
        }
        image = image.averaged((side / 2).max(MIN_TEXTURE_SIDE));
    }
}

impl FloorTexture {
    /// The paint of this texture for its image, within `room` paint regions (what the world's
    /// paint leaves: the image is averaged down further while its paint does not fit), or why
    /// it cannot be painted.
    pub fn paint(&self, image: &GreyImage, room: usize) -> Result<Vec<PaintSpec>, String> {
        if image.width == 0 || image.height == 0 || image.levels.len() != image.width * image.height
        {
            return Err(format!(
                "expected an image of width x height grey levels, found {} levels for {} x {}",
                image.levels.len(),
                image.width,
                image.height
            ));
        }
        let [sx, sy] = self.size;
        let [tx, ty] = self.tile;
        // Tiles along each axis: one when the image does not repeat along it.
        let tiles = [
            if self.repeat[0] {
                (sx / tx).ceil() as usize
            } else {
                1
            },
            if self.repeat[1] {
                (sy / ty).ceil() as usize
            } else {
                1
            },
        ];
        let (image, _) = fitted(image, tiles[0].saturating_mul(tiles[1]))?;
        halved_until(image, |image, rects| {
            let paint = self.laid(image, &rects, tiles);
            if paint.len() <= room {
                Ok(paint)
            } else {
                Err(format!(
                    "expected at most {room} paint regions (what the world's paint leaves), found {}",
                    paint.len()
                ))
            }
        })
    }

    /// The paint of `image` (its equal-grey `rects`) laid in `tiles` copies along x and y.
    fn laid(&self, image: &GreyImage, rects: &[GreyRect], tiles: [usize; 2]) -> Vec<PaintSpec> {
        let (red, roughness) = self.red_roughness;
        let plain = (red, roughness) == (1.0, 0.0);
        let reflectance = |level: u8| {
            let grey = grey_reflectance(level as f64 / 255.0);
            if plain {
                grey
            } else {
                let level = (grey - BLACK_REFLECTANCE) / (1.0 - BLACK_REFLECTANCE);
                reflection_factor(level * red, roughness, 0.0)
            }
        };
        // A camera sees the pixel's grey, which the reflection factor no longer gives.
        let colour = |level: u8| (!plain).then(|| values::colour([level as f64 / 255.0; 3]));
        let [sx, sy] = self.size;
        let [tx, ty] = self.tile;
        let (px, py) = (tx / image.width as f64, ty / image.height as f64);
        let (s, c) = self.yaw.sin_cos();
        let mut paint = Vec::new();
        for i in 0..tiles[0] {
            for j in 0..tiles[1] {
                // The tile's top-left corner in the rectangle's frame (origin at its centre).
                let left = -sx / 2.0 + i as f64 * tx;
                let top = -sy / 2.0 + (j + 1) as f64 * ty;
                for &([c0, c1, r0, r1], level) in rects {
                    // A rectangle on the image's last column (top row) of an image that does
                    // not repeat along x (y) stretches to the floor's edge, as clamped
                    // texture coordinates draw it.
                    let right_edge = !self.repeat[0] && c1 == image.width;
                    let top_edge = !self.repeat[1] && r0 == 0;
                    let x0 = left + c0 as f64 * px;
                    let x1 = if right_edge {
                        sx / 2.0
                    } else {
                        (left + c1 as f64 * px).min(sx / 2.0)
                    };
                    let y1 = if top_edge {
                        sy / 2.0
                    } else {
                        (top - r0 as f64 * py).min(sy / 2.0)
                    };
                    let y0 = (top - r1 as f64 * py).max(-sy / 2.0);
                    if x1 - x0 <= 1e-9 || y1 - y0 <= 1e-9 {
                        continue;
                    }
                    let (u, v) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
                    paint.push(PaintSpec::Rect {
                        center: [
                            Finite(snap(self.center[0] + c * u - s * v)),
                            Finite(snap(self.center[1] + s * u + c * v)),
                        ],
                        size: [Positive(x1 - x0), Positive(y1 - y0)],
                        yaw: Finite(self.yaw),
                        reflectance: Reflectance(reflectance(level)),
                        colour: colour(level),
                    });
                }
            }
        }
        paint
    }
}

impl WbtImport {
    /// Paints the floor textures whose images are given, keyed by the candidate file each was
    /// read from (the first candidate found counts); one that cannot be painted gets a warning.
    /// A texture with no image is left out: the caller, which looks for every texture's image
    /// (the floor's and the walls'), says which files it looked for. Call it once, after the
    /// import.
    pub fn paint_floor(&mut self, images: &BTreeMap<String, GreyImage>) {
        // Texture paint goes under the marks of visual-only shapes already painted.
        let marks = std::mem::take(&mut self.paint);
        let marked = paint_regions(&marks);
        for texture in &self.floor_textures {
            let found = texture
                .candidates
                .iter()
                .find_map(|c| images.get(c).map(|image| (c, image)));
            if let Some((file, image)) = found {
                let room = MAX_PAINT_REGIONS.saturating_sub(marked + paint_regions(&self.paint));
                match texture.paint(image, room) {
                    Ok(paint) => self.paint.extend(paint),
                    Err(why) => self.warnings.push(format!(
                        "{}: floor texture {file}: not painted: {why}",
                        texture.owner
                    )),
                }
            }
        }
        // The texture's paint is held by no node a supervisor moves.
        let owners = std::mem::take(&mut self.paint_owners);
        self.paint_owners = vec![Vec::new(); self.paint.len()];
        self.paint_owners.extend(owners);
        self.paint.extend(marks);
    }

    /// Fills each texture's candidate files (the floor's and the walls') for a world file in
    /// `dir`.
    pub(super) fn locate_textures(&mut self, dir: &Path) {
        for texture in &mut self.floor_textures {
            texture.candidates = texture_candidates(dir, &texture.urls);
        }
        for texture in &mut self.wall_textures {
            texture.candidates = texture_candidates(dir, &texture.urls);
        }
    }
}

/// The files an image texture of `urls` is looked for in, for a world file in `dir`: each url
/// beside the world file (not a web one), then its file name in `textures/` beside it.
fn texture_candidates(dir: &Path, urls: &[String]) -> Vec<String> {
    let mut candidates = Vec::new();
    for url in urls {
        let file = url.rsplit('/').next().unwrap_or(url);
        let is_web = url.contains("://");
        if !is_web && !url.is_empty() {
            candidates.push(dir.join(url).display().to_string());
        }
        if !file.is_empty() {
            candidates.push(dir.join("textures").join(file).display().to_string());
        }
    }
    candidates.dedup();
    candidates
}

impl<'d> Importer<'d> {
    /// The urls of the `ImageTexture` in the field `field` of an appearance node; `None`
    /// without one, or when its urls are all empty (what Webots' scene tree leaves when a
    /// texture is cleared, which loads no image in Webots: no texture, and nothing to warn of).
    pub(super) fn image_texture_urls(
        &mut self,
        appearance: &'d Node,
        field: &str,
    ) -> Option<Vec<String>> {
        let texture = self
            .nodes(appearance, field)
            .iter()
            .map(|&id| self.node(id))
            .find(|n| n.type_name == "ImageTexture")?;
        let urls = self.strings(texture, "url").to_vec();
        if urls.iter().all(|url| url.trim().is_empty()) {
            return None;
        }
        Some(urls)
    }

    /// The `ImageTexture` urls of an appearance (`PBRAppearance.baseColorMap`,
    /// `Appearance.texture`) and its `textureTransform` scale; `None` when it has no texture
    /// with a url.
    fn appearance_texture(
        &mut self,
        appearance: &'d Node,
    ) -> Option<(Vec<String>, [f64; 2], [bool; 2])> {
        let field = match appearance.type_name.as_str() {
            "PBRAppearance" => "baseColorMap",
            "Appearance" => "texture",
            // An appearance PROTO of a `colorOverride` is read as that colour (the floor's or
            // a patch of it, `floor_look_of`): its texture is counted white.
            _ if self.appearance_node_colour(appearance).is_some() => return None,
            _ => {
                let label = self.label(appearance);
                self.warn(format!(
                    "{label}: a floor appearance mazesim does not read (only PBRAppearance and Appearance with an ImageTexture): the floor is left bare"
                ));
                return None;
            }
        };
        let urls = self.image_texture_urls(appearance, field)?;
        let repeat = self.texture_repeats(appearance, field);
        let scale = self
            .nodes(appearance, "textureTransform")
            .first()
            .map(|&id| self.node(id))
            .map_or([1.0, 1.0], |t| self.vector(t, "scale", [1.0, 1.0]));
        Some((urls, scale, repeat))
    }

    /// Whether the `ImageTexture` in the field `field` of an appearance repeats along the
    /// image's x and y (its `repeatS` and `repeatT`, TRUE unless the file says FALSE).
    fn texture_repeats(&self, appearance: &'d Node, field: &str) -> [bool; 2] {
        let texture = self
            .nodes(appearance, field)
            .iter()
            .map(|&id| self.node(id))
            .find(|n| n.type_name == "ImageTexture");
        ["repeatS", "repeatT"].map(|name| {
            texture.is_none_or(|t| t.field(name).is_none_or(|f| f.value.bools != [false]))
        })
    }

    /// Records a texture laid on the floor rectangle `size` of `frame` (Z-up), one image per `tile`.
    /// Lays an appearance's image texture on a floor rectangle of `size` in tiles of `tile`,
    /// both along `frame`'s x and y; or, for the Y-up `Floor` PROTO of a world before R2022a
    /// (`y_up_floor`), along the PROTO's own x and z, its image's left column towards -x and
    /// top row towards -z, a quarter turn from the Z-up PROTO's (`frame` is its Z-up frame,
    /// whose x is the Y-up -z and whose y the Y-up -x).
    fn lay_texture(
        &mut self,
        owner: &'d Node,
        appearance: &'d Node,
        frame: &Frame,
        size: [f64; 2],
        tile: [f64; 2],
        y_up_floor: bool,
    ) {
        let Some((urls, scale, repeat)) = self.appearance_texture(appearance) else {
            return;
        };
        let label = self.label(owner);
        let tile = [tile[0] / scale[0], tile[1] / scale[1]];
        let sizes_ok = size.iter().chain(&tile).all(|v| v.is_finite() && *v > 0.0);
        if !sizes_ok {
            self.warn(format!(
                "{label}: a floor texture over {size:?} m in tiles of {tile:?} m: expected sizes above 0; not painted"
            ));
            return;
        }
        let x_axis = frame.axis(0);
        let (mut sx, mut sy) = (
            x_axis[0].hypot(x_axis[1]),
            frame.axis(1)[0].hypot(frame.axis(1)[1]),
        );
        let mut yaw = x_axis[1].atan2(x_axis[0]);
        if y_up_floor {
            // The image's x runs along the Z-up frame's -y, its y along the frame's x.
            yaw -= std::f64::consts::FRAC_PI_2;
            (sx, sy) = (sy, sx);
        }
        let red_roughness = self.appearance_red(appearance);
        self.floor_textures.push(FloorTexture {
            urls,
            owner: label,
            center: [snap(frame.origin[0]), snap(frame.origin[1])],
            size: [size[0] * sx, size[1] * sy],
            yaw: wrap_angle(snap(yaw)),
            tile: [tile[0] * sx, tile[1] * sy],
            repeat,
            candidates: Vec::new(),
            red_roughness,
        });
    }

    /// The floor of a `RectangleArena` (`frame` is its Z-up frame): its `floorAppearance`.
    pub fn arena_floor(&mut self, node: &'d Node, frame: &Frame, floor: [f64; 2]) {
        self.floor_look_of(node, "floorAppearance", frame, floor);
        let Some(&appearance) = self.nodes(node, "floorAppearance").first() else {
            return;
        };
        let tile = self.vector(node, "floorTileSize", [0.5, 0.5]);
        // `floor` is along the Z-up frame's axes; a Y-up Floor's texture is laid along its own.
        let size = if self.y_up {
            [floor[1], floor[0]]
        } else {
            floor
        };
        self.lay_texture(node, self.node(appearance), frame, size, tile, self.y_up);
    }

    /// A `Floor` PROTO: no collision in 2D, but its `appearance` may be a texture.
    pub fn floor(&mut self, node: &'d Node, frame: &Frame) {
        let local = self.local_frame(node, [0.0; 3]);
        let frame = self.z_up(&frame.then(&local));
        let size = self.vector(node, "size", [10.0, 10.0]);
        if self.y_up {
            // A Y-up Floor's size is along its own axes: its larger side covers both.
            let side = size[0].max(size[1]);
            self.floor_look_of(node, "appearance", &frame, [side, side]);
            self.floor_surface(&frame, [side, side]);
        } else {
            self.floor_look_of(node, "appearance", &frame, size);
            self.floor_surface(&frame, size);
        }
        let Some(&appearance) = self.nodes(node, "appearance").first() else {
            return;
        };
        let tile = self.vector(node, "tileSize", [0.5, 0.5]);
        self.lay_texture(node, self.node(appearance), &frame, size, tile, self.y_up);
    }

    /// A `Shape` in the scene: a textured horizontal `Plane` at floor level is a floor texture.
    pub fn textured_shape(&mut self, node: &'d Node, frame: &Frame) {
        let Some(&geometry) = self.nodes(node, "geometry").first() else {
            return;
        };
        let Some(&appearance) = self.nodes(node, "appearance").first() else {
            return;
        };
        let geometry = self.node(geometry);
        if geometry.type_name == "IndexedFaceSet" {
            self.textured_face_set(node, geometry, frame);
            return;
        }
        if geometry.type_name != "Plane" {
            return;
        }
        let frame = self.z_up(frame);
        let level = frame.origin[2];
        if tilt(frame.axis(2)) > TILT_TOLERANCE || level.abs() > 10.0 * FLOOR_LEVEL {
            return;
        }
        let mut size = self.vector(geometry, "size", [1.0, 1.0]);
        if self.y_up {
            size = [size[1], size[0]];
        }
        self.lay_texture(node, self.node(appearance), &frame, size, size, false);
    }

    /// A textured `IndexedFaceSet` lying on the floor as one rectangle whose texture
    /// coordinates run from (0, 0) at one corner to (u, v) at the opposite one, along its sides
    /// (the floor of a `RectangleArena` or `Floor` PROTO that Webots' "Convert to Base Node(s)"
    /// saved as a Solid, its Shape drawing the texture `u` by `v` times): its image laid in tiles
    /// as on the PROTO's floor. Returns whether it did (`frame` is the shape's parent's).
    pub fn textured_face_set(&mut self, node: &'d Node, geometry: &'d Node, frame: &Frame) -> bool {
        let Some(&appearance) = self.nodes(node, "appearance").first() else {
            return false;
        };
        let Some((corners, uv)) = self.face_set_quad(geometry, frame) else {
            return false;
        };
        let span = |a: usize, b: usize| [0, 1, 2].map(|i| corners[b][i] - corners[a][i]);
        // The corner of texture coordinate (0, 0), and those of (u, 0) and (0, v).
        let Some(origin) = (0..4).find(|&k| uv[k] == [0.0, 0.0]) else {
            return false;
        };
        let (u, v) = (
            uv.iter().map(|t| t[0]).fold(0.0, f64::max),
            uv.iter().map(|t| t[1]).fold(0.0, f64::max),
        );
        let (Some(along_u), Some(along_v), Some(far)) = (
            (0..4).find(|&k| uv[k] == [u, 0.0]),
            (0..4).find(|&k| uv[k] == [0.0, v]),
            (0..4).find(|&k| uv[k] == [u, v]),
        ) else {
            return false;
        };
        let (x, y) = (span(origin, along_u), span(origin, along_v));
        let diagonal = span(origin, far);
        let (width, depth) = (x[0].hypot(x[1]), y[0].hypot(y[1]));
        let square = (x[0] * y[0] + x[1] * y[1]).abs() <= 1e-6 * width * depth;
        let closed = (0..2).all(|i| (x[i] + y[i] - diagonal[i]).abs() <= 1e-6 * (width + depth));
        let level = corners
            .iter()
            .map(|c| c[2])
            .fold(f64::NEG_INFINITY, f64::max);
        let flat = corners.iter().all(|c| (c[2] - level).abs() <= FLOOR_LEVEL);
        let upright = x[0] * y[1] - x[1] * y[0] > 0.0; // not a mirror image of the texture
        if !(u > 0.0 && v > 0.0 && width > 0.0 && depth > 0.0 && square && closed && flat)
            || level.abs() > 10.0 * FLOOR_LEVEL
            || !upright
        {
            return false;
        }
        let (ux, uy) = ([x[0] / width, x[1] / width], [y[0] / depth, y[1] / depth]);
        let centre = [0, 1, 2].map(|i| (corners[origin][i] + corners[far][i]) / 2.0);
        let floor = Frame {
            linear: [[ux[0], uy[0], 0.0], [ux[1], uy[1], 0.0], [0.0, 0.0, 1.0]],
            origin: centre,
        };
        let size = [width, depth];
        let tile = [width / u, depth / v];
        self.lay_texture(node, self.node(appearance), &floor, size, tile, false);
        true
    }

    /// The four corners (world frame) and texture coordinates of an `IndexedFaceSet` of one
    /// face of four corners, with a texture coordinate for each (its `texCoordIndex`, or its
    /// `coordIndex` when it has none); `None` for any other.
    fn face_set_quad(
        &self,
        geometry: &'d Node,
        frame: &Frame,
    ) -> Option<([Vec3; 4], [[f64; 2]; 4])> {
        let coord = self.node(*self.nodes(geometry, "coord").first()?);
        let points = self.numbers(coord, "point")?;
        let tex = self.node(*self.nodes(geometry, "texCoord").first()?);
        let tex_points = self.numbers(tex, "point")?;
        let face = self.numbers(geometry, "coordIndex")?;
        let tex_face = self
            .numbers(geometry, "texCoordIndex")
            .filter(|t| !t.is_empty())
            .unwrap_or(face);
        let corners_of = |indices: &[f64]| -> Option<[usize; 4]> {
            let used: Vec<f64> = match indices.split_last() {
                Some((last, rest)) if *last < 0.0 => rest.to_vec(),
                _ => indices.to_vec(),
            };
            let used: Vec<usize> = used
                .iter()
                .map(|&i| (i >= 0.0 && i.fract() == 0.0).then_some(i as usize))
                .collect::<Option<_>>()?;
            used.try_into().ok()
        };
        let (ids, tex_ids) = (corners_of(face)?, corners_of(tex_face)?);
        let mut corners = [[0.0; 3]; 4];
        let mut uv = [[0.0; 2]; 4];
        for k in 0..4 {
            let p = points.get(3 * ids[k]..3 * ids[k] + 3)?;
            corners[k] = world_point(frame, [p[0], p[1], p[2]]);
            let t = tex_points.get(2 * tex_ids[k]..2 * tex_ids[k] + 2)?;
            uv[k] = [t[0], t[1]];
        }
        Some((corners, uv))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texture(size: [f64; 2], tile: [f64; 2]) -> FloorTexture {
        FloorTexture {
            urls: vec!["track.png".into()],
            owner: "line 1: RectangleArena".into(),
            center: [0.0, 0.0],
            size,
            yaw: 0.0,
            tile,
            repeat: [true, true],
            candidates: vec!["track.png".into()],
            red_roughness: (1.0, 0.0),
        }
    }

    fn reflectance_at(paint: &[PaintSpec], x: f64, y: f64) -> Option<f64> {
        paint.iter().rev().find_map(|p| match p {
            PaintSpec::Rect {
                center,
                size,
                reflectance,
                ..
            } => {
                let inside = (x - center[0].0).abs() < size[0].0 / 2.0
                    && (y - center[1].0).abs() < size[1].0 / 2.0;
                inside.then_some(reflectance.0)
            }
            _ => None,
        })
    }

    #[test]
    fn rows_of_equal_grey_join_into_rectangles() {
        // 4 x 3: a black column in the middle of white, one grey pixel at the bottom right.
        let levels = vec![
            1.0, 0.0, 1.0, 1.0, //
            1.0, 0.0, 1.0, 1.0, //
            1.0, 0.0, 1.0, 0.5,
        ];
        let image = GreyImage {
            width: 4,
            height: 3,
            levels,
        };
        assert_eq!(pixel_rects(&image).len(), 5);
        let paint = texture([0.4, 0.3], [0.4, 0.3])
            .paint(&image, MAX_PAINT_REGIONS)
            .unwrap();
        // Pixel (row 0, column 1) is at x in [-0.1, 0], y in [0.05, 0.15].
        assert_eq!(reflectance_at(&paint, -0.05, 0.1), Some(0.2));
        assert_eq!(reflectance_at(&paint, -0.15, -0.1), Some(1.0));
        assert_eq!(
            reflectance_at(&paint, 0.15, -0.1),
            Some(grey_reflectance(0.5))
        );
        assert_eq!(reflectance_at(&paint, 0.15, 0.1), Some(1.0));
    }

    #[test]
    fn an_appearance_s_red_and_roughness_scale_the_paint_a_camera_still_sees_grey() {
        let image = GreyImage {
            width: 2,
            height: 1,
            levels: vec![0.0, 1.0],
        };
        // White of roughness 1 reflects 0.6 (Webots' `0.2 + 0.8 red (1 - 0.5 roughness)`), and
        // of a base colour 0.5 roughness 0.5, 0.5; black stays 0.2.
        for (red_roughness, white) in [((1.0, 1.0), 0.6), ((0.5, 0.5), 0.5)] {
            let paint = FloorTexture {
                red_roughness,
                ..texture([0.2, 0.1], [0.2, 0.1])
            }
            .paint(&image, MAX_PAINT_REGIONS)
            .unwrap();
            let close = |a: Option<f64>, b: f64| a.is_some_and(|a| (a - b).abs() < 1e-12);
            assert!(close(reflectance_at(&paint, -0.05, 0.0), 0.2));
            assert!(close(reflectance_at(&paint, 0.05, 0.0), white));
            let colours: Vec<_> = paint
                .iter()
                .map(|p| match p {
                    PaintSpec::Rect { colour, .. } => colour.map(|c| c.map(|l| l.0)),
                    _ => None,
                })
                .collect();
            assert_eq!(colours, [Some([0.0; 3]), Some([1.0; 3])]);
        }
    }

    #[test]
    fn tiles_repeat_the_image_and_stop_at_the_floor_edge() {
        let image = GreyImage {
            width: 2,
            height: 1,
            levels: vec![0.0, 1.0],
        };
        // A 1 x 0.2 floor in tiles of 0.4 x 0.2: black, white, black, white, black (cut).
        let paint = texture([1.0, 0.2], [0.4, 0.2])
            .paint(&image, MAX_PAINT_REGIONS)
            .unwrap();
        for (x, f) in [
            (-0.45, 0.2),
            (-0.25, 1.0),
            (-0.05, 0.2),
            (0.15, 1.0),
            (0.45, 0.2),
        ] {
            assert_eq!(reflectance_at(&paint, x, 0.0), Some(f), "x {x}");
        }
        assert_eq!(reflectance_at(&paint, 0.51, 0.0), None);
    }

    #[test]
    fn an_image_that_does_not_repeat_is_laid_once_its_edges_stretched() {
        // Top row black, white; bottom row white, black; one 0.4 m copy at the (-x, -y) corner
        // of a 1 m floor, its last column stretched to +x and its top row to +y.
        let image = GreyImage {
            width: 2,
            height: 2,
            levels: vec![0.0, 1.0, 1.0, 0.0],
        };
        let mut once = texture([1.0, 1.0], [0.4, 0.4]);
        once.repeat = [false, false];
        let paint = once.paint(&image, MAX_PAINT_REGIONS).unwrap();
        assert_eq!(paint.len(), 4);
        for (x, y, f) in [
            (-0.45, -0.45, 1.0), // bottom left
            (-0.15, -0.2, 1.0),  // top right
            (0.3, -0.45, 0.2),   // the last column, stretched: bottom right
            (-0.45, 0.3, 0.2),   // the top row, stretched: top left
            (-0.15, 0.3, 1.0),
            (0.45, 0.45, 1.0), // the top right texel in the corner
        ] {
            assert_eq!(reflectance_at(&paint, x, y), Some(f), "({x}, {y})");
        }
        // Repeated along y only: copies up the floor, the last column stretched along x.
        once.repeat = [false, true];
        let paint = once.paint(&image, MAX_PAINT_REGIONS).unwrap();
        assert_eq!(reflectance_at(&paint, 0.3, 0.0), Some(0.2)); // second copy's bottom row
        assert_eq!(reflectance_at(&paint, -0.45, 0.0), Some(1.0));
        assert_eq!(reflectance_at(&paint, 0.3, 0.2), Some(1.0)); // its top row
    }

    #[test]
    fn a_texture_fits_the_paint_the_world_has_left() {
        // 512 x 512 in one-pixel stripes, black and white: 512 rectangles, one grey one once
        // averaged to 256 x 256; in 4 tiles 2048 regions, or 4.
        let side = 512;
        let levels = (0..side * side).map(|i| (i % 2) as f64).collect();
        let image = GreyImage {
            width: side,
            height: side,
            levels,
        };
        let tiled = texture([1.0, 1.0], [0.5, 0.5]);
        assert_eq!(tiled.paint(&image, MAX_PAINT_REGIONS).unwrap().len(), 2048);
        assert_eq!(tiled.paint(&image, 1000).unwrap().len(), 4);
        let err = tiled.paint(&image, 3).unwrap_err();
        assert!(err.contains("expected at most 3 paint regions"), "{err}");
    }

    #[test]
    fn too_many_tiles_are_refused_not_painted() {
        let image = GreyImage {
            width: 2,
            height: 2,
            levels: vec![0.0, 1.0, 1.0, 0.0],
        };
        let err = texture([1e6, 1e6], [1e-3, 1e-3])
            .paint(&image, usize::MAX)
            .unwrap_err();
        assert!(
            err.contains("expected at most 200000 paint rectangles"),
            "{err}"
        );
    }

    #[test]
    fn large_images_keep_their_edges_to_the_pixel() {
        // 512 x 300, black left of column 200: the edge is at 200 / 512 of the width.
        let (width, height) = (512, 300);
        let levels = (0..width * height)
            .map(|i| if i % width < 200 { 0.0 } else { 1.0 })
            .collect();
        let image = GreyImage {
            width,
            height,
            levels,
        };
        let paint = texture([0.512, 0.3], [0.512, 0.3])
            .paint(&image, MAX_PAINT_REGIONS)
            .unwrap();
        assert_eq!(paint.len(), 2, "one black and one white rectangle");
        let edge = -0.256 + 0.2;
        assert_eq!(reflectance_at(&paint, edge - 0.0005, 0.0), Some(0.2));
        assert_eq!(reflectance_at(&paint, edge + 0.0005, 0.0), Some(1.0));
    }

    /// An 800 x 800 white image with a black ring 3 pixels wide, 300 pixels in radius, and
    /// whether each pixel is on the ring.
    fn ring_image() -> (GreyImage, Vec<bool>) {
        let side = 800;
        let on_ring: Vec<bool> = (0..side * side)
            .map(|i| {
                let (r, c) = ((i / side) as f64 + 0.5, (i % side) as f64 + 0.5);
                ((c - 400.0).hypot(r - 400.0) - 300.0).abs() < 1.5
            })
            .collect();
        let levels = on_ring
            .iter()
            .map(|&on| if on { 0.0 } else { 1.0 })
            .collect();
        let image = GreyImage {
            width: side,
            height: side,
            levels,
        };
        (image, on_ring)
    }

    #[test]
    fn a_thin_line_of_a_large_image_is_painted_pixel_for_pixel() {
        // One pixel a millimetre: every pixel of the ring, which is one 8-connected piece, is
        // painted black where it lies.
        let (image, on_ring) = ring_image();
        let paint = texture([0.8, 0.8], [0.8, 0.8])
            .paint(&image, MAX_PAINT_REGIONS)
            .unwrap();
        for (i, _) in on_ring.iter().enumerate().filter(|(_, &on)| on) {
            let (r, c) = ((i / 800) as f64 + 0.5, (i % 800) as f64 + 0.5);
            let (x, y) = (-0.4 + c * 1e-3, 0.4 - r * 1e-3);
            assert_eq!(reflectance_at(&paint, x, y), Some(0.2), "pixel {r}, {c}");
        }
    }

    #[test]
    fn over_the_paint_budget_a_thin_line_is_averaged_into_a_band_seen_all_round() {
        let (image, _) = ring_image();
        // Just too many tiles for the image at its own size, then for it at half its size.
        let over = |image: &GreyImage| MAX_TEXTURE_PAINT / pixel_rects(image).len() + 1;
        for tiles in [over(&image), over(&image.averaged(400))] {
            let (fitted, rects) = fitted(&image, tiles).unwrap();
            assert!(fitted.width < 800 && tiles * rects.len() <= MAX_TEXTURE_PAINT);
            // Crossing the ring outwards at every half degree, in steps of a quarter of a pixel
            // of the image: the darkest pixel met, and the darkness summed across the band (the
            // line's width in pixels of the image where it is black).
            let scale = fitted.width as f64 / 800.0;
            for step in 0..720 {
                let (s, c) = (step as f64 / 720.0 * std::f64::consts::TAU).sin_cos();
                let levels: Vec<f64> = (0..=80)
                    .map(|k| 290.0 + k as f64 * 0.25)
                    .map(|radius| {
                        let col = ((400.0 + radius * c) * scale) as usize;
                        let row = ((400.0 + radius * s) * scale) as usize;
                        fitted.levels[row * fitted.width + col]
                    })
                    .collect();
                let darkest = levels.iter().copied().fold(1.0_f64, f64::min);
                let width: f64 = levels.iter().map(|g| (1.0 - g) * 0.25).sum();
                let at = format!("{} px, {} degrees", fitted.width, step as f64 / 2.0);
                assert!(darkest < 0.7, "{at}: darkest {darkest}");
                assert!((2.0..4.0).contains(&width), "{at}: width {width}");
            }
        }
    }

    #[test]
    fn averaging_shares_each_cell_among_the_pixels_it_covers() {
        let shares = area_shares(5, 2);
        assert_eq!(shares[0], vec![(0, 0.4), (1, 0.4), (2, 0.2)]);
        assert_eq!(shares[1], vec![(2, 0.2), (3, 0.4), (4, 0.4)]);
        assert_eq!(area_shares(3, 3)[1], vec![(1, 1.0)]);
    }

    #[test]
    fn a_y_up_arena_lays_its_texture_on_the_converted_floor() {
        // R2021a: floorSize is (x, z) of the Y-up PROTO, 2 m along north (ENU -y), 1 m along
        // east; the texture is laid along the PROTO's own x (ENU -y) and -z (ENU x).
        let import = WbtImport::from_text(
            "#VRML_SIM R2021a utf8
RectangleArena { floorSize 2 1 floorTileSize 1 0.5 floorAppearance Appearance { texture ImageTexture { url [\"t.png\"] } } }\n",
            "old.wbt",
        )
        .unwrap();
        let texture = &import.floor_textures[0];
        assert_eq!(texture.size, [2.0, 1.0]);
        assert_eq!(texture.tile, [1.0, 0.5]);
        assert!((texture.yaw + std::f64::consts::FRAC_PI_2).abs() < 1e-6);
        assert_eq!(texture.center, [0.0, 0.0]);
        assert_eq!(texture.candidates, ["t.png", "textures/t.png"]);
    }

    /// A world whose floor is a `RectangleArena` saved as base nodes: a Solid bounded by a
    /// Plane, its Shape a textured quad drawing the image `u` times across (`uv` is "u v").
    fn converted_floor(uv: &str, points: &str) -> WbtImport {
        WbtImport::from_text(
            &format!(
                "#VRML_SIM R2025a utf8
Solid {{ translation 0.3 0.25 0 children [ Solid {{ children [ Shape {{
  appearance PBRAppearance {{ baseColorMap ImageTexture {{ url [\"../track.png\"] }} textureTransform TextureTransform {{ scale 0.5 0.5 }} }}
  geometry IndexedFaceSet {{ coord Coordinate {{ point [ {points} ] }}
    texCoord TextureCoordinate {{ point [ 0 0, {uv} ] }}
    coordIndex [ 2, 0, 1, 3, -1 ] texCoordIndex [ 2, 0, 1, 3, -1 ] }} }} ]
  boundingObject Plane {{ }} }} ] }}
"
            ),
            "line.wbt",
        )
        .unwrap()
    }

    #[test]
    fn a_floor_saved_as_a_textured_quad_lays_its_image_as_the_arena_did() {
        // Texture coordinates 0..2 scaled by 0.5: the image once over the 1 m floor.
        let import = converted_floor(
            "2 0, 0 2, 2 2",
            "-0.5 -0.5 0, 0.5 -0.5 0, -0.5 0.5 0, 0.5 0.5 0",
        );
        assert_eq!(import.floor_textures.len(), 1, "{:?}", import.warnings);
        let texture = &import.floor_textures[0];
        assert_eq!(texture.center, [0.3, 0.25]);
        assert_eq!(texture.size, [1.0, 1.0]);
        assert_eq!(texture.tile, [1.0, 1.0]);
        assert!(texture.yaw.abs() < 1e-9);
        assert_eq!(texture.candidates[0], "../track.png");
        // Four images along x, one along y on a 2 x 1 m quad turned a quarter: its image's x
        // runs along the world's y.
        let import = converted_floor("8 0, 0 2, 8 2", "0 0 0, 0 2 0, -1 0 0, -1 2 0");
        let texture = &import.floor_textures[0];
        assert_eq!(texture.size, [2.0, 1.0]);
        assert_eq!(texture.tile, [0.5, 1.0]);
        assert!((texture.yaw - std::f64::consts::FRAC_PI_2).abs() < 1e-9);
        assert_eq!(texture.center, [-0.2, 1.25]);
    }

    #[test]
    fn a_textured_quad_that_is_not_a_floor_rectangle_lays_no_image() {
        // Mirrored (u runs towards -x), sheared, and raised 5 cm above the floor.
        for (uv, points) in [
            (
                "2 0, 0 2, 2 2",
                "0.5 -0.5 0, -0.5 -0.5 0, 0.5 0.5 0, -0.5 0.5 0",
            ),
            (
                "2 0, 0 2, 2 2",
                "-0.5 -0.5 0, 0.5 -0.5 0, -0.3 0.5 0, 0.7 0.5 0",
            ),
            (
                "2 0, 0 2, 2 2",
                "-0.5 -0.5 0.05, 0.5 -0.5 0.05, -0.5 0.5 0.05, 0.5 0.5 0.05",
            ),
        ] {
            assert!(
                converted_floor(uv, points).floor_textures.is_empty(),
                "{points}"
            );
        }
    }

    #[test]
    fn a_missing_image_leaves_the_floor_bare_and_lists_the_files_to_look_for() {
        let mut import = WbtImport::from_text(
            "#VRML_SIM R2023b utf8\nRectangleArena { floorAppearance PBRAppearance { baseColorMap ImageTexture { url [\"textures/track.png\"] } } }\n",
            "/worlds/line.wbt",
        )
        .unwrap();
        assert_eq!(import.floor_textures.len(), 1);
        assert!(import.floor_textures[0]
            .candidates
            .contains(&"/worlds/textures/track.png".to_string()));
        import.paint_floor(&BTreeMap::new());
        assert!(import.paint.is_empty());
    }
}
