//! The faces of a contact or tie surface: 6-node triangles (of tet10, wedge15 and pyramid13
//! elements) and 8-node serendipity quadrilaterals (of hex20, wedge15 and pyramid13), with
//! their maps, quadrature rules, sub-cells and edges in one place, so that the interface code
//! reads either shape.
//!
//! A face maps its reference domain to space by `X(s, t) = Σ_a N_a(s, t) X_a`:
//!
//! - **tri6** `[v0, v1, v2, m01, m12, m20]` on the triangle `s, t ≥ 0, s + t ≤ 1`, with
//!   barycentrics `L = (1 − s − t, s, t)`: `N = L_i (2 L_i − 1)` at the corners, `4 L_a L_b` at
//!   the midside nodes; integrated by Dunavant's 6-point degree-4 rule.
//! - **quad8** `[v0, v1, v2, v3, m01, m12, m23, m30]` on the square `[−1, 1]²` (corners at
//!   `(∓1, ∓1)` counter-clockwise): `N = ¼ (1 + ξ_a s)(1 + η_a t)(ξ_a s + η_a t − 1)` at the
//!   corners, `½ (1 − s²)(1 + η_a t)` at the midsides of the edges `t = ±1` and
//!   `½ (1 − t²)(1 + ξ_a s)` at those of `s = ±1` (Zienkiewicz & Taylor, *The Finite Element
//!   Method*, vol. 1, 6th ed., Sec. 6.4); integrated by the 3 × 3 Gauss–Legendre rule. On a
//!   flat face the area element `|∂X/∂s × ∂X/∂t|` is a polynomial of degree ≤ 4 in `(s, t)`
//!   (the map is cubic, its derivatives quadratic), which 3 × 3 Gauss integrates exactly
//!   (degree 5 in each variable): flat faces' areas are exact whatever their shape in the plane.
//!
//! Along each edge both maps are quadratic in the edge's parameter (the quad8's cubic terms
//! `s² t`, `s t²` are quadratic on `t = ±1` and `s = ±1`), which the closest-point search on
//! an edge uses.

use super::{DUNAVANT4, tri6_shape};
use squeal_element::geometry::cross;

/// The shape of a surface face.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Shape {
    /// 6-node triangle.
    Tri6,
    /// 8-node serendipity quadrilateral.
    Quad8,
}

/// A boundary face of a surface: its shape and node indices (the first `node_count()` of `nodes`;
/// a triangle's last two are unused).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct SurfaceFace {
    /// Triangle or quadrilateral.
    pub shape: Shape,
    /// Node indices, corners first (`[u32::MAX; 2]` pad a triangle).
    pub nodes: [u32; 8],
}

/// Shape functions (`[f64; 8]`, a triangle's last two zero) and their `s`, `t` derivatives.
pub type Values = ([f64; 8], [f64; 8], [f64; 8]);

/// The four quad8 corners in reference coordinates, counter-clockwise.
const QUAD_CORNERS: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// Reference coordinates of the tri6's and the quad8's nodes.
const TRI_REFERENCE: [[f64; 2]; 6] = [
    [0.0, 0.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [0.5, 0.0],
    [0.5, 0.5],
    [0.0, 0.5],
];
const QUAD_REFERENCE: [[f64; 2]; 8] = [
    [-1.0, -1.0],
    [1.0, -1.0],
    [1.0, 1.0],
    [-1.0, 1.0],
    [0.0, -1.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [-1.0, 0.0],
];

/// Three-point Gauss–Legendre rule on `[−1, 1]`: `(point, weight)`.
const GAUSS3: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 5.0 / 9.0),
    (0.0, 8.0 / 9.0),
    (0.774_596_669_241_483_4, 5.0 / 9.0),
];

impl SurfaceFace {
    /// A 6-node triangle.
    pub fn tri6(n: [u32; 6]) -> Self {
        Self {
            shape: Shape::Tri6,
            nodes: [n[0], n[1], n[2], n[3], n[4], n[5], u32::MAX, u32::MAX],
        }
    }

    /// An 8-node quadrilateral.
    pub fn quad8(nodes: [u32; 8]) -> Self {
        Self {
            shape: Shape::Quad8,
            nodes,
        }
    }

    /// Number of nodes (6 or 8).
    pub fn node_count(&self) -> usize {
        self.shape.node_count()
    }

    /// The face's node indices.
    pub fn nodes(&self) -> &[u32] {
        &self.nodes[..self.node_count()]
    }

    /// The nodes' coordinates (a triangle's last two zero).
    pub fn coords(&self, mesh: &squeal_mesh::Mesh) -> [[f64; 3]; 8] {
        std::array::from_fn(|i| {
            if i < self.node_count() {
                mesh.nodes[self.nodes[i] as usize]
            } else {
                [0.0; 3]
            }
        })
    }
}

impl Shape {
    /// Number of nodes.
    pub fn node_count(self) -> usize {
        match self {
            Shape::Tri6 => 6,
            Shape::Quad8 => 8,
        }
    }

