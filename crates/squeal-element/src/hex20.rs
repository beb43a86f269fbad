//! The 20-node hexahedron (serendipity brick): Abaqus C3D20 / C3D20R, VTK 25
//! (`VTK_QUADRATIC_HEXAHEDRON`), Gmsh 17.
//!
//! Reference domain `[-1, 1]³`. Canonical order (Abaqus's, which is also VTK's): vertices
//! `0 (-,-,-), 1 (+,-,-), 2 (+,+,-), 3 (-,+,-)`, then `4..8` the same at `ζ = +1`; midside
//! nodes `8..20` on the edges `(0,1) (1,2) (2,3) (3,0)`, `(4,5) (5,6) (6,7) (7,4)`,
//! `(0,4) (1,5) (2,6) (3,7)`. Gmsh numbers the same vertices but its edges as
//! `(0,1) (0,3) (0,4) (1,2) (1,5) (2,3) (2,6) (3,7) (4,5) (4,7) (5,6) (6,7)`
//! (Gmsh reference manual, "Node ordering"): [`Hex20`]'s `GMSH_TO_CANONICAL` converts.
//!
//! Shape functions (Zienkiewicz & Taylor vol. 1, sec. 8.7), with `(ξ_a, η_a, ζ_a)` node `a`'s
//! reference coordinates:
//!
//! ```text
//! vertex:            N_a = (1 + ξξ_a)(1 + ηη_a)(1 + ζζ_a)(ξξ_a + ηη_a + ζζ_a - 2) / 8
//! midside, ξ_a = 0:  N_a = (1 - ξ²)(1 + ηη_a)(1 + ζζ_a) / 4   (likewise for η_a, ζ_a = 0)
//! ```
//!
//! # Quadrature
//!
//! - Full integration, 3×3×3 Gauss ([`Hex20`]'s `stiffness_rule`): exact for the stiffness of
//!   a parallelepiped (`J` constant, `Bᵀ C B` of degree 4 in each variable, the rule's degree
//!   is 5) and for the interior-node residual of a linear field on any element with straight
//!   edges (`adj(J)ᵀ ∇_ξN` of degree ≤ 4 in each variable): the patch test passes on
//!   distorted meshes (`tests/fe/solid.rs` of squeal-fe, `linear_fields_pass_the_patch_test_on_distorted_meshes`).
//! - Reduced integration, 2×2×2 Gauss (Abaqus C3D20R, [`Hex20`]'s `reduced_stiffness_rule`):
//!   cheaper, and softer, which offsets the stiffness the element's incomplete quadratic
//!   field adds in bending. It integrates degree 3 only, so a single element has spurious
//!   zero-energy ("hourglass") modes besides its six rigid motions (the stiffness, 60×60,
//!   has rank at most 48 with 8 points × 6 strains; measured: 12 zero eigenvalues, six
//!   spurious). Neighbours constrain most of them, but not all at once: measured on free
//!   meshes (`tests/fe/solid.rs` of squeal-fe), a row of two elements (2×1×1) still has 9 zero
//!   eigenvalues, a 2×2×2 block 6, the rigid motions only. So they are harmless in a mesh
//!   that is more than one element across in every direction, and need checking where it is
//!   not: a single element across the thickness, a one-element appendage, a row of elements.
//!   squeal assembles with the full rule; the reduced rule is for comparisons
//!   (`AssemblyOptions::reduced_integration` of squeal-fe).
//! - Mass: 4×4×4 Gauss, exact for the consistent mass of an element with straight edges
//!   (`N_a N_b det J` of degree 4 + 2 in each variable).

use crate::quadrature::Quadrature;
use crate::reference::{ElementKind, Face, ReferenceElement};

/// The 20-node hexahedron.
#[derive(Clone, Copy, Debug)]
pub struct Hex20;

/// Vertex pairs of the edges carrying midside nodes `8..20`.
pub const EDGES: [[usize; 2]; 12] = [
    [0, 1],
    [1, 2],
    [2, 3],
    [3, 0],
    [4, 5],
    [5, 6],
    [6, 7],
    [7, 4],
    [0, 4],
    [1, 5],
    [2, 6],
    [3, 7],
];

