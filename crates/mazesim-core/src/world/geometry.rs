//! Plain geometry of a compiled world: boxes, floor shapes and their bounds, in f64 metres.

/// An axis-aligned bounding box.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
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
                let [lx, ly] = rect_local(center, turn, p);
                lx.abs() <= half[0] && ly.abs() <= half[1]
            }
            PaintShape::Circle { center, radius } => {
                let dx = p[0] - center[0];
                let dy = p[1] - center[1];
                dx * dx + dy * dy <= radius * radius
            }
            PaintShape::Capsule { a, b, radius } => segment_distance2(a, b, p) <= radius * radius,
        }
    }

    /// Where the disc of `radius` around `c` lies with respect to the shape, given `turn()`.
    /// `Across` when an edge passes through the disc, and also when the disc only comes near one
    /// (a rectangle's corner): the caller then looks point by point. The answer holds for exact
    /// points; for points computed with rounding, widen `radius` by a slack above it.
    #[inline]
    pub fn disc_side(&self, c: [f64; 2], radius: f64, turn: [f64; 2]) -> DiscSide {
        match *self {
            PaintShape::Rect { center, half, .. } => {
                let [lx, ly] = rect_local(center, turn, c);
                let (ax, ay) = (lx.abs(), ly.abs());
                if ax + radius <= half[0] && ay + radius <= half[1] {
                    DiscSide::Inside
                } else if ax - radius > half[0] || ay - radius > half[1] {
                    DiscSide::Outside
                } else {
                    DiscSide::Across
                }
            }
            PaintShape::Circle {
                center,
                radius: round,
            } => {
                let dx = c[0] - center[0];
                let dy = c[1] - center[1];
                disc_side_of_gap(dx * dx + dy * dy, round, radius)
            }
            PaintShape::Capsule {
                a,
                b,
                radius: stroke,
            } => disc_side_of_gap(segment_distance2(a, b, c), stroke, radius),
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

/// Where a disc lies with respect to a paint shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DiscSide {
    /// Every point of the disc is painted by the shape.
    Inside,
    /// No point of the disc is painted by the shape.
    Outside,
    /// Some points may be painted and some not.
    Across,
}

/// `p` in the frame of a rectangle centred at `center` turned by `turn` (its yaw's sine, cosine).
#[inline]
fn rect_local(center: [f64; 2], turn: [f64; 2], p: [f64; 2]) -> [f64; 2] {
    let [s, c] = turn;
    let dx = p[0] - center[0];
    let dy = p[1] - center[1];
    [c * dx + s * dy, -s * dx + c * dy]
}

/// Squared distance from `p` to the segment `a`-`b`.
#[inline]
fn segment_distance2(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> f64 {
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
    dx * dx + dy * dy
}

/// Where a disc of `radius` lies with respect to the points within `reach` of a centre (a
/// point, or a segment), its own centre lying `distance2` (squared) from it.
#[inline]
fn disc_side_of_gap(distance2: f64, reach: f64, radius: f64) -> DiscSide {
    let inner = reach - radius;
    let outer = reach + radius;
    if inner >= 0.0 && distance2 <= inner * inner {
        DiscSide::Inside
    } else if distance2 > outer * outer {
        DiscSide::Outside
    } else {
        DiscSide::Across
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

    #[test]
    fn a_disc_inside_or_outside_has_every_point_so() {
        let shapes = [
            PaintShape::Rect {
                center: [0.1, -0.2],
                half: [0.05, 0.02],
                yaw: 0.7,
            },
            PaintShape::Circle {
                center: [0.0, 0.1],
                radius: 0.03,
            },
            PaintShape::Capsule {
                a: [-0.1, 0.0],
                b: [0.05, 0.04],
                radius: 0.01,
            },
        ];
        let mut rng = crate::rng::Rng::new(0x2545_f491_4f6c_dd1d);
        let mut uniform = move || rng.uniform();
        let mut seen = [0; 3];
        for shape in shapes {
            let turn = shape.turn();
            let b = shape.bounds().grown(0.02);
            for _ in 0..4000 {
                let c = [
                    b.min[0] + uniform() * (b.max[0] - b.min[0]),
                    b.min[1] + uniform() * (b.max[1] - b.min[1]),
                ];
                let radius = 0.001 + 0.01 * uniform();
                let side = shape.disc_side(c, radius, turn);
                seen[side as usize] += 1;
                for k in 0..64 {
                    let (s, co) = (k as f64 * 0.0982).sin_cos();
                    let r = radius * [1.0, 0.999, 0.5, 0.0][k % 4];
                    let p = [c[0] + r * co, c[1] + r * s];
                    match side {
                        DiscSide::Inside => assert!(shape.contains(p), "{shape:?} {c:?} {p:?}"),
                        DiscSide::Outside => assert!(!shape.contains(p), "{shape:?} {c:?} {p:?}"),
                        DiscSide::Across => {}
                    }
                }
            }
        }
        assert!(seen.iter().all(|&n| n > 500), "{seen:?}");
    }
}
