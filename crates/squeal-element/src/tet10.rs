//! The 10-node tetrahedron in squeal's canonical node ordering.
//!
//! The canonical ordering is Abaqus C3D10's, which is also VTK's quadratic tetra (cell type 24):
//! vertices 0–3, then the midside nodes of edges
//! `4:(0,1) 5:(1,2) 6:(2,0) 7:(0,3) 8:(1,3) 9:(2,3)`.
//! Gmsh's type 11 puts the midside nodes of edges (2,3) and (1,3) the other way round
//! (its node 8 is on edge (2,3), its node 9 on edge (1,3)): [`GMSH_TO_CANONICAL`] converts.
//!
//! Reference coordinates `(ξ, η, ζ)` with barycentric `L = (1-ξ-η-ζ, ξ, η, ζ)`; vertex `i` sits
//! at `L_i = 1`. Shape functions: `N_i = L_i (2 L_i - 1)` at the vertices and `4 L_a L_b` at
//! the midside node of edge `(a, b)`.
//!
//! Quadrature ([`Tet10`]'s [`ReferenceElement`] rules): stiffness by the 4-point rule of
//! degree 2, exact for straight-sided elements (`det J` constant, integrand of degree 2);
//! consistent mass by the 14-point rule of degree 5 (integrand of degree 4). The finite
//! element crate integrates curved elements' stiffness with the 24-point rule of degree 6
//! (see `squeal_fe::element`).

use crate::quadrature::Quadrature;
pub use crate::reference::det3;
use crate::reference::{ElementKind, Face, ReferenceElement};

/// The 10-node tetrahedron (Abaqus C3D10, VTK 24, Gmsh 11).
#[derive(Clone, Copy, Debug)]
pub struct Tet10;

impl ReferenceElement<10> for Tet10 {
    const KIND: ElementKind = ElementKind::Tet10;
    const VERTICES: usize = 4;
    const NODES_REF: [[f64; 3]; 10] = NODES_REF;
    const EDGES: &'static [[usize; 2]] = &EDGES;
    const FACES: &'static [Face] = &[
        Face::Tri6(FACES[0]),
        Face::Tri6(FACES[1]),
        Face::Tri6(FACES[2]),
        Face::Tri6(FACES[3]),
    ];
    const VTK_CELL_TYPE: u8 = 24;
    const VTK_ORDER: [usize; 10] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9];
    const GMSH_TYPE: i32 = 11;
    const GMSH_TO_CANONICAL: [usize; 10] = GMSH_TO_CANONICAL;

    fn shape(xi: [f64; 3]) -> [f64; 10] {
        shape(xi)
    }

    fn shape_gradients(xi: [f64; 3]) -> [[f64; 3]; 10] {
        shape_gradients(xi)
    }

    fn stiffness_rule() -> Quadrature {
        Quadrature::four_point()
    }

    fn mass_rule() -> Quadrature {
        Quadrature::fourteen_point()
    }

    /// [`volume`]: Keast's 5-point rule, exact for curved elements too.
    fn volume(x: &[[f64; 3]; 10]) -> f64 {
        volume(x)
    }

    /// The ten nodes, the centroid and the four points of the degree-2 rule.
    fn jacobian_samples() -> Vec<[f64; 3]> {
        let a = 0.585_410_196_624_968_5;
        let b = 0.138_196_601_125_010_5;
        let mut p: Vec<[f64; 3]> = NODES_REF.to_vec();
        p.push([0.25, 0.25, 0.25]);
        p.extend([[b, b, b], [a, b, b], [b, a, b], [b, b, a]]);
        p
    }
}

/// Vertex pairs of the edges carrying midside nodes 4..10, in canonical order.
pub const EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]];

/// `canonical[i] = gmsh[GMSH_TO_CANONICAL[i]]`.
pub const GMSH_TO_CANONICAL: [usize; 10] = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8];

/// The four faces as 6-node triangles `[v0, v1, v2, m01, m12, m20]` (local node numbers),
/// oriented so that `(x1 - x0) × (x2 - x0)` points out of a positively oriented element.
pub const FACES: [[usize; 6]; 4] = [
    [0, 2, 1, 6, 5, 4],
    [0, 1, 3, 4, 8, 7],
    [1, 2, 3, 5, 9, 8],
    [0, 3, 2, 7, 9, 6],
];

/// Reference coordinates of the ten nodes.
pub const NODES_REF: [[f64; 3]; 10] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.5, 0.0, 0.0],
    [0.5, 0.5, 0.0],
    [0.0, 0.5, 0.0],
    [0.0, 0.0, 0.5],
    [0.5, 0.0, 0.5],
    [0.0, 0.5, 0.5],
];

fn barycentric(xi: [f64; 3]) -> [f64; 4] {
    [1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]]
}

