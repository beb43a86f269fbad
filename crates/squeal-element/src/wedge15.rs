//! The 15-node wedge (triangular prism): Abaqus C3D15, VTK 26 (`VTK_QUADRATIC_WEDGE`),
//! Gmsh 18.
//!
//! Reference domain: the triangle `{ξ, η ≥ 0, ξ + η ≤ 1}` times `ζ ∈ [-1, 1]`, with the
//! triangle's barycentric coordinates `L = (1 - ξ - η, ξ, η)`. Canonical order (Abaqus's):
//! vertices `0, 1, 2` at `ζ = -1` on `L_0, L_1, L_2 = 1`, then `3, 4, 5` above them at
//! `ζ = +1`; midside nodes `6..15` on the edges `(0,1) (1,2) (2,0)`, `(3,4) (4,5) (5,3)`,
//! `(0,3) (1,4) (2,5)`. The triangle `0, 1, 2` is counter-clockwise seen from the top face.
//!
//! - Gmsh (type 18) has the same vertices and the edges `(0,1) (0,2) (0,3) (1,2) (1,4)
//!   (2,5) (3,4) (3,5) (4,5)`.
//! - VTK (type 26) orders the edges as Abaqus does but orients the wedge the other way: its
//!   triangle `(0, 1, 2)` has its normal pointing *away* from `(3, 4, 5)` (VTK's `vtkWedge`
//!   documentation; meshio converts with the same permutation): `VTK_ORDER` swaps vertices 1
//!   and 2, 4 and 5, and their edges.
//!
//! Shape functions (Zienkiewicz & Taylor vol. 1, sec. 8.8), `t` the triangle vertex and
//! `s = ±1` the level of the node:
//!
//! ```text
//! vertex:                  N = L_t (1 + sζ)(2 L_t + sζ - 2) / 2
//! midside of (t, u) at s:  N = 2 L_t L_u (1 + sζ)
//! midside of (t, t + 3):   N = L_t (1 - ζ²)
//! ```
//!
//! Quadrature ([`Quadrature::wedge_gauss`]): the stiffness integrand of an element with
//! straight edges has degree ≤ 4 in `(ξ, η)` and in `ζ` for the terms the patch test needs
//! (and for the whole stiffness of a right prism), so the full rule is the 9-point collapsed
//! triangle rule (degree 4) times 3 Gauss points (degree 5), 27 points. Mass: 16 × 4 points
//! (degree 6 and 7), exact for elements with straight edges (`N_a N_b det J`: degree 5 in
//! the triangle, 6 in `ζ`).

use crate::quadrature::Quadrature;
use crate::reference::{ElementKind, Face, ReferenceElement};

/// The 15-node wedge.
#[derive(Clone, Copy, Debug)]
pub struct Wedge15;

/// Vertex pairs of the edges carrying midside nodes `6..15`.
pub const EDGES: [[usize; 2]; 9] = [
    [0, 1],
    [1, 2],
    [2, 0],
    [3, 4],
    [4, 5],
    [5, 3],
    [0, 3],
    [1, 4],
    [2, 5],
];

/// Triangle coordinates `(ξ, η)` of the triangle's vertices.
const TRI: [[f64; 2]; 3] = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];

/// Gradients of the barycentric coordinates with respect to `(ξ, η)`.
const DL: [[f64; 2]; 3] = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];

const fn nodes_ref() -> [[f64; 3]; 15] {
    let mut p = [[0.0; 3]; 15];
    let mut i = 0;
    while i < 6 {
        let t = i % 3;
        p[i] = [TRI[t][0], TRI[t][1], if i < 3 { -1.0 } else { 1.0 }];
        i += 1;
    }
    let mut k = 0;
    while k < 9 {
        let [a, b] = EDGES[k];
        let mut d = 0;
        while d < 3 {
            p[6 + k][d] = (p[a][d] + p[b][d]) * 0.5;
            d += 1;
        }
        k += 1;
    }
    p
}

