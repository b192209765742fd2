//! The colours a camera sees: each collision shape keeps the colour of its Solid's visible
//! shapes, each floor mark the colour of its shape, and the floor the colour of a
//! `RectangleArena`'s `floorAppearance` or a `Floor`'s `appearance`.
//!
//! Webots draws a `PBRAppearance` in its `baseColor` (default white) and an `Appearance` in its
//! `Material`'s `diffuseColor` (default 0.8 grey; white, unlit, without a material); a node's
//! `emissiveColor` adds to either (Webots' reference manual, PBRAppearance, Appearance and
//! Material). A texture multiplies that colour by the image's: a textured appearance gives the
//! colour of its image's mean colour (which the caller reads and hands in) times its own
//! colour, and none while the image is not given. An appearance PROTO (`BrushedAluminium`, `Roughcast`,
//! `Parquetry`...) multiplies its texture by its `colorOverride` (Webots' guide, Appearances):
//! the colour the instance writes there is taken, the texture counted as white; without one it
//! gives no colour. A shape without a colour is drawn in the grey of its reflection factor.
//!
//! Webots' infra-red sensors divide the distance a ray runs by the reflection factor
//! `f = 0.2 + 0.8 red (1 - 0.5 roughness) (1 - 0.5 occlusion)` of the shape it meets (reference
//! manual, DistanceSensor, "Infra-Red Sensors"), where `red` is the red of the colour the ray
//! picks (`WbShape::pickColor` in Webots' source): a `PBRAppearance`'s `baseColor` times
//! `1 - transparency`, with its `roughness`; an `Appearance`'s `Material.diffuseColor` (white
//! without a material, or with a texture) times `1 - transparency`, with roughness 0; no
//! appearance, white. Emission does not count. The colour is multiplied by a texture's, which
//! the import does not read, nor an occlusion map's value (taken as 0): a texture is counted
//! white, so the factor is the highest the texture allows. An appearance PROTO gives the red of
//! its `colorOverride` (white without one), roughness 0.
//!
//! A collision shape reflects by its appearance when a camera sees its colour; one without a
//! colour keeps the factor 1 of a white surface. A wall whose first visible shape is textured
//! (an `ImageTexture` of a `PBRAppearance`'s `baseColorMap` or an `Appearance`'s `texture`) is
//! listed with its texture ([`WallTexture`]): when the caller reads the image (as floor
//! textures are read) and hands in its mean colour, [`WbtImport::shade_walls`] gives the wall
//! the factor of that colour's red times the appearance's own (the texture's colour multiplies
//! the appearance's, as Webots picks it), with the appearance's roughness, and the camera's
//! colour of that mean colour times the appearance's; without the image the wall stays white
//! to the sensors and a camera sees the appearance's own colour (the texture counted white). A
//! `Wall`'s, a `SolidBox`'s or a `RectangleArena`'s textured appearance field is listed the
//! same way. The floor of a colour read reflects by its appearance too (a white floor of
//! `roughness 1`, 0.6); one of no colour read (a texture, an appearance PROTO), as white.

use std::collections::BTreeMap;

use super::frames::Frame;
use super::import::Importer;
use super::tree::Node;
use super::WbtImport;

/// Most nodes looked through for a Solid's first visible shape.
const MAX_LOOKS: usize = 10_000;

/// How a collision shape looks to a camera and to the infra-red sensors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Look {
    /// The colour a camera sees (`None`: the grey of `reflectance`).
    pub colour: Option<[f64; 3]>,
    /// The reflection factor of Webots' infra-red sensors (see the module).
    pub reflectance: f64,
    /// The index of its texture in [`WbtImport::wall_textures`], for a textured shape whose
    /// colour the import does not read.
    pub texture: Option<usize>,
}

