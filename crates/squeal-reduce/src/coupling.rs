//! Parts joined to parts: a node set's mean motion as six boundary coordinates of the
//! Craig–Bampton reduction, and springs between two such points (of two parts) or to ground.
//!
//! # Mean motion of a set (RBE3, Abaqus `*COUPLING, *DISTRIBUTING`)
//!
//! A coupling set `S` with weights `w_k` (its faces' area weights `w_k = (1/A) ∫ N_k dA`,
//! [`crate::interface::footprint`], when the set holds boundary faces; else `1/|S|` each),
//! summing to 1, and centroid `c = Σ w_k x_k`, keeps six coordinates:
//!
//! - the translation `t = Σ_k w_k u_k` (three rows);
//! - the rotation `θ = J⁻¹ Σ_k w_k r_k × u_k`, `r_k = x_k − c`,
//!   `J = Σ_k w_k (|r_k|² I − r_k r_kᵀ)` (three rows): the least-squares rigid fit of the
//!   set's motion, so that a rigid motion `u_k = t + θ × r_k` gives back `t` and `θ`
//!   exactly (`Σ w r × (θ × r) = J θ` and `Σ w r = 0`). `J` is invertible unless the set's
//!   nodes lie on one line; such a set is refused.
//!
//! Rotation row `a` on node `k` is `w_k (g_a × r_k) · u_k` with `g_a` row `a` of `J⁻¹`
//! (`(r × e_d) · g = e_d · (g × r)`). Each of the six is a constraint row `r = C u` of
//! [`crate::craig_bampton`] (the part's coupling set is its boundary: a pad's pistons, a
//! caliper's bores and guides, a bracket's ears), held in the factored stiffness by the
//! footprint springs of its module docs: the six rows see every rigid motion, so a part held by
//! its couplings alone (a floating caliper) has a positive definite `K'`. However many nodes the
//! set has, the part keeps six dofs for it, which keeps the pad's coupling sets small.
//!
//! # Springs between coupling points (Abaqus `*CONNECTOR` with elasticity, Nastran `CBUSH`)
//!
//! A connection joins point `a` (centroid `c_a`) of one part to point `b` (centroid `c_b`) of
//! another, or to ground. Both motions are taken at the connection's point `p`: the mid-point
//! `(c_a + c_b)/2`, or `c_a` to ground, `d_a = t_a + θ_a × (p − c_a)`, and the spring's energy is
//!
//! `E = ½ (d_a − d_b)ᵀ T (d_a − d_b) + ½ (θ_a − θ_b)ᵀ R (θ_a − θ_b)`,
//!
//! `T = Σ_i k_i e_i e_iᵀ`, `R = Σ_i κ_i e_i e_iᵀ` over the connection's orthonormal axes `e_i`
//! (`d_b = θ_b = 0` for ground). A rigid motion of the whole assembly stores no energy
//! (`d_a = d_b` when both parts move as one body), whatever the offset between the centroids.
//! With `D = [G_a  −G_b]`, `G = [I  −[p − c]×]` and `E_θ = [0 I  0 −I]` on the two points' six
//! dofs each, the stiffness added to the assembled reduced brake is
//! `K_c = Dᵀ T D + E_θᵀ R E_θ` (symmetric, positive semi-definite).
//!
//! A connection that carries the clamp force (`load`: a piston between the caliper and the
//! inboard pad, a finger on the outboard one) has the pad's load point as end `a`: the brake
//! applies the pad's share of the clamp force `F` there, and `−F` to end `b` at `c_a`
//! (a force `−F` on its translations and the moment `(c_a − c_b) × (−F)` on its rotations), so
//! that the hydraulic pressure between the caliper's bore and the piston is a pair of internal
//! forces: the assembly's loads stay self-equilibrated and the caliper floats on its guides.
//!
//! # Springs on the vibration only (`vibration_only`)
//!
//! A caliper's clamp is pressure-controlled: the pad's load is the line pressure times the
//! piston area whatever the piston's stiffness, while the piston seal and the fluid column
//! resist the piston's vibration (a dynamic stiffness). A connection marked `vibration_only`
//! adds its `K_c` to the stiffness of the vibration about the static equilibrium (the
//! linearized eqs (18)–(20), the harmonics `k >= 1` of the harmonic balance) but not to the
//! static equilibrium of eq (14) nor to the 0th harmonic; `squeal_brake` keeps it apart
//! (`Brake::k_vibration`).

