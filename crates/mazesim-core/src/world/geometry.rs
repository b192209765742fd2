//! Plain geometry of a compiled world: boxes, floor shapes and their bounds, in f64 metres.

/// An axis-aligned bounding box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    /// Lower corner.
    pub min: [f64; 2],
    /// Upper corner.
    pub max: [f64; 2],
}

impl Bounds {
    /// The empty box (union identity).
    pub const EMPTY: Bounds = Bounds {
        min: [f64::INFINITY, f64::INFINITY],
        max: [f64::NEG_INFINITY, f64::NEG_INFINITY],
    };

    /// Smallest box holding both.
    pub fn union(self, o: Bounds) -> Bounds {
        Bounds {
            min: [self.min[0].min(o.min[0]), self.min[1].min(o.min[1])],
            max: [self.max[0].max(o.max[0]), self.max[1].max(o.max[1])],
        }
    }

    /// The box grown by `m` on every side.
    pub fn grown(self, m: f64) -> Bounds {
        Bounds {
            min: [self.min[0] - m, self.min[1] - m],
            max: [self.max[0] + m, self.max[1] + m],
        }
    }

    /// True when nothing was added.
    pub fn is_empty(&self) -> bool {
        self.min[0] > self.max[0]
    }

    /// Whether the point lies inside (borders included).
    pub fn contains(&self, p: [f64; 2]) -> bool {
        p[0] >= self.min[0] && p[0] <= self.max[0] && p[1] >= self.min[1] && p[1] <= self.max[1]
    }

    fn around(center: [f64; 2], half: [f64; 2], yaw: f64) -> Bounds {
        let (s, c) = yaw.sin_cos();
        let ex = (c * half[0]).abs() + (s * half[1]).abs();
        let ey = (s * half[0]).abs() + (c * half[1]).abs();
        Bounds {
            min: [center[0] - ex, center[1] - ey],
            max: [center[0] + ex, center[1] + ey],
        }
    }
}

/// A wall: a box, possibly rotated, with an infra-red reflection factor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallBox {
    /// Centre.
    pub center: [f64; 2],
    /// Half extents along its own axes.
    pub half: [f64; 2],
    /// Rotation in radians.
    pub yaw: f64,
    /// Reflection factor f in (0, 1].
    pub reflectance: f64,
}

impl WallBox {
    /// Bounding box.
    pub fn bounds(&self) -> Bounds {
        Bounds::around(self.center, self.half, self.yaw)
    }

    /// A wall of `thickness` along the segment `a`-`b`, lengthened by half a thickness at each end.
    pub fn from_segment(a: [f64; 2], b: [f64; 2], thickness: f64, reflectance: f64) -> WallBox {
        let d = [b[0] - a[0], b[1] - a[1]];
        let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
        WallBox {
            center: [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0],
            half: [(len + thickness) / 2.0, thickness / 2.0],
            yaw: d[1].atan2(d[0]),
            reflectance,
        }
    }
}

/// A region of floor paint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PaintShape {
    /// A rotated rectangle.
    Rect {
        /// Centre.
        center: [f64; 2],
        /// Half extents.
        half: [f64; 2],
        /// Rotation.
        yaw: f64,
    },
    /// A disc.
    Circle {
        /// Centre.
        center: [f64; 2],
        /// Radius.
        radius: f64,
    },
    /// All points within `radius` of the segment a-b.
    Capsule {
        /// One end.
        a: [f64; 2],
        /// Other end.
        b: [f64; 2],
        /// Half the stroke width.
        radius: f64,
    },
}

impl PaintShape {
    /// Whether the point is painted by this shape.
    pub fn contains(&self, p: [f64; 2]) -> bool {
        self.contains_turned(p, self.turn())
    }

    /// Sine and cosine of a rectangle's yaw ((0, 1) for other shapes), for `contains_turned`.
    pub fn turn(&self) -> [f64; 2] {
        match *self {
            PaintShape::Rect { yaw, .. } => {
                let (s, c) = yaw.sin_cos();
                [s, c]
            }
            _ => [0.0, 1.0],
        }
    }

    /// `contains`, given `turn()` computed once beforehand.
    #[inline]
    pub fn contains_turned(&self, p: [f64; 2], turn: [f64; 2]) -> bool {
        match *self {
            PaintShape::Rect { center, half, .. } => {
                let [s, c] = turn;
                let dx = p[0] - center[0];
                let dy = p[1] - center[1];
                let lx = c * dx + s * dy;
                let ly = -s * dx + c * dy;
                lx.abs() <= half[0] && ly.abs() <= half[1]
            }
            PaintShape::Circle { center, radius } => {
                let dx = p[0] - center[0];
                let dy = p[1] - center[1];
                dx * dx + dy * dy <= radius * radius
            }
            PaintShape::Capsule { a, b, radius } => {
                let ab = [b[0] - a[0], b[1] - a[1]];
                let ap = [p[0] - a[0], p[1] - a[1]];
                let len2 = ab[0] * ab[0] + ab[1] * ab[1];
                let t = if len2 > 0.0 {
                    ((ap[0] * ab[0] + ap[1] * ab[1]) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let dx = ap[0] - t * ab[0];
                let dy = ap[1] - t * ab[1];
                dx * dx + dy * dy <= radius * radius
            }
        }
    }

    /// Bounding box.
    pub fn bounds(&self) -> Bounds {
        match *self {
            PaintShape::Rect { center, half, yaw } => Bounds::around(center, half, yaw),
            PaintShape::Circle { center, radius } => Bounds::around(center, [radius; 2], 0.0),
            PaintShape::Capsule { a, b, radius } => Bounds {
                min: [a[0].min(b[0]), a[1].min(b[1])],
                max: [a[0].max(b[0]), a[1].max(b[1])],
            }
            .grown(radius),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotated_rect_contains_and_bounds() {
        let r = PaintShape::Rect {
            center: [1.0, 1.0],
            half: [0.5, 0.1],
            yaw: std::f64::consts::FRAC_PI_2,
        };
        assert!(r.contains([1.0, 1.45]));
        assert!(!r.contains([1.45, 1.0]));
        let b = r.bounds();
        assert!((b.max[1] - 1.5).abs() < 1e-12 && (b.max[0] - 1.1).abs() < 1e-12);
    }

    #[test]
    fn capsule_has_round_ends() {
        let c = PaintShape::Capsule {
            a: [0.0, 0.0],
            b: [1.0, 0.0],
            radius: 0.1,
        };
        assert!(c.contains([1.05, 0.05]));
        assert!(!c.contains([1.09, 0.09]));
        assert!(c.contains([0.5, -0.1]));
    }

    #[test]
    fn segment_wall_closes_corners() {
        let w = WallBox::from_segment([0.0, 0.0], [0.0, 1.0], 0.01, 1.0);
        let b = w.bounds();
        assert!((b.min[1] + 0.005).abs() < 1e-12 && (b.max[1] - 1.005).abs() < 1e-12);
    }
}