const VERTICES: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

const fn nodes_ref() -> [[f64; 3]; 20] {
    let mut p = [[0.0; 3]; 20];
    let mut i = 0;
    while i < 8 {
        p[i] = VERTICES[i];
        i += 1;
    }
    let mut k = 0;
    while k < 12 {
        let [a, b] = EDGES[k];
        let mut d = 0;
        while d < 3 {
            p[8 + k][d] = (VERTICES[a][d] + VERTICES[b][d]) * 0.5;
            d += 1;
        }
        k += 1;
    }
    p
}

impl ReferenceElement<20> for Hex20 {
    const KIND: ElementKind = ElementKind::Hex20;
    const VERTICES: usize = 8;
    const NODES_REF: [[f64; 3]; 20] = nodes_ref();
    const EDGES: &'static [[usize; 2]] = &EDGES;
    const FACES: &'static [Face] = &[
        Face::Quad8([0, 3, 2, 1, 11, 10, 9, 8]),
        Face::Quad8([4, 5, 6, 7, 12, 13, 14, 15]),
        Face::Quad8([0, 1, 5, 4, 8, 17, 12, 16]),
        Face::Quad8([1, 2, 6, 5, 9, 18, 13, 17]),
        Face::Quad8([2, 3, 7, 6, 10, 19, 14, 18]),
        Face::Quad8([3, 0, 4, 7, 11, 16, 15, 19]),
    ];
    const VTK_CELL_TYPE: u8 = 25;
    const VTK_ORDER: [usize; 20] = [
        0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19,
    ];
    const GMSH_TYPE: i32 = 17;
    const GMSH_TO_CANONICAL: [usize; 20] = [
        0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15,
    ];

    fn shape(xi: [f64; 3]) -> [f64; 20] {
        std::array::from_fn(|a| {
            let p = Self::NODES_REF[a];
            let f = |d: usize| 1.0 + xi[d] * p[d];
            if a < 8 {
                0.125 * f(0) * f(1) * f(2) * (xi[0] * p[0] + xi[1] * p[1] + xi[2] * p[2] - 2.0)
            } else {
                let k = midside_axis(p);
                let (j, l) = ((k + 1) % 3, (k + 2) % 3);
                0.25 * (1.0 - xi[k] * xi[k]) * f(j) * f(l)
            }
        })
    }

    fn shape_gradients(xi: [f64; 3]) -> [[f64; 3]; 20] {
        std::array::from_fn(|a| {
            let p = Self::NODES_REF[a];
            let f = |d: usize| 1.0 + xi[d] * p[d];
            if a < 8 {
                let s = xi[0] * p[0] + xi[1] * p[1] + xi[2] * p[2] - 2.0;
                // ∂/∂ξ_d of f0 f1 f2 s = p_d (f_j f_l) (s + f_d).
                std::array::from_fn(|d| {
                    let (j, l) = ((d + 1) % 3, (d + 2) % 3);
                    0.125 * p[d] * f(j) * f(l) * (s + f(d))
                })
            } else {
                let k = midside_axis(p);
                let (j, l) = ((k + 1) % 3, (k + 2) % 3);
                let mut g = [0.0; 3];
                g[k] = -0.5 * xi[k] * f(j) * f(l);
                g[j] = 0.25 * (1.0 - xi[k] * xi[k]) * p[j] * f(l);
                g[l] = 0.25 * (1.0 - xi[k] * xi[k]) * f(j) * p[l];
                g
            }
        })
    }

    fn stiffness_rule() -> Quadrature {
        gauss(3)
    }

    fn reduced_stiffness_rule() -> Option<Quadrature> {
        Some(gauss(2))
    }

    fn mass_rule() -> Quadrature {
        gauss(4)
    }
}

/// The axis along which a midside node's reference coordinate is 0.
fn midside_axis(p: [f64; 3]) -> usize {
    (0..3).find(|&d| p[d] == 0.0).unwrap_or(0)
}

fn gauss(n: usize) -> Quadrature {
    Quadrature::hex_product(n)
}