use crate::ReduceError;
use crate::interface::{InterfaceError, footprint};
use serde::{Deserialize, Serialize};
use squeal_element::geometry::cross;
use squeal_mesh::Mesh;

/// A node set of a part kept as one coupling point (its six mean-motion coordinates).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct CouplingSet {
    /// The node set.
    pub set: String,
    /// The pad's load point (pistons or fingers): its point has the role `piston` and the
    /// brake applies the pad's clamp force there.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub load: bool,
    /// Kept node by node instead (a tie between parts, [`crate::part_tie`]): each node's three
    /// dofs are boundary coordinates, points of role [`crate::rom::PointRole::Tie`], kept
    /// before the mean-motion sets' points.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub nodal: bool,
}

/// The mean motion of a node set: weights, centroid and `J⁻¹` (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct MeanMotion {
    /// `(node index, weight)`, weights summing to 1.
    pub weights: Vec<(u32, f64)>,
    /// `c = Σ w_k x_k`.
    pub centroid: [f64; 3],
    /// The area of the set's faces, when it has some.
    pub area: Option<f64>,
    /// The faces' mean outward normal, when it has some.
    pub normal: Option<[f64; 3]>,
    /// `J⁻¹`.
    pub j_inverse: [[f64; 3]; 3],
}

impl MeanMotion {
    /// The set's mean motion on `mesh` (module docs); refuses a missing or empty set and one
    /// whose nodes lie on a line.
    pub fn of(mesh: &Mesh, set: &str) -> Result<Self, ReduceError> {
        let nodes = mesh
            .node_set(set)
            .ok_or_else(|| InterfaceError::MissingSet(set.into()))?;
        if nodes.is_empty() {
            return Err(InterfaceError::EmptySet(set.into()).into());
        }
        let (weights, area, normal) = match footprint(mesh, set) {
            Ok(p) => (p.weights, Some(p.area), Some(p.normal)),
            Err(InterfaceError::NoFaces { .. }) => {
                let w = 1.0 / nodes.len() as f64;
                let mut v: Vec<(u32, f64)> = nodes.iter().map(|&n| (n, w)).collect();
                v.sort_by_key(|e| e.0);
                v.dedup_by_key(|e| e.0);
                (v, None, None)
            }
            Err(e) => return Err(e.into()),
        };
        let mut c = [0.0; 3];
        for &(n, w) in &weights {
            let x = mesh.nodes[n as usize];
            (0..3).for_each(|d| c[d] += w * x[d]);
        }
        let mut j = [[0.0; 3]; 3];
        for &(n, w) in &weights {
            let x = mesh.nodes[n as usize];
            let r = [x[0] - c[0], x[1] - c[1], x[2] - c[2]];
            let r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
            for a in 0..3 {
                for b in 0..3 {
                    j[a][b] += w * (if a == b { r2 } else { 0.0 } - r[a] * r[b]);
                }
            }
        }
        let j_inverse = inverse3(&j).ok_or_else(|| {
            ReduceError::Options(format!(
                "coupling set {set}: its nodes lie on a line (or are one node), so its mean rotation about that line is not defined: give a set spread over a face"
            ))
        })?;
        Ok(Self {
            weights,
            centroid: c,
            area,
            normal,
            j_inverse,
        })
    }