/// An image texture of a wall's appearance, as found in the world (see the module).
#[derive(Debug, Clone, PartialEq)]
pub struct WallTexture {
    /// The `url` entries of the `ImageTexture`, in order.
    pub urls: Vec<String>,
    /// `line L: Shape` of the textured shape.
    pub owner: String,
    /// The red the appearance gives a white texture (its colour's red times `1 -
    /// transparency`), which the image's mean red multiplies.
    pub red: f64,
    /// The colour the appearance gives a white texture as a camera sees it (a
    /// `PBRAppearance`'s `baseColor`; white for an `Appearance`, whose texture replaces its
    /// material's diffuse colour), which the image's mean colour multiplies.
    pub colour: [f64; 3],
    /// The appearance's roughness.
    pub roughness: f64,
    /// Files to look for, in order, as a floor texture's.
    pub candidates: Vec<String>,
}

/// How a movable body looks to a camera: its colour (`None`: the grey of its reflectance),
/// whether its collision shape is one `Sphere` (a ball, which a camera draws as one) and how
/// high it stands on the floor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyLook {
    /// The colour a camera sees, as [`Look::colour`].
    pub colour: Option<[f64; 3]>,
    /// Whether the body is a ball resting on the floor (its disc's radius is the sphere's).
    pub sphere: bool,
    /// The vertical extent of its collision shape (m): a box or cylinder is drawn this high,
    /// standing on the floor.
    pub height: f64,
}

impl Look {
    /// A shape whose colour the import does not read: white to the infra-red sensors.
    pub const UNREAD: Look = Look {
        colour: None,
        reflectance: 1.0,
        texture: None,
    };
}

/// The reflection factor Webots' infra-red sensors give a surface of `red` (the picked colour's
/// red, transparency applied), `roughness` and `occlusion`, each clamped to [0, 1].
pub fn reflection_factor(red: f64, roughness: f64, occlusion: f64) -> f64 {
    let unit = |x: f64| {
        if x.is_finite() {
            x.clamp(0.0, 1.0)
        } else {
            0.0
        }
    };
    0.2 + 0.8 * unit(red) * (1.0 - 0.5 * unit(roughness)) * (1.0 - 0.5 * unit(occlusion))
}

impl<'d> Importer<'d> {
    /// The colour of an appearance node as a camera sees it, or `None` (see the module).
    pub fn appearance_node_colour(&mut self, appearance: &'d Node) -> Option<[f64; 3]> {
        let (base, emissive) = match appearance.type_name.as_str() {
            "PBRAppearance" => {
                if !self.nodes(appearance, "baseColorMap").is_empty() {
                    return None;
                }
                (
                    self.vector(appearance, "baseColor", [1.0; 3]),
                    self.vector(appearance, "emissiveColor", [0.0; 3]),
                )
            }
            "Appearance" => {
                if !self.nodes(appearance, "texture").is_empty() {
                    return None;
                }
                match self.nodes(appearance, "material").first() {
                    Some(&material) => {
                        let material = self.node(material);
                        (
                            self.vector(material, "diffuseColor", [0.8; 3]),
                            self.vector(material, "emissiveColor", [0.0; 3]),
                        )
                    }
                    None => ([1.0; 3], [0.0; 3]),
                }
            }
            _ => {
                appearance.field("colorOverride")?;
                (self.vector(appearance, "colorOverride", [1.0; 3]), [0.0; 3])
            }
        };
        let colour = [0, 1, 2].map(|i| (base[i] + emissive[i]).clamp(0.0, 1.0));
        colour.iter().all(|c| c.is_finite()).then_some(colour)
    }

    /// The reflection factor Webots' infra-red sensors give a shape of an appearance node (see
    /// the module).
    pub fn appearance_node_reflectance(&mut self, appearance: &'d Node) -> f64 {
        let (red, roughness) = self.appearance_red(appearance);
        reflection_factor(red, roughness, 0.0)
    }

