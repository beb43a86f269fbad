//! The 13-node pyramid: VTK 27 (`VTK_QUADRATIC_PYRAMID`), Gmsh 19 (Abaqus has no such
//! element).
//!
//! Reference domain: the square base `[-1, 1]²` at `ζ = 0` and the apex `(0, 0, 1)`.
//! Canonical order (VTK's): base vertices `0 (-1,-1), 1 (1,-1), 2 (1,1), 3 (-1,1)`, whose
//! normal by the right-hand rule points to the apex `4`; midside nodes `5..13` on the edges
//! `(0,1) (1,2) (2,3) (3,0) (0,4) (1,4) (2,4) (3,4)`. Gmsh has the same vertices and the edges
//! `(0,1) (0,3) (0,4) (1,2) (1,4) (2,3) (2,4) (3,4)`.
//!
//! # Shape functions
//!
//! No polynomial space of 13 functions on the pyramid is conforming with both the 8-node
//! quadrilateral on the base and the 6-node triangles on the sides; the shape functions are
//! rational (Bedrosian, "Shape functions and integration formulas for three-dimensional
//! finite element analysis", Int. J. Numer. Methods Eng. 35, 1992, 95–108). With
//! `r = 1 - ζ` and a vertex at `(ξ_i, η_i)`:
//!
//! ```text
//! base vertex:        N = (ξ_i ξ + η_i η - 1) ((1 + ξ_i ξ)(1 + η_i η) - ζ + ξ_i η_i ξ η ζ / r) / 4
//! apex:               N = ζ (2ζ - 1)
//! base midside, ξ=0:  N = (r² - ξ²)(r + η_m η) / (2r)     (η_m = ±1; likewise with ξ, η swapped)
//! side midside of i:  N = ζ (r + ξ_i ξ)(r + η_i η) / r
//! ```
//!
//! They are nodal, sum to one, reproduce linear fields, and reduce to the 8-node serendipity
//! quadrilateral on the base and to the 6-node triangle on each side face (unit tests below),
//! so pyramids conform with hex20 and wedge15 (on quadrilaterals) and with tet10 (on
//! triangles). The gradients are bounded but have no limit at the apex, which no rule
//! samples.
//!
//! # Quadrature
//!
//! In the collapsed coordinates of [`Quadrature::pyramid_gauss`] (`ξ = u r`, `η = v r`,
//! `ζ = w`) the shape functions and their gradients are polynomials: the functions of degree
//! ≤ 2 in `u`, `v` and ≤ 3 in `w`, the gradients ≤ 2 in each. With the Jacobian `r²`, the
//! stiffness of a pyramid with a parallelogram base (affine map) has degree ≤ 4 in `u`, `v`
//! and ≤ 6 in `w`: 3 × 3 × 4 points integrate it exactly. Mass: degree ≤ 4 and ≤ 8, 3 × 3 × 5
//! points.

use crate::quadrature::Quadrature;
use crate::reference::{ElementKind, Face, ReferenceElement};

/// The 13-node pyramid.
#[derive(Clone, Copy, Debug)]
pub struct Pyramid13;

/// Vertex pairs of the edges carrying midside nodes `5..13`.
pub const EDGES: [[usize; 2]; 8] = [
    [0, 1],
    [1, 2],
    [2, 3],
    [3, 0],
    [0, 4],
    [1, 4],
    [2, 4],
    [3, 4],
];

/// `(ξ_i, η_i)` of the base vertices.
const BASE: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

const fn nodes_ref() -> [[f64; 3]; 13] {
    let mut p = [[0.0; 3]; 13];
    let mut i = 0;
    while i < 4 {
        p[i] = [BASE[i][0], BASE[i][1], 0.0];
        i += 1;
    }
    p[4] = [0.0, 0.0, 1.0];
    let mut k = 0;
    while k < 8 {
        let [a, b] = EDGES[k];
        let mut d = 0;
        while d < 3 {
            p[5 + k][d] = (p[a][d] + p[b][d]) * 0.5;
            d += 1;
        }
        k += 1;
    }
    p
}