    /// The six rows (translations x, y, z, rotations about x, y, z) as, for each row, the
    /// motion direction at each node: `(node, c)` with the row `Σ_k c_k · u_k`.
    pub fn rows(&self, mesh: &Mesh) -> [Vec<(u32, [f64; 3])>; 6] {
        std::array::from_fn(|row| {
            self.weights
                .iter()
                .map(|&(n, w)| {
                    if row < 3 {
                        let mut e = [0.0; 3];
                        e[row] = w;
                        (n, e)
                    } else {
                        let x = mesh.nodes[n as usize];
                        let r = [
                            x[0] - self.centroid[0],
                            x[1] - self.centroid[1],
                            x[2] - self.centroid[2],
                        ];
                        let g = self.j_inverse[row - 3];
                        (n, cross(g, r).map(|v| w * v))
                    }
                })
                .collect()
        })
    }
}

/// `a⁻¹` of a symmetric positive semi-definite 3 × 3, `None` when its determinant is below
/// `1e-12` of the cube of its mean diagonal (a set on a line: `J` has a zero eigenvalue).
fn inverse3(a: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let cof = |i: usize, j: usize| {
        let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
        let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
        a[r0][c0] * a[r1][c1] - a[r0][c1] * a[r1][c0]
    };
    let det = a[0][0] * cof(0, 0) + a[0][1] * cof(0, 1) + a[0][2] * cof(0, 2);
    let scale = (a[0][0] + a[1][1] + a[2][2]) / 3.0;
    if !(det > 1e-12 * scale.powi(3) && det.is_finite()) {
        return None;
    }
    Some(std::array::from_fn(|i| {
        std::array::from_fn(|j| cof(j, i) / det)
    }))
}

/// One end of a connection: a part's coupling point.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct End {
    /// The part's name.
    pub part: String,
    /// The coupling's node set.
    pub set: String,
    /// Index of the coupling point among the part's points.
    pub point: usize,
}

/// A spring between two parts' coupling points, or from one to ground (module docs).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Connection {
    /// Its name (`connectors.<k>` of the scene, or the one it gives).
    pub name: String,
    /// First end.
    pub a: End,
    /// Second end; `None`: ground.
    pub b: Option<End>,
    /// Stiffness along the axes (N/m).
    pub stiffness: [f64; 3],
    /// Rotational stiffness about the axes (N m/rad).
    pub rotational: [f64; 3],
    /// Orthonormal axes (rows).
    pub axes: [[f64; 3]; 3],
    /// Carries the clamp force: `a` is a pad's load point (module docs).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub load: bool,
    /// Acts on the vibration about the static equilibrium only, not in eq (14) (module docs).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub vibration_only: bool,
}

/// A connection as given, its ends by part and set (resolved to points after the reduction).
#[derive(Clone, Debug, PartialEq)]
pub struct ConnectionInput {
    /// Its name.
    pub name: String,
    /// First end: part and coupling set.
    pub a: (String, String),
    /// Second end; `None`: ground.
    pub b: Option<(String, String)>,
    /// Stiffness along the axes (N/m).
    pub stiffness: [f64; 3],
    /// Rotational stiffness about the axes (N m/rad).
    pub rotational: [f64; 3],
    /// Orthonormal axes (rows).
    pub axes: [[f64; 3]; 3],
    /// Carries the clamp force (`a` a pad's load set).
    pub load: bool,
    /// Acts on the vibration about the static equilibrium only.
    pub vibration_only: bool,
}

/// `G = [I  −[r]×]` (3 × 6): the motion at offset `r` from a point of translation `t` and
/// rotation `θ`, `t + θ × r = t − r × θ`.
pub fn offset_map(r: [f64; 3]) -> [[f64; 6]; 3] {
    // −[r]× = [[0, r_z, −r_y], [−r_z, 0, r_x], [r_y, −r_x, 0]].
    [
        [1.0, 0.0, 0.0, 0.0, r[2], -r[1]],
        [0.0, 1.0, 0.0, -r[2], 0.0, r[0]],
        [0.0, 0.0, 1.0, r[1], -r[0], 0.0],
    ]
}