    /// The red an appearance node gives the infra-red sensors (a texture counted white) and
    /// its roughness (see the module).
    pub(super) fn appearance_red(&mut self, appearance: &'d Node) -> (f64, f64) {
        match appearance.type_name.as_str() {
            "PBRAppearance" => {
                let base = self.vector(appearance, "baseColor", [1.0; 3])[0];
                let transparency = self.number(appearance, "transparency", 0.0);
                let roughness = self.number(appearance, "roughness", 0.0);
                (base * (1.0 - transparency), roughness)
            }
            "Appearance" => match self.nodes(appearance, "material").first() {
                Some(&material) => {
                    let material = self.node(material);
                    let diffuse = if self.nodes(appearance, "texture").is_empty() {
                        self.vector(material, "diffuseColor", [0.8; 3])[0]
                    } else {
                        1.0
                    };
                    let transparency = self.number(material, "transparency", 0.0);
                    (diffuse * (1.0 - transparency), 0.0)
                }
                None => (1.0, 0.0),
            },
            _ => (self.vector(appearance, "colorOverride", [1.0; 3])[0], 0.0),
        }
    }

    /// The look of a node whose appearance field `field` (a Shape's `appearance`, a `Wall`'s
    /// or a `SolidBox`'s) is a `PBRAppearance` or an `Appearance` with an `ImageTexture` of a
    /// url: its texture listed in `wall_textures`; until [`WbtImport::shade_walls`] gives it
    /// the image's colour, the camera sees the appearance's own colour (the texture counted
    /// white, as the infra-red sensors count it; none for white) and the sensors a white
    /// surface.
    fn textured_look(&mut self, holder: &'d Node, field: &str) -> Option<Look> {
        let &appearance = self.nodes(holder, field).first()?;
        let appearance = self.node(appearance);
        let texture_field = match appearance.type_name.as_str() {
            "PBRAppearance" => "baseColorMap",
            "Appearance" => "texture",
            _ => return None,
        };
        let urls = self.image_texture_urls(appearance, texture_field)?;
        let (red, roughness) = self.appearance_red(appearance);
        let colour = if texture_field == "baseColorMap" {
            self.vector(appearance, "baseColor", [1.0; 3])
        } else {
            [1.0; 3]
        };
        let owner = self.label(holder);
        self.wall_textures.push(WallTexture {
            urls,
            owner,
            red,
            colour,
            roughness,
            candidates: Vec::new(),
        });
        let seen = colour.map(|c| {
            if c.is_finite() {
                c.clamp(0.0, 1.0)
            } else {
                1.0
            }
        });
        // White, which a camera draws as the grey of a white wall, stays no colour.
        Some(Look {
            colour: (seen != [1.0; 3]).then_some(seen),
            texture: Some(self.wall_textures.len() - 1),
            ..Look::UNREAD
        })
    }

    /// The reflection factor of a Shape's appearance (1, white, without one).
    pub fn shape_reflectance(&mut self, shape: &'d Node) -> f64 {
        match self.nodes(shape, "appearance").first() {
            Some(&appearance) => self.appearance_node_reflectance(self.node(appearance)),
            None => 1.0,
        }
    }

    /// The colour of a node's appearance field `field` (a Shape's `appearance`, a PROTO's
    /// `wallAppearance`...), or `None`.
    pub fn field_colour(&mut self, node: &'d Node, field: &str) -> Option<[f64; 3]> {
        let &appearance = self.nodes(node, field).first()?;
        self.appearance_node_colour(self.node(appearance))
    }

    /// The look of a node's appearance field `field` when a camera sees its colour, with the
    /// reflection factor of that appearance.
    pub fn field_look(&mut self, node: &'d Node, field: &str) -> Option<Look> {
        let &appearance = self.nodes(node, field).first()?;
        let appearance = self.node(appearance);
        let colour = self.appearance_node_colour(appearance)?;
        Some(Look {
            colour: Some(colour),
            reflectance: self.appearance_node_reflectance(appearance),
            texture: None,
        })
    }

    /// How a Solid (or a plain robot) looks: as the first of its visible shapes whose colour a
    /// camera sees (its `children`, through `Pose`, `Transform` and `Group`, not into other
    /// Solids), else as its `boundingObject` when that is a `Shape` with one, else
    /// [`Look::UNREAD`].
    pub fn solid_look(&mut self, solid: &'d Node) -> Look {
        self.solid_seen_look(solid).unwrap_or(Look::UNREAD)
    }

