//! 3D frames of a Webots scene: translation, axis-angle rotation and scale composed down the
//! tree, and the change from the old Y-up (NUE) convention to mazesim's Z-up (ENU) one.

/// A 3-vector.
pub type Vec3 = [f64; 3];
/// A 3x3 matrix, row-major.
pub type Mat3 = [[f64; 3]; 3];

/// The identity matrix.
pub const IDENTITY: Mat3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// NUE (x north, y up, z east) to ENU: `(x, y, z) -> (-z, -x, y)`, the mapping of Webots' own
/// R2022a world converter (translations `(x, y, z) -> (-z, -x, y)`, rotation axes likewise).
pub const NUE_TO_ENU: Mat3 = [[0.0, 0.0, -1.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

/// The inverse of [`NUE_TO_ENU`]: expresses a Z-up definition in a Y-up frame. A Y-up PROTO or
/// primitive of size `(x, y, z)` equals this rotation of its Z-up twin of size `(z, x, y)`.
pub const ENU_TO_NUE: Mat3 = [[0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [-1.0, 0.0, 0.0]];

/// Matrix product `a * b`.
pub fn mul(a: &Mat3, b: &Mat3) -> Mat3 {
    let mut m = [[0.0; 3]; 3];
    for (i, row) in m.iter_mut().enumerate() {
        for (j, cell) in row.iter_mut().enumerate() {
            *cell = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    m
}

/// Matrix times vector.
pub fn apply(m: &Mat3, v: Vec3) -> Vec3 {
    [0, 1, 2].map(|i| m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2])
}

/// Euclidean length.
pub fn norm(v: Vec3) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// Length of the horizontal (x, y) part.
pub fn horizontal_norm(v: Vec3) -> f64 {
    v[0].hypot(v[1])
}

/// Angle in radians between `v` and the vertical axis, in [0, pi/2] (either direction counts).
pub fn tilt(v: Vec3) -> f64 {
    horizontal_norm(v).atan2(v[2].abs())
}

/// Rotation of `angle` radians about `axis` (Rodrigues); `None` for a zero axis.
pub fn axis_angle(axis: Vec3, angle: f64) -> Option<Mat3> {
    let n = norm(axis);
    if n.is_nan() || n <= 1e-12 || !angle.is_finite() {
        return None;
    }
    let [x, y, z] = axis.map(|a| a / n);
    let (s, c) = angle.sin_cos();
    let t = 1.0 - c;
    Some([
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
    ])
}

/// A frame: points map as `linear * p + origin`; `linear` holds rotation times scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Rotation and scale.
    pub linear: Mat3,
    /// Where the local origin lies in the parent frame.
    pub origin: Vec3,
}

impl Frame {
    /// The identity frame.
    pub const IDENTITY: Frame = Frame {
        linear: IDENTITY,
        origin: [0.0; 3],
    };

    /// A pure rotation.
    pub fn rotation(m: Mat3) -> Frame {
        Frame {
            linear: m,
            origin: [0.0; 3],
        }
    }

    /// A pure translation.
    pub fn translation(t: Vec3) -> Frame {
        Frame {
            linear: IDENTITY,
            origin: t,
        }
    }

    /// Translation, rotation and scale as Webots applies them (`T * R * S`).
    pub fn new(translation: Vec3, rotation: Mat3, scale: Vec3) -> Frame {
        let mut linear = rotation;
        for row in &mut linear {
            for (j, cell) in row.iter_mut().enumerate() {
                *cell *= scale[j];
            }
        }
        Frame {
            linear,
            origin: translation,
        }
    }

    /// This frame followed by `child`, a frame expressed in this one.
    pub fn then(&self, child: &Frame) -> Frame {
        let moved = apply(&self.linear, child.origin);
        Frame {
            linear: mul(&self.linear, &child.linear),
            origin: [0, 1, 2].map(|i| moved[i] + self.origin[i]),
        }
    }

    /// A direction of the local frame in the parent frame (scale included).
    pub fn vector(&self, v: Vec3) -> Vec3 {
        apply(&self.linear, v)
    }

    /// The local axis `i` (0 = x, 1 = y, 2 = z) in the parent frame.
    pub fn axis(&self, i: usize) -> Vec3 {
        [self.linear[0][i], self.linear[1][i], self.linear[2][i]]
    }
}

/// Converts a size written for a Y-up definition, `(x, y, z)`, to its Z-up twin `(z, x, y)`.
pub fn y_up_size(s: Vec3) -> Vec3 {
    [s[2], s[0], s[1]]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (0..3).all(|i| (a[i] - b[i]).abs() < 1e-12)
    }

    #[test]
    fn nue_conversion_matches_the_webots_converter() {
        // translation (x, y, z) -> (-z, -x, y)
        assert!(close(
            apply(&NUE_TO_ENU, [1.0, 2.0, 3.0]),
            [-3.0, -1.0, 2.0]
        ));
        // a rotation about y (up in NUE) becomes the same rotation about z
        let r = axis_angle([0.0, 1.0, 0.0], 0.5).unwrap();
        let converted = mul(&mul(&NUE_TO_ENU, &r), &ENU_TO_NUE);
        let expected = axis_angle([0.0, 0.0, 1.0], 0.5).unwrap();
        for i in 0..3 {
            assert!(close(converted[i], expected[i]));
        }
        assert_eq!(mul(&NUE_TO_ENU, &ENU_TO_NUE), IDENTITY);
        // the robot's forward -z in NUE is +x in ENU
        assert!(close(apply(&NUE_TO_ENU, [0.0, 0.0, -1.0]), [1.0, 0.0, 0.0]));
        assert!(close(apply(&ENU_TO_NUE, [1.0, 0.0, 0.0]), [0.0, 0.0, -1.0]));
    }

    #[test]
    fn frames_compose_parent_first() {
        let parent = Frame::new(
            [1.0, 0.0, 0.0],
            axis_angle([0.0, 0.0, 1.0], std::f64::consts::FRAC_PI_2).unwrap(),
            [1.0; 3],
        );
        let child = Frame::translation([1.0, 0.0, 0.0]);
        assert!(close(parent.then(&child).origin, [1.0, 1.0, 0.0]));
        let scaled = Frame::new([0.0; 3], IDENTITY, [2.0, 3.0, 4.0]);
        assert!(close(scaled.vector([1.0, 1.0, 1.0]), [2.0, 3.0, 4.0]));
        assert!(axis_angle([0.0; 3], 1.0).is_none());
        assert!((tilt([0.0, 1.0, 1.0]) - std::f64::consts::FRAC_PI_4).abs() < 1e-12);
    }
}