/// The connection's stiffness on the six dofs of `a` (then of `b`, when it has one), each
/// point's dofs ordered translations x, y, z, rotations about x, y, z; `ca`, `cb` the
/// centroids (module docs). The matrix is 6 × 6 to ground, else 12 × 12, row-major.
pub fn connection_stiffness(c: &Connection, ca: [f64; 3], cb: Option<[f64; 3]>) -> Vec<Vec<f64>> {
    let p = match cb {
        Some(cb) => std::array::from_fn(|d| 0.5 * (ca[d] + cb[d])),
        None => ca,
    };
    let n = if cb.is_some() { 12 } else { 6 };
    let rel = |c0: [f64; 3]| std::array::from_fn::<f64, 3, _>(|d| p[d] - c0[d]);
    // D (3 × n) and E_θ (3 × n).
    let ga = offset_map(rel(ca));
    let mut dm = vec![vec![0.0; n]; 3];
    let mut em = vec![vec![0.0; n]; 3];
    for i in 0..3 {
        dm[i][..6].copy_from_slice(&ga[i]);
        em[i][3 + i] = 1.0;
    }
    if let Some(cb) = cb {
        let gb = offset_map(rel(cb));
        for i in 0..3 {
            for j in 0..6 {
                dm[i][6 + j] = -gb[i][j];
            }
            em[i][9 + i] = -1.0;
        }
    }
    let tensor = |k: [f64; 3]| -> [[f64; 3]; 3] {
        std::array::from_fn(|i| {
            std::array::from_fn(|j| (0..3).map(|a| k[a] * c.axes[a][i] * c.axes[a][j]).sum())
        })
    };
    let (t, r) = (tensor(c.stiffness), tensor(c.rotational));
    let mut out = vec![vec![0.0; n]; n];
    for i in 0..n {
        for j in 0..n {
            let mut s = 0.0;
            for a in 0..3 {
                for b in 0..3 {
                    s += dm[a][i] * t[a][b] * dm[b][j] + em[a][i] * r[a][b] * em[b][j];
                }
            }
            out[i][j] = s;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rigid motion of both ends stores no energy, whatever the offset between them: the
    /// connection's stiffness times the rigid motion's dofs is zero to round-off (1e-9 of the
    /// stiffness times the motion's size).
    #[test]
    fn rigid_motion_stores_no_energy() {
        let c = Connection {
            name: "pin".into(),
            a: End {
                part: "a".into(),
                set: "A".into(),
                point: 0,
            },
            b: None,
            stiffness: [1e7, 2e7, 3e7],
            rotational: [1e3, 2e3, 5e3],
            axes: [[1.0, 0.0, 0.0], [0.0, 0.6, 0.8], [0.0, -0.8, 0.6]],
            load: false,
            vibration_only: false,
        };
        let (ca, cb) = ([0.1, 0.02, -0.03], [0.13, -0.01, 0.05]);
        let k = connection_stiffness(&c, ca, Some(cb));
        let (t, th) = ([1e-3, -2e-3, 0.5e-3], [0.01, -0.02, 0.03]);
        // Each point's dofs: its own translation t + θ × c, and θ.
        let at = |x: [f64; 3]| {
            let m = cross(th, x);
            [t[0] + m[0], t[1] + m[1], t[2] + m[2], th[0], th[1], th[2]]
        };
        let q: Vec<f64> = at(ca).into_iter().chain(at(cb)).collect();
        let f: Vec<f64> = k
            .iter()
            .map(|row| row.iter().zip(&q).map(|(a, b)| a * b).sum())
            .collect();
        let size = 3e7 * 0.03;
        assert!(f.iter().all(|x| x.abs() < 1e-9 * size), "{f:?}");
    }
}