    fn solid_seen_look(&mut self, solid: &'d Node) -> Option<Look> {
        let mut textured = None;
        let look = self.solid_coloured_look(solid, &mut textured);
        look.or(textured)
    }

    /// [`Importer::solid_look`] of the shapes whose colour a camera sees; the look of the
    /// first textured shape met on the way goes into `textured`.
    fn solid_coloured_look(
        &mut self,
        solid: &'d Node,
        textured: &mut Option<Look>,
    ) -> Option<Look> {
        let mut stack: Vec<&'d Node> = self
            .nodes(solid, "children")
            .iter()
            .rev()
            .map(|&id| self.node(id))
            .collect();
        let mut looks = 0;
        while let Some(node) = stack.pop() {
            looks += 1;
            if looks > MAX_LOOKS {
                break;
            }
            match node.type_name.as_str() {
                "Shape" => {
                    if let Some(look) = self.field_look(node, "appearance") {
                        return Some(look);
                    }
                    if textured.is_none() {
                        *textured = self.textured_look(node, "appearance");
                    }
                }
                "Pose" | "Transform" | "Group" => {
                    let children = self.nodes(node, "children");
                    stack.extend(children.iter().rev().map(|&id| self.node(id)));
                }
                _ => {}
            }
        }
        let &bounding = self.nodes(solid, "boundingObject").first()?;
        let bounding = self.node(bounding);
        if bounding.type_name == "Shape" {
            let look = self.field_look(bounding, "appearance");
            if look.is_none() && textured.is_none() {
                *textured = self.textured_look(bounding, "appearance");
            }
            return look;
        }
        None
    }

    /// How a known PROTO's collision boxes look: as a `RectangleArena`'s `wallAppearance`, a
    /// `Wall`'s or a `SolidBox`'s `appearance`, a textured one as a textured Shape's (their
    /// defaults, left out of the instance, are textured PROTOs: no colour, white).
    pub fn proto_look(&mut self, node: &'d Node) -> Look {
        let field = match node.type_name.as_str() {
            "RectangleArena" => "wallAppearance",
            "Wall" | "SolidBox" => "appearance",
            _ => return Look::UNREAD,
        };
        let look = self.field_look(node, field);
        look.or_else(|| self.textured_look(node, field))
            .unwrap_or(Look::UNREAD)
    }

    /// The look of a floor (a `RectangleArena`'s `floorAppearance`, a `Floor`'s `appearance`,
    /// `size` along `frame`'s x and y): the world's first floor gives the floor its colour and
    /// reflection factor when the import reads them (else the floor stays white); a later one
    /// of a colour read lies on it as a floor mark of its rectangle (a patch of black floor a
    /// maze lays in its middle for the ground sensors to find).
    pub fn floor_look_of(&mut self, node: &'d Node, field: &str, frame: &Frame, size: [f64; 2]) {
        let look = self.field_look(node, field);
        if !self.floor_seen {
            self.floor_seen = true;
            if let Some(look) = look {
                self.floor_colour = look.colour;
                self.floor_reflectance = Some(look.reflectance);
            }
            return;
        }
        let Some(look) = look else {
            return;
        };
        self.mark_rectangle(frame, size, look.reflectance, look.colour);
    }
}