    /// The nodes' reference coordinates.
    pub fn reference(self) -> &'static [[f64; 2]] {
        match self {
            Shape::Tri6 => &TRI_REFERENCE,
            Shape::Quad8 => &QUAD_REFERENCE,
        }
    }

    /// The reference domain's centroid.
    pub fn centre(self) -> [f64; 2] {
        match self {
            Shape::Tri6 => [1.0 / 3.0, 1.0 / 3.0],
            Shape::Quad8 => [0.0, 0.0],
        }
    }

    /// Shape functions and derivatives at `st` (module docs).
    pub fn values(self, st: [f64; 2]) -> Values {
        match self {
            Shape::Tri6 => {
                let (n, ds, dt) = tri6_shape(st[0], st[1]);
                let pad = |a: [f64; 6]| std::array::from_fn(|i| if i < 6 { a[i] } else { 0.0 });
                (pad(n), pad(ds), pad(dt))
            }
            Shape::Quad8 => quad8_shape(st[0], st[1]),
        }
    }

    /// The quadrature rule over the reference domain: `(st, weight)`, the weights summing to
    /// the reference area (1/2 for the triangle, 4 for the square).
    pub fn rule(self) -> Vec<([f64; 2], f64)> {
        match self {
            Shape::Tri6 => DUNAVANT4
                .iter()
                .map(|&(s, t, w)| ([s, t], 0.5 * w))
                .collect(),
            Shape::Quad8 => {
                let mut out = Vec::with_capacity(9);
                for (s, ws) in GAUSS3 {
                    for (t, wt) in GAUSS3 {
                        out.push(([s, t], ws * wt));
                    }
                }
                out
            }
        }
    }

    /// Whether `st` lies in the reference domain, within `tol`.
    pub fn contains(self, st: [f64; 2], tol: f64) -> bool {
        match self {
            Shape::Tri6 => st[0] >= -tol && st[1] >= -tol && st[0] + st[1] <= 1.0 + tol,
            Shape::Quad8 => st[0].abs() <= 1.0 + tol && st[1].abs() <= 1.0 + tol,
        }
    }

    /// `st` put on the reference domain (a point within round-off of an edge onto it).
    pub fn clamp(self, st: [f64; 2]) -> [f64; 2] {
        match self {
            Shape::Tri6 => {
                let s = st[0].max(0.0);
                let t = st[1].max(0.0);
                let over = (s + t - 1.0).max(0.0);
                [s - 0.5 * over, t - 0.5 * over]
            }
            Shape::Quad8 => st.map(|v| v.clamp(-1.0, 1.0)),
        }
    }

    /// A box around the reference domain that Newton's iterates are kept in (far outside,
    /// the quadratic map may fold).
    pub fn keep(self, st: [f64; 2]) -> [f64; 2] {
        match self {
            Shape::Tri6 => st.map(|v| v.clamp(-1.0, 2.0)),
            Shape::Quad8 => st.map(|v| v.clamp(-3.0, 3.0)),
        }
    }

    /// The edges as pairs of reference corners, in the faces' edge order.
    pub fn edges(self) -> Vec<([f64; 2], [f64; 2])> {
        match self {
            Shape::Tri6 => vec![
                ([0.0, 0.0], [1.0, 0.0]),
                ([1.0, 0.0], [0.0, 1.0]),
                ([0.0, 1.0], [0.0, 0.0]),
            ],
            Shape::Quad8 => (0..4)
                .map(|k| (QUAD_CORNERS[k], QUAD_CORNERS[(k + 1) % 4]))
                .collect(),
        }
    }

    /// The sub-cells of the lumped tributary areas (see [`super::nodal`]): reference
    /// triangles, each with the local nodes that share its area equally.
    ///
    /// A tri6 is split at its edge midpoints into four triangles, each shared by its three
    /// nodes. A quad8 is cut at its edge midpoints into four corner triangles
    /// `[v_k, m_k, m_{k−1}]` (each shared by its three nodes) and the central square
    /// `[m01, m12, m23, m30]` (two reference triangles, shared by the four midside nodes).
    pub fn subcells(self) -> Vec<([[f64; 2]; 3], Vec<usize>)> {
        match self {
            Shape::Tri6 => [[0, 3, 5], [3, 1, 4], [5, 4, 2], [3, 4, 5]]
                .into_iter()
                .map(|k: [usize; 3]| (k.map(|i| TRI_REFERENCE[i]), k.to_vec()))
                .collect(),
            Shape::Quad8 => {
                let q = QUAD_REFERENCE;
                let mut out: Vec<([[f64; 2]; 3], Vec<usize>)> = (0..4)
                    .map(|k| {
                        let (m_next, m_prev) = (4 + k, 4 + (k + 3) % 4);
                        ([q[k], q[m_next], q[m_prev]], vec![k, m_next, m_prev])
                    })
                    .collect();
                out.push(([q[4], q[5], q[6]], vec![4, 5, 6, 7]));
                out.push(([q[4], q[6], q[7]], vec![4, 5, 6, 7]));
                out
            }
        }
    }
}

