//! The colours a camera sees: each collision shape keeps the colour of its Solid's visible
//! shapes, each floor mark the colour of its shape, and the floor the colour of a
//! `RectangleArena`'s `floorAppearance` or a `Floor`'s `appearance`.
//!
//! Webots draws a `PBRAppearance` in its `baseColor` (default white) and an `Appearance` in its
//! `Material`'s `diffuseColor` (default 0.8 grey; white, unlit, without a material); a node's
//! `emissiveColor` adds to either (Webots' reference manual, PBRAppearance, Appearance and
//! Material). A texture multiplies that colour by the image's, which the import does not read:
//! a textured appearance gives no colour. An appearance PROTO (`BrushedAluminium`, `Roughcast`,
//! `Parquetry`...) multiplies its texture by its `colorOverride` (Webots' guide, Appearances):
//! the colour the instance writes there is taken, the texture counted as white; without one it
//! gives no colour. A shape without a colour is drawn in the grey of its reflection factor.

use super::import::Importer;
use super::tree::Node;

/// Most nodes looked through for a Solid's first visible shape.
const MAX_LOOKS: usize = 10_000;

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

    /// The colour of a node's appearance field `field` (a Shape's `appearance`, a PROTO's
    /// `wallAppearance`...), or `None`.
    pub fn field_colour(&mut self, node: &'d Node, field: &str) -> Option<[f64; 3]> {
        let &appearance = self.nodes(node, field).first()?;
        self.appearance_node_colour(self.node(appearance))
    }

    /// The colour of a Solid (or a plain robot) as a camera sees it: that of the first of its
    /// visible shapes that has one (its `children`, through `Pose`, `Transform` and `Group`,
    /// not into other Solids), else of its `boundingObject` when that is a `Shape`.
    pub fn solid_colour(&mut self, solid: &'d Node) -> Option<[f64; 3]> {
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
                    if let Some(colour) = self.field_colour(node, "appearance") {
                        return Some(colour);
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
            return self.field_colour(bounding, "appearance");
        }
        None
    }

    /// The colour of a known PROTO's collision boxes: a `RectangleArena`'s `wallAppearance`, a
    /// `Wall`'s or a `SolidBox`'s `appearance` (their defaults are textured: no colour).
    pub fn proto_colour(&mut self, node: &'d Node) -> Option<[f64; 3]> {
        match node.type_name.as_str() {
            "RectangleArena" => self.field_colour(node, "wallAppearance"),
            "Wall" | "SolidBox" => self.field_colour(node, "appearance"),
            _ => None,
        }
    }

    /// Keeps the first floor colour the world gives (a `RectangleArena`'s `floorAppearance`, a
    /// `Floor`'s `appearance`).
    pub fn floor_colour_of(&mut self, node: &'d Node, field: &str) {
        if self.floor_colour.is_none() {
            self.floor_colour = self.field_colour(node, field);
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::wbt::WbtImport;

    fn import(text: &str) -> WbtImport {
        WbtImport::from_text(text, "test.wbt").unwrap_or_else(|e| panic!("{e}"))
    }

    fn solid_with(appearance: &str) -> Option<[f64; 3]> {
        let w = import(&format!(
            "#VRML_SIM R2023b utf8\nSolid {{ translation 0.3 0 0.05 children [ Shape {{ \
             {appearance} geometry Box {{ size 0.1 0.1 0.1 }} }} ] \
             boundingObject Box {{ size 0.1 0.1 0.1 }} }}\n"
        ));
        assert_eq!(w.obstacles.len(), 1);
        w.obstacle_colours[0]
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
    fn no_appearance_a_texture_or_an_unknown_proto_give_no_colour() {
        assert_eq!(solid_with(""), None);
        assert_eq!(
            solid_with(
                "appearance PBRAppearance { baseColor 1 0 0 baseColorMap ImageTexture { url [ \"a.png\" ] } }"
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
        assert!(w.obstacle_colours[..4]
            .iter()
            .all(|c| *c == Some([0.0, 1.0, 0.0])));
        assert_eq!(w.obstacle_colours[4], Some([1.0, 0.0, 0.0]));
        assert_eq!(w.obstacle_colours[5], None);
        let world = w.to_world("colours").unwrap();
        let colours = world.wall_colours();
        assert_eq!(colours.len(), 6);
        assert_eq!(colours[4], Some([1.0, 0.0, 0.0]));
        assert_eq!(world.floor_colour(), Some([0.0, 0.0, 1.0]));
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
}