impl WbtImport {
    /// Gives each textured wall the look of its texture's image, given as the image's mean
    /// colour (red, green, blue in [0, 1]) keyed by the candidate file it was read from (the
    /// first candidate found counts): the reflection factor `f = 0.2 + 0.8 (mean red x the
    /// appearance's red) (1 - 0.5 roughness)` and the colour a camera sees, the mean colour
    /// times the appearance's. A wall whose texture has no image stays white (drawn by a camera as
    /// a white wall is, unless its appearance has a colour of its own). Call it once, after the import.
    pub fn shade_walls(&mut self, mean_colours: &BTreeMap<String, [f64; 3]>) {
        let shades: Vec<Option<Look>> = self
            .wall_textures
            .iter()
            .enumerate()
            .map(|(index, texture)| {
                let mean = texture
                    .candidates
                    .iter()
                    .find_map(|c| mean_colours.get(c))?;
                let colour = [0, 1, 2].map(|i| (mean[i] * texture.colour[i]).clamp(0.0, 1.0));
                Some(Look {
                    colour: colour.iter().all(|c| c.is_finite()).then_some(colour),
                    reflectance: reflection_factor(mean[0] * texture.red, texture.roughness, 0.0),
                    texture: Some(index),
                })
            })
            .collect();
        let looks = self.obstacle_looks.iter_mut().chain(&mut self.sensed_looks);
        for look in looks {
            if let Some(Some(shade)) = look.texture.and_then(|k| shades.get(k)) {
                *look = *shade;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{reflection_factor, BodyLook, Look};
    use crate::wbt::WbtImport;
    use crate::world::spec::{BodySpec, PaintSpec};

    fn import(text: &str) -> WbtImport {
        WbtImport::from_text(text, "test.wbt").unwrap_or_else(|e| panic!("{e}"))
    }

    fn look_with(appearance: &str) -> Look {
        let w = import(&format!(
            "#VRML_SIM R2023b utf8\nSolid {{ translation 0.3 0 0.05 children [ Shape {{ \
             {appearance} geometry Box {{ size 0.1 0.1 0.1 }} }} ] \
             boundingObject Box {{ size 0.1 0.1 0.1 }} }}\n"
        ));
        assert_eq!(w.obstacles.len(), 1);
        let look = w.obstacle_looks[0];
        let wall = &w.to_spec("look").walls[0];
        assert_eq!(wall.reflectance.0, look.reflectance);
        look
    }

    fn solid_with(appearance: &str) -> Option<[f64; 3]> {
        look_with(appearance).colour
    }

    fn reflectance_with(appearance: &str) -> f64 {
        look_with(appearance).reflectance
    }

    #[test]
    fn a_textured_wall_reflects_by_its_image_s_mean_red_once_given() {
        let mut w = import(
            "#VRML_SIM R2023b utf8\nSolid { translation 0.3 0 0.05 children [ Shape { \
             appearance PBRAppearance { baseColor 0.5 1 1 roughness 1 baseColorMap ImageTexture { \
             url [ \"bricks.png\" ] } } geometry Box { size 0.1 0.1 0.1 } } ] \
             boundingObject Box { size 0.1 0.1 0.1 } }\n",
        );
        let [texture] = w.wall_textures.as_slice() else {
            panic!("{:?}", w.wall_textures)
        };
        assert_eq!(texture.urls, ["bricks.png"]);
        assert_eq!(texture.candidates, ["bricks.png", "textures/bricks.png"]);
        assert_eq!((texture.red, texture.roughness), (0.5, 1.0));
        // Without its image the wall is white to the sensors, and a camera sees the
        // appearance's own colour (the texture counted white).
        assert_eq!(w.obstacle_looks[0].reflectance, 1.0);
        assert_eq!(w.obstacle_looks[0].colour, Some([0.5, 1.0, 1.0]));
        let other = [("elsewhere.png".to_string(), [0.0; 3])]
            .into_iter()
            .collect();
        w.shade_walls(&other);
        assert_eq!(w.obstacle_looks[0].reflectance, 1.0);
        let found = [("textures/bricks.png".to_string(), [0.8, 0.4, 0.2])]
            .into_iter()
            .collect();
        w.shade_walls(&found);
        // 0.2 + 0.8 * (0.8 * 0.5) * (1 - 0.5 * 1).
        assert!((w.obstacle_looks[0].reflectance - 0.36).abs() < 1e-12);
        // The camera sees the image's mean colour times the base colour (0.5 1 1).
        assert_eq!(w.obstacle_looks[0].colour, Some([0.4, 0.4, 0.2]));
        assert!((w.to_spec("textured").walls[0].reflectance.0 - 0.36).abs() < 1e-12);
    }

    #[test]
    fn the_reflection_factor_is_webots_infra_red_formula() {
        assert_eq!(reflection_factor(1.0, 0.0, 0.0), 1.0);
        assert_eq!(reflection_factor(0.0, 1.0, 1.0), 0.2);
        assert!((reflection_factor(0.5, 1.0, 0.0) - 0.4).abs() < 1e-12);
        // The E-puck's shell: grey 0.5 at transparency 0.4, roughness 0.5.
        assert!((reflection_factor(0.5 * 0.6, 0.5, 0.0) - 0.38).abs() < 1e-12);
        assert!((reflection_factor(1.0, 0.0, 1.0) - 0.6).abs() < 1e-12);
        assert_eq!(reflection_factor(f64::NAN, 2.0, -1.0), 0.2);
    }

    #[test]
    fn a_wall_reflects_by_its_red_transparency_and_roughness() {
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
        assert_eq!(
            reflectance_with("appearance PBRAppearance { baseColor 1 0 0 }"),
            1.0
        );
        assert!(close(
            reflectance_with("appearance PBRAppearance { baseColor 0.5 0.5 0.5 roughness 1 }"),
            0.4
        ));
        assert!(close(
            reflectance_with("appearance PBRAppearance { baseColor 0 1 1 emissiveColor 1 0 0 }"),
            0.2
        ));
        assert!(close(
            reflectance_with("appearance PBRAppearance { transparency 0.5 roughness 0.5 }"),
            0.5
        ));
        // A Material has no roughness: Webots picks 0 for it.
        assert!(close(
            reflectance_with(
                "appearance Appearance { material Material { diffuseColor 0.5 0 0 transparency 0.5 } }"
            ),
            0.4
        ));
        assert!(close(
            reflectance_with("appearance Appearance { material Material { } }"),
            0.84
        ));
        assert!(close(
            reflectance_with("appearance Roughcast { colorOverride 0.25 0.25 0.25 }"),
            0.4
        ));
        // What gives no colour keeps the factor of a white surface.
        for unread in [
            "",
            "appearance PBRAppearance { baseColor 0 0 0 roughness 1 baseColorMap ImageTexture { } }",
            "appearance Parquetry { }",
        ] {
            assert_eq!(look_with(unread), Look::UNREAD, "{unread}");
        }
    }

    #[test]
    fn a_movable_body_and_a_floor_mark_reflect_by_their_appearance() {
        let w = import(
            "#VRML_SIM R2023b utf8\n\
             Solid { translation 0.3 0 0.05 children [ Shape { \
               appearance PBRAppearance { baseColor 0.5 0.5 0.5 roughness 1 } \
               geometry Sphere { radius 0.05 } } ] \
               boundingObject Sphere { radius 0.05 } physics Physics { } }\n\
             Pose { translation -0.2 0 0.0005 children [ Shape { \
               appearance PBRAppearance { baseColor 1 1 1 roughness 1 transparency 0.5 } \
               geometry Box { size 0.1 0.1 0.001 } } ] }\n",
        );
        let [BodySpec::Circle { reflectance, .. }] = w.bodies.as_slice() else {
            panic!("one ball: {:?}", w.bodies);
        };
        assert!((reflectance.0 - 0.4).abs() < 1e-12);
        let [PaintSpec::Rect { reflectance, .. }] = w.paint.as_slice() else {
            panic!("one mark: {:?}", w.paint);
        };
        assert!((reflectance.0 - 0.4).abs() < 1e-12);
    }

    #[test]
    fn a_pbr_appearance_gives_its_base_colour_and_emission_adds() {
        assert_eq!(
            solid_with("appearance PBRAppearance { baseColor 1 0 0 roughness 1 }"),
            Some([1.0, 0.0, 0.0])
        );
        assert_eq!(
            solid_with("appearance PBRAppearance { baseColor 0.5 0 0 emissiveColor 0.7 0 0.25 }"),
            Some([1.0, 0.0, 0.25])
        );
        // Default base colour: white.
        assert_eq!(solid_with("appearance PBRAppearance { }"), Some([1.0; 3]));
    }

    #[test]
    fn an_appearance_gives_its_material_diffuse_colour() {
        assert_eq!(
            solid_with("appearance Appearance { material Material { diffuseColor 0 1 0 } }"),
            Some([0.0, 1.0, 0.0])
        );
        assert_eq!(
            solid_with("appearance Appearance { material Material { } }"),
            Some([0.8; 3])
        );
        assert_eq!(solid_with("appearance Appearance { }"), Some([1.0; 3]));
    }

    #[test]
    fn no_appearance_or_an_unknown_proto_give_no_colour_a_texture_its_appearance_s() {
        assert_eq!(solid_with(""), None);
        assert_eq!(
            solid_with(
                "appearance PBRAppearance { baseColor 1 0 0 baseColorMap ImageTexture { url [ \"a.png\" ] } }"
            ),
            Some([1.0, 0.0, 0.0])
        );
        assert_eq!(
            solid_with(
                "appearance Appearance { material Material { diffuseColor 0 1 0 } texture ImageTexture { url [ \"a.png\" ] } }"
            ),
            None
        );
        assert_eq!(solid_with("appearance Parquetry { }"), None);
        assert_eq!(
            solid_with("appearance Roughcast { colorOverride 0 0 1 }"),
            Some([0.0, 0.0, 1.0])
        );
    }

    #[test]
    fn a_textured_solid_box_or_wall_is_listed_with_its_texture_and_seen_in_its_colour() {
        // A textured appearance in a PROTO's field lost its colour and its texture: the box was
        // grey to a camera and its image never read.
        let mut w = import(
            "#VRML_SIM R2023b utf8\nSolidBox { translation 0.3 0 0.05 size 0.1 0.1 0.1 \
             appearance PBRAppearance { baseColor 1 0 0 baseColorMap ImageTexture { \
             url [ \"tag.jpg\" ] } } }\nWall { translation -0.3 0 0 size 0.01 0.5 0.1 \
             appearance PBRAppearance { baseColor 0 0 1 roughness 1 baseColorMap ImageTexture { \
             url [ \"bricks.png\" ] } } }\n",
        );
        let urls: Vec<_> = w.wall_textures.iter().map(|t| t.urls.clone()).collect();
        assert_eq!(urls, [["tag.jpg"], ["bricks.png"]]);
        let colours: Vec<_> = w.obstacle_looks.iter().map(|l| l.colour).collect();
        assert_eq!(colours, [Some([1.0, 0.0, 0.0]), Some([0.0, 0.0, 1.0])]);
        let grey = [("tag.jpg".to_string(), [0.5; 3])].into_iter().collect();
        w.shade_walls(&grey);
        assert_eq!(w.obstacle_looks[0].colour, Some([0.5, 0.0, 0.0]));
        assert_eq!(w.obstacle_looks[1].colour, Some([0.0, 0.0, 1.0]));
    }

    #[test]
    fn protos_and_floors_keep_the_colours_their_fields_give() {
        let w = import(
            "#VRML_SIM R2023b utf8\n\
             RectangleArena { floorSize 1 1 floorAppearance PBRAppearance { baseColor 0 0 1 } \
               wallAppearance PBRAppearance { baseColor 0 1 0 } }\n\
             SolidBox { translation 0.2 0 0.05 size 0.1 0.1 0.1 \
               appearance PBRAppearance { baseColor 1 0 0 } }\n\
             Wall { translation -0.3 0 0 size 0.01 0.2 0.1 }\n",
        );
        assert_eq!(w.floor_colour, Some([0.0, 0.0, 1.0]));
        assert_eq!(w.obstacles.len(), 6);
        assert!(w.obstacle_looks[..4]
            .iter()
            .all(|l| l.colour == Some([0.0, 1.0, 0.0])));
        assert_eq!(w.obstacle_looks[4].colour, Some([1.0, 0.0, 0.0]));
        assert_eq!(w.obstacle_looks[5].colour, None);
        let world = w.to_world("colours").unwrap();
        let colours = world.wall_colours();
        assert_eq!(colours.len(), 6);
        assert_eq!(colours[4], Some([1.0, 0.0, 0.0]));
        assert_eq!(world.floor_colour(), Some([0.0, 0.0, 1.0]));
    }

    #[test]
    fn a_floor_of_a_colour_read_reflects_by_its_red_and_roughness() {
        // Webots' factor for the floor's own shape: white of roughness 1, 0.6; a floor of no
        // colour read (the default Parquetry), white.
        for (appearance, factor) in [
            (
                "PBRAppearance { baseColor 1 1 1 roughness 1 metalness 0 }",
                0.6,
            ),
            ("PBRAppearance { baseColor 0.5 0.5 0.5 }", 0.6),
            ("PBRAppearance { }", 1.0),
            ("Parquetry { }", 1.0),
        ] {
            let w = import(&format!(
                "#VRML_SIM R2023b utf8\nRectangleArena {{ floorSize 1 1 floorAppearance {appearance} }}\n"
            ));
            let world = w.to_world("floor").unwrap();
            let read = world.floor().reflectance_at([0.1, 0.1]);
            assert!((read - factor).abs() < 1e-12, "{appearance}: {read}");
        }
    }

    #[test]
    fn a_later_floor_of_a_colour_read_is_a_patch_on_the_first() {
        // A maze on a Parquetry arena (its colour not read: white) with a black chequered
        // Floor 25 cm square in its middle, where the ground sensors find the goal.
        let w = import(
            "#VRML_SIM R2023b utf8\n\
             RectangleArena { floorSize 2 2 }\n\
             Floor { translation 0.5 0 0.0001 size 0.25 0.25 \
               appearance Parquetry { type \"chequered\" colorOverride 0 0 0 } }\n",
        );
        assert_eq!(w.floor_colour, None);
        assert!(
            !w.warnings.iter().any(|m| m.contains("left bare")),
            "{:?}",
            w.warnings
        );
        let world = w.to_world("patch").unwrap();
        let floor = world.floor();
        assert!((floor.reflectance_at([0.5, 0.1]) - 0.2).abs() < 1e-12);
        assert!((floor.reflectance_at([0.5, 0.2]) - 1.0).abs() < 1e-12);
        assert!((floor.reflectance_at([0.0, 0.0]) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_coloured_floor_mark_keeps_its_colour() {
        let w = import(
            "#VRML_SIM R2023b utf8\n\
             Pose { translation 0.2 0 0.0005 children [ Shape { \
               appearance PBRAppearance { baseColor 1 0 1 } geometry Box { size 0.1 0.1 0.001 } } ] }\n",
        );
        assert_eq!(w.paint.len(), 1);
        let world = w.to_world("mark").unwrap();
        assert_eq!(world.paint_colour(0), Some([1.0, 0.0, 1.0]));
        assert_eq!(world.paint_colour(1), None);
    }

    #[test]
    fn a_ball_with_physics_keeps_its_colour_and_a_box_is_no_sphere() {
        let w = import(
            "#VRML_SIM R2023b utf8\n\
             Solid { translation 0.2 0 0.02 children [ Shape { appearance PBRAppearance { \
               baseColor 0 0 1 } geometry DEF S Sphere { radius 0.02 } } ] \
               boundingObject USE S physics Physics { mass 0.05 } }\n\
             Solid { translation -0.2 0 0.02 boundingObject Box { size 0.04 0.04 0.04 } \
               physics Physics { mass 0.05 } }\n",
        );
        assert_eq!(w.bodies.len(), 2);
        assert_eq!(
            w.body_looks,
            [
                BodyLook {
                    colour: Some([0.0, 0.0, 1.0]),
                    sphere: true,
                    height: 0.04
                },
                BodyLook {
                    colour: None,
                    sphere: false,
                    height: 0.04
                }
            ]
        );
    }
}