/// Gradients of the barycentric coordinates with respect to `(ξ, η, ζ)`.
const DL: [[f64; 3]; 4] = [
    [-1.0, -1.0, -1.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
];

/// Shape function values at reference point `xi`.
pub fn shape(xi: [f64; 3]) -> [f64; 10] {
    let l = barycentric(xi);
    let mut n = [0.0; 10];
    for i in 0..4 {
        n[i] = l[i] * (2.0 * l[i] - 1.0);
    }
    for (k, [a, b]) in EDGES.iter().enumerate() {
        n[4 + k] = 4.0 * l[*a] * l[*b];
    }
    n
}

/// Shape function gradients `dN[i][j] = ∂N_i/∂ξ_j` at reference point `xi`.
pub fn shape_gradients(xi: [f64; 3]) -> [[f64; 3]; 10] {
    let l = barycentric(xi);
    let mut g = [[0.0; 3]; 10];
    for i in 0..4 {
        for j in 0..3 {
            g[i][j] = (4.0 * l[i] - 1.0) * DL[i][j];
        }
    }
    for (k, [a, b]) in EDGES.iter().enumerate() {
        for j in 0..3 {
            g[4 + k][j] = 4.0 * (l[*b] * DL[*a][j] + l[*a] * DL[*b][j]);
        }
    }
    g
}

/// Jacobian `J[i][j] = ∂x_i/∂ξ_j` of the isoparametric map at `xi`.
pub fn jacobian(x: &[[f64; 3]; 10], xi: [f64; 3]) -> [[f64; 3]; 3] {
    crate::reference::jacobian::<Tet10, 10>(x, xi)
}

/// Volume of an element from its nodes' coordinates in canonical order: the integral of the
/// Jacobian determinant by Keast's 5-point degree-3 rule, exact for straight-sided and curved
/// elements alike (the determinant is a cubic). Negative for an inverted element.
pub fn volume(x: &[[f64; 3]; 10]) -> f64 {
    // Keast degree-3 rule (5 points, one negative weight) is exact for det J of a
    // straight-sided element (constant) and of degree 3 in general.
    const A: f64 = 0.25;
    const B: f64 = 1.0 / 6.0;
    const C: f64 = 0.5;
    let pts: [([f64; 3], f64); 5] = [
        ([A, A, A], -4.0 / 5.0),
        ([B, B, B], 9.0 / 20.0),
        ([C, B, B], 9.0 / 20.0),
        ([B, C, B], 9.0 / 20.0),
        ([B, B, C], 9.0 / 20.0),
    ];
    pts.iter()
        .map(|(p, w)| w * det3(&jacobian(x, *p)))
        .sum::<f64>()
        / 6.0
}

/// How far the element is from straight-sided: the largest distance of a midside node from
/// the midpoint of its edge, relative to that edge's length (0 for a straight-sided element,
/// whose map from the reference element is affine; infinite for an edge of zero length).
pub fn midside_offset(x: &[[f64; 3]; 10]) -> f64 {
    crate::reference::midside_offset::<Tet10, 10>(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shape_functions_are_nodal_and_sum_to_one() {
        for (i, p) in NODES_REF.iter().enumerate() {
            let n = shape(*p);
            for (j, v) in n.iter().enumerate() {
                let expect = if i == j { 1.0 } else { 0.0 };
                assert!((v - expect).abs() < 1e-15, "N_{j}(node {i}) = {v}");
            }
        }
        let n = shape([0.1, 0.2, 0.3]);
        assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn gradients_match_finite_differences() {
        let p = [0.13, 0.21, 0.37];
        let g = shape_gradients(p);
        let h = 1e-6;
        for j in 0..3 {
            let mut a = p;
            let mut b = p;
            a[j] += h;
            b[j] -= h;
            let (na, nb) = (shape(a), shape(b));
            for i in 0..10 {
                let fd = (na[i] - nb[i]) / (2.0 * h);
                // Central differences of a quadratic are exact up to round-off.
                assert!(
                    (fd - g[i][j]).abs() < 1e-9,
                    "dN{i}/dxi{j}: {fd} vs {}",
                    g[i][j]
                );
            }
        }
    }

    #[test]
    fn midside_offset_is_relative_to_the_edge() {
        assert_eq!(midside_offset(&NODES_REF), 0.0);
        // Midside node 9 of edge (2, 3), length √2, moved by 0.1 across it.
        let mut x = NODES_REF;
        x[9][0] += 0.1;
        assert!((midside_offset(&x) - 0.1 / 2f64.sqrt()).abs() < 1e-15);
        // Scaled by 1000: the same.
        let big = x.map(|p| p.map(|v| 1000.0 * v));
        assert!((midside_offset(&big) - 0.1 / 2f64.sqrt()).abs() < 1e-15);
        // A collapsed edge.
        let mut flat = NODES_REF;
        flat[1] = flat[0];
        assert_eq!(midside_offset(&flat), f64::INFINITY);
    }

    #[test]
    fn reference_element_volume_is_one_sixth() {
        assert!((volume(&NODES_REF) - 1.0 / 6.0).abs() < 1e-15);
    }
}