/// The 8-node serendipity quadrilateral's shape functions and derivatives at `(s, t)`
/// (module docs).
pub fn quad8_shape(s: f64, t: f64) -> Values {
    let (mut n, mut ds, mut dt) = ([0.0; 8], [0.0; 8], [0.0; 8]);
    for (k, [a, b]) in QUAD_CORNERS.into_iter().enumerate() {
        let (p, q) = (1.0 + a * s, 1.0 + b * t);
        let r = a * s + b * t - 1.0;
        n[k] = 0.25 * p * q * r;
        ds[k] = 0.25 * a * q * (r + p);
        dt[k] = 0.25 * b * p * (r + q);
    }
    // Midsides of the edges t = −1, s = 1, t = 1, s = −1.
    for (k, (a, b)) in [(0.0, -1.0), (1.0, 0.0), (0.0, 1.0), (-1.0, 0.0)]
        .into_iter()
        .enumerate()
    {
        if a == 0.0 {
            let q = 1.0 + b * t;
            n[4 + k] = 0.5 * (1.0 - s * s) * q;
            ds[4 + k] = -s * q;
            dt[4 + k] = 0.5 * (1.0 - s * s) * b;
        } else {
            let p = 1.0 + a * s;
            n[4 + k] = 0.5 * (1.0 - t * t) * p;
            ds[4 + k] = 0.5 * (1.0 - t * t) * a;
            dt[4 + k] = -t * p;
        }
    }
    (n, ds, dt)
}

/// The face of shape `shape` with node coordinates `x` at `st`: shape function values, the
/// point, and `∂X/∂s`, `∂X/∂t`.
pub fn tangents(shape: Shape, x: &[[f64; 3]; 8], st: [f64; 2]) -> ([f64; 8], [[f64; 3]; 3]) {
    let (n, ds, dt) = shape.values(st);
    let (mut xs, mut xt, mut xp) = ([0.0; 3], [0.0; 3], [0.0; 3]);
    for k in 0..shape.node_count() {
        for d in 0..3 {
            xs[d] += ds[k] * x[k][d];
            xt[d] += dt[k] * x[k][d];
            xp[d] += n[k] * x[k][d];
        }
    }
    (n, [xp, xs, xt])
}

/// Shape function values, position and `∂X/∂s × ∂X/∂t` at `st` (the area element's normal
/// times the reference-to-physical area ratio).
pub fn map_point(shape: Shape, x: &[[f64; 3]; 8], st: [f64; 2]) -> ([f64; 8], [f64; 3], [f64; 3]) {
    let (n, [xp, xs, xt]) = tangents(shape, x, st);
    (n, xp, cross(xs, xt))
}

/// The face's point at the centre of its reference domain.
pub fn centroid(shape: Shape, x: &[[f64; 3]; 8]) -> [f64; 3] {
    map_point(shape, x, shape.centre()).1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quad8_shape_functions_interpolate_and_sum_to_one() {
        // Kronecker at the nodes; partition of unity and zero derivative sums elsewhere
        // (to round-off, 1e-15).
        for (i, p) in QUAD_REFERENCE.iter().enumerate() {
            let (n, _, _) = quad8_shape(p[0], p[1]);
            for (j, v) in n.iter().enumerate() {
                assert!(
                    (v - f64::from(u8::from(i == j))).abs() < 1e-15,
                    "{i} {j} {v}"
                );
            }
        }
        let (n, ds, dt) = quad8_shape(0.3, -0.7);
        assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert!(ds.iter().sum::<f64>().abs() < 1e-15 && dt.iter().sum::<f64>().abs() < 1e-15);
        // Derivatives against central differences (h = 1e-6: error ~ h², 1e-9 allowed).
        let h = 1e-6;
        let (np, _, _) = quad8_shape(0.3 + h, -0.7);
        let (nm, _, _) = quad8_shape(0.3 - h, -0.7);
        let (nq, _, _) = quad8_shape(0.3, -0.7 + h);
        let (nr, _, _) = quad8_shape(0.3, -0.7 - h);
        for k in 0..8 {
            assert!(((np[k] - nm[k]) / (2.0 * h) - ds[k]).abs() < 1e-9);
            assert!(((nq[k] - nr[k]) / (2.0 * h) - dt[k]).abs() < 1e-9);
        }
    }

    #[test]
    fn subcells_cover_the_reference_domain() {
        // The sub-cells' reference areas sum to the domain's (1/2, 4), exactly in binary.
        for (shape, area) in [(Shape::Tri6, 0.5), (Shape::Quad8, 4.0)] {
            let sum: f64 = shape
                .subcells()
                .iter()
                .map(|(q, _)| {
                    let e1 = [q[1][0] - q[0][0], q[1][1] - q[0][1]];
                    let e2 = [q[2][0] - q[0][0], q[2][1] - q[0][1]];
                    0.5 * (e1[0] * e2[1] - e1[1] * e2[0])
                })
                .sum();
            assert_eq!(sum, area);
            let w: f64 = shape.rule().iter().map(|p| p.1).sum();
            assert!((w - area).abs() < 1e-15);
        }
    }
}
