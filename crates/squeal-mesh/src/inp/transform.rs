//! Placement of a part instance (`*INSTANCE` data lines).

/// Abaqus `*INSTANCE` positioning: data line 1 is a translation `t`; data line 2 is a rotation
/// by `angle` degrees about the axis through points `a` and `b` (right-hand rule about the
/// direction a -> b). The translation is applied first, then the rotation (as stated for the
/// same data lines of Abaqus `*FIELD OPERATIONS`): `x' = a + R (x + t - a)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Placement {
    pub translation: [f64; 3],
    pub rotation: Option<Rotation>,
}

impl Default for Placement {
    fn default() -> Self {
        Self {
            translation: [0.0; 3],
            rotation: None,
        }
    }
}

/// A rotation about an axis through `origin`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Rotation {
    pub origin: [f64; 3],
    pub matrix: [[f64; 3]; 3],
}

impl Rotation {
    /// Rodrigues' formula `R = cos θ I + sin θ [k]x + (1 - cos θ) k kᵀ` for the unit axis `k`
    /// along `b - a`. `None` if the points coincide (no axis).
    pub fn about_axis(a: [f64; 3], b: [f64; 3], angle_deg: f64) -> Option<Self> {
        let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if !(len > 0.0 && len.is_finite()) {
            return None;
        }
        let k = d.map(|v| v / len);
        let (s, c) = angle_deg.to_radians().sin_cos();
        let cross = [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]];
        let mut m = [[0.0; 3]; 3];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                let id = if i == j { 1.0 } else { 0.0 };
                *v = c * id + s * cross[i][j] + (1.0 - c) * k[i] * k[j];
            }
        }
        Some(Self {
            origin: a,
            matrix: m,
        })
    }
}

impl Placement {
    pub fn is_identity(&self) -> bool {
        self.translation == [0.0; 3] && self.rotation.is_none()
    }

    pub fn apply(&self, x: [f64; 3]) -> [f64; 3] {
        let y = [
            x[0] + self.translation[0],
            x[1] + self.translation[1],
            x[2] + self.translation[2],
        ];
        match &self.rotation {
            None => y,
            Some(r) => {
                let d = [y[0] - r.origin[0], y[1] - r.origin[1], y[2] - r.origin[2]];
                std::array::from_fn(|i| {
                    r.origin[i]
                        + r.matrix[i][0] * d[0]
                        + r.matrix[i][1] * d[1]
                        + r.matrix[i][2] * d[2]
                })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quarter_turn_about_a_shifted_z_axis() {
        // 90 degrees about the vertical axis through (1, 0, 0): the point (2, 0, 5) goes to
        // (1, 1, 5) by the right-hand rule. Round-off of sin/cos(pi/2) is ~1e-16.
        let p = Placement {
            translation: [1.0, 0.0, 0.0],
            rotation: Rotation::about_axis([1.0, 0.0, 0.0], [1.0, 0.0, 3.0], 90.0),
        };
        let y = p.apply([1.0, 0.0, 5.0]);
        for (a, b) in y.iter().zip([1.0, 1.0, 5.0]) {
            assert!((a - b).abs() < 1e-14, "{y:?}");
        }
        assert!(Rotation::about_axis([1.0; 3], [1.0; 3], 30.0).is_none());
    }
}