fn barycentric(xi: [f64; 3]) -> [f64; 3] {
    [1.0 - xi[0] - xi[1], xi[0], xi[1]]
}

/// What node `a` is: a vertex `(t, s)`, a triangle-edge midside `(t, u, s)` or a vertical
/// midside over `t`.
enum Role {
    Vertex(usize, f64),
    TriangleEdge(usize, usize, f64),
    Vertical(usize),
}

fn role(a: usize) -> Role {
    let level = |n: usize| if n < 3 { -1.0 } else { 1.0 };
    if a < 6 {
        return Role::Vertex(a % 3, level(a));
    }
    let [p, q] = EDGES[a - 6];
    if a < 12 {
        Role::TriangleEdge(p % 3, q % 3, level(p))
    } else {
        Role::Vertical(p)
    }
}

impl ReferenceElement<15> for Wedge15 {
    const KIND: ElementKind = ElementKind::Wedge15;
    const VERTICES: usize = 6;
    const NODES_REF: [[f64; 3]; 15] = nodes_ref();
    const EDGES: &'static [[usize; 2]] = &EDGES;
    const FACES: &'static [Face] = &[
        Face::Tri6([0, 2, 1, 8, 7, 6]),
        Face::Tri6([3, 4, 5, 9, 10, 11]),
        Face::Quad8([0, 1, 4, 3, 6, 13, 9, 12]),
        Face::Quad8([1, 2, 5, 4, 7, 14, 10, 13]),
        Face::Quad8([0, 3, 5, 2, 12, 11, 14, 8]),
    ];
    const VTK_CELL_TYPE: u8 = 26;
    const VTK_ORDER: [usize; 15] = [0, 2, 1, 3, 5, 4, 8, 7, 6, 11, 10, 9, 12, 14, 13];
    const GMSH_TYPE: i32 = 18;
    const GMSH_TO_CANONICAL: [usize; 15] = [0, 1, 2, 3, 4, 5, 6, 9, 7, 12, 14, 13, 8, 10, 11];

    fn shape(xi: [f64; 3]) -> [f64; 15] {
        let l = barycentric(xi);
        let z = xi[2];
        std::array::from_fn(|a| match role(a) {
            Role::Vertex(t, s) => 0.5 * l[t] * (1.0 + s * z) * (2.0 * l[t] + s * z - 2.0),
            Role::TriangleEdge(t, u, s) => 2.0 * l[t] * l[u] * (1.0 + s * z),
            Role::Vertical(t) => l[t] * (1.0 - z * z),
        })
    }

    fn shape_gradients(xi: [f64; 3]) -> [[f64; 3]; 15] {
        let l = barycentric(xi);
        let z = xi[2];
        std::array::from_fn(|a| match role(a) {
            Role::Vertex(t, s) => {
                let c = 0.5 * (1.0 + s * z) * (4.0 * l[t] + s * z - 2.0);
                [
                    c * DL[t][0],
                    c * DL[t][1],
                    0.5 * l[t] * s * (2.0 * l[t] + 2.0 * s * z - 1.0),
                ]
            }
            Role::TriangleEdge(t, u, s) => {
                let c = 2.0 * (1.0 + s * z);
                [
                    c * (DL[t][0] * l[u] + l[t] * DL[u][0]),
                    c * (DL[t][1] * l[u] + l[t] * DL[u][1]),
                    2.0 * l[t] * l[u] * s,
                ]
            }
            Role::Vertical(t) => [
                DL[t][0] * (1.0 - z * z),
                DL[t][1] * (1.0 - z * z),
                -2.0 * z * l[t],
            ],
        })
    }

    fn stiffness_rule() -> Quadrature {
        Quadrature::wedge_product(3, 3)
    }

    fn mass_rule() -> Quadrature {
        Quadrature::wedge_product(4, 4)
    }
}