impl ReferenceElement<13> for Pyramid13 {
    const KIND: ElementKind = ElementKind::Pyramid13;
    const VERTICES: usize = 5;
    const NODES_REF: [[f64; 3]; 13] = nodes_ref();
    const EDGES: &'static [[usize; 2]] = &EDGES;
    const FACES: &'static [Face] = &[
        Face::Quad8([0, 3, 2, 1, 8, 7, 6, 5]),
        Face::Tri6([0, 1, 4, 5, 10, 9]),
        Face::Tri6([1, 2, 4, 6, 11, 10]),
        Face::Tri6([2, 3, 4, 7, 12, 11]),
        Face::Tri6([3, 0, 4, 8, 9, 12]),
    ];
    const VTK_CELL_TYPE: u8 = 27;
    const VTK_ORDER: [usize; 13] = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12];
    const GMSH_TYPE: i32 = 19;
    const GMSH_TO_CANONICAL: [usize; 13] = [0, 1, 2, 3, 4, 5, 8, 10, 6, 7, 9, 11, 12];

    fn shape(xi: [f64; 3]) -> [f64; 13] {
        let [x, y, z] = xi;
        let r = 1.0 - z;
        if r == 0.0 {
            // The apex: every other function vanishes there (their limits are 0).
            return std::array::from_fn(|a| if a == 4 { 1.0 } else { 0.0 });
        }
        let mut n = [0.0; 13];
        for (i, [a, b]) in BASE.iter().enumerate() {
            let big = (1.0 + a * x) * (1.0 + b * y) - z + a * b * x * y * z / r;
            n[i] = 0.25 * (a * x + b * y - 1.0) * big;
            n[9 + i] = z * (r + a * x) * (r + b * y) / r;
        }
        n[4] = z * (2.0 * z - 1.0);
        for (k, m) in n[5..9].iter_mut().enumerate() {
            let [u, v] = base_midside(k);
            *m = if u == 0.0 {
                (r * r - x * x) * (r + v * y) / (2.0 * r)
            } else {
                (r * r - y * y) * (r + u * x) / (2.0 * r)
            };
        }
        n
    }

    fn shape_gradients(xi: [f64; 3]) -> [[f64; 3]; 13] {
        let [x, y, z] = xi;
        let r = 1.0 - z;
        let mut g = [[0.0; 3]; 13];
        for (i, [a, b]) in BASE.iter().enumerate() {
            // Vertex: N = A B / 4.
            let big_a = a * x + b * y - 1.0;
            let big_b = (1.0 + a * x) * (1.0 + b * y) - z + a * b * x * y * z / r;
            let db = [
                a * (1.0 + b * y) + a * b * y * z / r,
                b * (1.0 + a * x) + a * b * x * z / r,
                -1.0 + a * b * x * y / (r * r),
            ];
            let da = [*a, *b, 0.0];
            g[i] = std::array::from_fn(|d| 0.25 * (da[d] * big_b + big_a * db[d]));
            // Side midside: N = ζ S T / r, S = r + ξ_i ξ, T = r + η_i η.
            let (s, t) = (r + a * x, r + b * y);
            g[9 + i] = [
                z * a * t / r,
                z * s * b / r,
                s * t / r - z * (s + t) / r + z * s * t / (r * r),
            ];
        }
        g[4] = [0.0, 0.0, 4.0 * z - 1.0];
        for k in 0..4 {
            let [u, v] = base_midside(k);
            // N = P Q / (2r): P = r² - ξ², Q = r + η_m η (or with ξ, η swapped).
            let (along, across, m, swap) = if u == 0.0 {
                (x, y, v, false)
            } else {
                (y, x, u, true)
            };
            let (p, q) = (r * r - along * along, r + m * across);
            let d_along = -along * q / r;
            let d_across = p * m / (2.0 * r);
            let dz = (-2.0 * r * q - p) / (2.0 * r) + p * q / (2.0 * r * r);
            g[5 + k] = if swap {
                [d_across, d_along, dz]
            } else {
                [d_along, d_across, dz]
            };
        }
        g
    }

    fn stiffness_rule() -> Quadrature {
        Quadrature::pyramid_product(3, 4)
    }

    fn mass_rule() -> Quadrature {
        Quadrature::pyramid_product(3, 5)
    }

    /// The nodes but the apex (where the gradients have no limit), and the stiffness rule's
    /// points.
    fn jacobian_samples() -> Vec<[f64; 3]> {
        let mut p: Vec<[f64; 3]> = Self::NODES_REF
            .iter()
            .enumerate()
            .filter(|(a, _)| *a != 4)
            .map(|(_, p)| *p)
            .collect();
        p.extend(Self::stiffness_rule().points);
        p
    }
}

/// `(ξ, η)` of base midside node `5 + k`.
fn base_midside(k: usize) -> [f64; 2] {
    let [a, b] = EDGES[k];
    [
        0.5 * (BASE[a][0] + BASE[b][0]),
        0.5 * (BASE[a][1] + BASE[b][1]),
    ]
}
