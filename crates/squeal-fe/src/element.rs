//! Element matrices of the isoparametric 10-node tetrahedron (canonical node ordering of
//! [`squeal_mesh::tet10`]; midside nodes may be off the edge midpoints).
//!
//! Local dof `3 a + d` is direction `d` (0 = x, 1 = y, 2 = z) of node `a`, as in the global
//! node-major numbering. With `B` the strain–displacement matrix (Voigt order
//! `11, 22, 33, 12, 13, 23`, engineering shear strains) and `N` the shape functions:
//!
//! - stiffness `K_e = ∫ Bᵀ C B dV`,
//! - consistent mass `M_e = ∫ ρ Nᵀ N dV`, which is `m_ab I₃` with `m_ab = ρ ∫ N_a N_b dV`.
//!
//! Both are computed from the upper triangle and mirrored, so they are symmetric bit for bit.
//!
//! # Quadrature of the stiffness
//!
//! With `x(ξ) = Σ_a x_a N_a(ξ)` the Jacobian `J = ∂x/∂ξ` is linear in `ξ` and `det J` cubic.
//! The physical gradients are `∇N = J⁻ᵀ ∇_ξ N = adj(J)ᵀ ∇_ξ N / det J`, so
//!
//! ```text
//! K_e = ∫_ref Bᵀ C B det J dξ,   Bᵀ C B det J = (∇_ξN)ᵀ adj(J) C' adj(J)ᵀ (∇_ξN) / det J,
//! ```
//!
//! a polynomial of degree 1 + 2 + 2 + 1 = 6 over the cubic `det J` (C' is C rearranged for
//! the 3×3 blocks).
//!
//! - Straight-sided element (midside nodes at the edge midpoints): `J` is constant, the
//!   integrand is the degree-2 polynomial `Bᵀ C B det J`, and the 4-point rule of degree 2 is
//!   exact.
//! - Curved element: the integrand is rational, so no rule is exact. Moving the midside nodes
//!   by `δ` (relative to the edge) adds to the integrand a first-order term of degree 3,
//!   which the 4-point rule misses: its error grows like `δ` (0.31 δ measured on an element of
//!   the coarse disc). On the disc's bore and hat (midside nodes on circles, `δ` up to 0.09)
//!   that shifted frequencies by up to 7.5e-4. A degree-6 rule integrates the numerator
//!   exactly where `det J` is constant and leaves an error of high order in `δ`
//!   (1e-10 at `δ` = 1e-2, round-off at 1e-3 on the same element):
//!   [`crate::Quadrature::twenty_four_point`] (Keast's positive 24-point rule).
//!
//! Remaining error of the 24-point rule, against a collapsed Gauss rule of 12³ points
//! (converged: 12³ and 20³ points agree to 4e-15), measured in `tests/curved.rs`: on the
//! coarse disc's elements, at most 5.6e-5 relative (Frobenius norm of `K_e`; 4.4e-8 on its
//! element with the largest midside offset), and at most 5.7e-8 on its 20 lowest
//! clamped frequencies (the 4-point rule: 7.5e-4). Which elements are curved:
//! [`crate::AssemblyOptions`].
//!
//! The consistent mass `ρ N_a N_b det J` is a polynomial of degree 4 + 3 = 7 on a curved
//! element; the 14-point rule (degree 5) misses at most 8e-6 of an element's mass matrix on
//! the coarse disc, which moves its frequencies by 1e-11: it is kept.

use crate::error::ElementError;
use crate::material::Voigt6;
use crate::quadrature::Quadrature;
use squeal_mesh::tet10;

/// Node coordinates of one element in canonical order.
pub type ElementCoords = [[f64; 3]; 10];

/// Shape function gradients with respect to `x` (`g[a][j] = ∂N_a/∂x_j`) and `det J` at the
/// reference point `xi`; an error if `det J ≤ 0` (`point` names the quadrature point).
pub fn physical_gradients(
    x: &ElementCoords,
    xi: [f64; 3],
    point: usize,
) -> Result<([[f64; 3]; 10], f64), ElementError> {
    let g_ref = tet10::shape_gradients(xi);
    let mut j = [[0.0; 3]; 3];
    for (xn, gn) in x.iter().zip(&g_ref) {
        for r in 0..3 {
            for c in 0..3 {
                j[r][c] += xn[r] * gn[c];
            }
        }
    }
    let det = tet10::det3(&j);
    if !(det > 0.0 && det.is_finite()) {
        return Err(ElementError::NonPositiveJacobian { point, det });
    }
    // J⁻¹ by cofactors: inv[k][m] = ∂ξ_k/∂x_m.
    let inv = [
        [
            (j[1][1] * j[2][2] - j[1][2] * j[2][1]) / det,
            (j[0][2] * j[2][1] - j[0][1] * j[2][2]) / det,
            (j[0][1] * j[1][2] - j[0][2] * j[1][1]) / det,
        ],
        [
            (j[1][2] * j[2][0] - j[1][0] * j[2][2]) / det,
            (j[0][0] * j[2][2] - j[0][2] * j[2][0]) / det,
            (j[0][2] * j[1][0] - j[0][0] * j[1][2]) / det,
        ],
        [
            (j[1][0] * j[2][1] - j[1][1] * j[2][0]) / det,
            (j[0][1] * j[2][0] - j[0][0] * j[2][1]) / det,
            (j[0][0] * j[1][1] - j[0][1] * j[1][0]) / det,
        ],
    ];
    let g = g_ref.map(|gr| {
        std::array::from_fn(|m| gr[0] * inv[0][m] + gr[1] * inv[1][m] + gr[2] * inv[2][m])
    });
    Ok((g, det))
}

/// `C B_b` for one node: the 6×3 product of the elasticity matrix with the node's block of
/// `B`, whose columns are `(gx,0,0,gy,gz,0)`, `(0,gy,0,gx,0,gz)`, `(0,0,gz,0,gx,gy)`.
fn c_times_b(c: &Voigt6, g: [f64; 3], scale: f64) -> [[f64; 3]; 6] {
    let [gx, gy, gz] = g.map(|v| v * scale);
    std::array::from_fn(|i| {
        let ci = &c[i];
        [
            ci[0] * gx + ci[3] * gy + ci[4] * gz,
            ci[1] * gy + ci[3] * gx + ci[5] * gz,
            ci[2] * gz + ci[4] * gx + ci[5] * gy,
        ]
    })
}

/// Element stiffness `K_e = Σ_q w_q det J_q B_qᵀ C B_q` (Zienkiewicz & Taylor, The Finite
/// Element Method vol. 1, eq. 6.9). The 4-point rule ([`Quadrature::four_point`]) is exact for
/// straight-sided elements; for curved ones see the module documentation.
pub fn element_stiffness(
    x: &ElementCoords,
    c: &Voigt6,
    rule: &Quadrature,
) -> Result<[[f64; 30]; 30], ElementError> {
    let mut k = [[0.0; 30]; 30];
    for (q, (xi, w)) in rule.points.iter().zip(&rule.weights).enumerate() {
        let (g, det) = physical_gradients(x, *xi, q)?;
        let cb: [[[f64; 3]; 6]; 10] = std::array::from_fn(|b| c_times_b(c, g[b], w * det));
        for a in 0..10 {
            let [gx, gy, gz] = g[a];
            for (b, cbb) in cb.iter().enumerate().skip(a) {
                for d in 0..3 {
                    // Row d of B_aᵀ (C B_b).
                    let row = [
                        gx * cbb[0][d] + gy * cbb[3][d] + gz * cbb[4][d],
                        gy * cbb[1][d] + gx * cbb[3][d] + gz * cbb[5][d],
                        gz * cbb[2][d] + gx * cbb[4][d] + gy * cbb[5][d],
                    ];
                    for (p, v) in row.iter().enumerate() {
                        k[3 * a + p][3 * b + d] += v;
                    }
                }
            }
        }
    }
    mirror_upper(&mut k);
    Ok(k)
}

/// The scalar consistent mass `m_ab = ρ Σ_q w_q det J_q N_a N_b` (the element mass matrix is
/// `m_ab I₃`). The 14-point rule ([`Quadrature::fourteen_point`]) is exact for straight-sided
/// elements.
pub fn element_mass_scalar(
    x: &ElementCoords,
    density: f64,
    rule: &Quadrature,
) -> Result<[[f64; 10]; 10], ElementError> {
    let mut m = [[0.0; 10]; 10];
    for (q, (xi, w)) in rule.points.iter().zip(&rule.weights).enumerate() {
        let (_, det) = physical_gradients(x, *xi, q)?;
        let n = tet10::shape(*xi);
        let s = density * w * det;
        for a in 0..10 {
            let sa = s * n[a];
            for b in a..10 {
                m[a][b] += sa * n[b];
            }
        }
    }
    mirror_upper(&mut m);
    Ok(m)
}

/// Consistent element mass `M_e = ∫ ρ Nᵀ N dV` as a 30×30 matrix (see
/// [`element_mass_scalar`]).
pub fn element_mass(
    x: &ElementCoords,
    density: f64,
    rule: &Quadrature,
) -> Result<[[f64; 30]; 30], ElementError> {
    let s = element_mass_scalar(x, density, rule)?;
    let mut m = [[0.0; 30]; 30];
    for a in 0..10 {
        for b in 0..10 {
            for d in 0..3 {
                m[3 * a + d][3 * b + d] = s[a][b];
            }
        }
    }
    Ok(m)
}

/// Element volume `Σ_q w_q det J_q` (exact for straight-sided elements with any rule, for
/// curved ones with a rule of degree 3 or more).
pub fn element_volume(x: &ElementCoords, rule: &Quadrature) -> Result<f64, ElementError> {
    let mut v = 0.0;
    for (q, (xi, w)) in rule.points.iter().zip(&rule.weights).enumerate() {
        v += w * physical_gradients(x, *xi, q)?.1;
    }
    Ok(v)
}

/// Strain `ε = B u` (Voigt order `11, 22, 33, 12, 13, 23`, engineering shear) at reference
/// point `xi`, for nodal displacements `u`.
pub fn strain_at(
    x: &ElementCoords,
    u: &[[f64; 3]; 10],
    xi: [f64; 3],
) -> Result<[f64; 6], ElementError> {
    let (g, _) = physical_gradients(x, xi, 0)?;
    // Displacement gradient h[i][j] = ∂u_i/∂x_j.
    let mut h = [[0.0; 3]; 3];
    for (ua, ga) in u.iter().zip(&g) {
        for i in 0..3 {
            for j in 0..3 {
                h[i][j] += ua[i] * ga[j];
            }
        }
    }
    Ok([
        h[0][0],
        h[1][1],
        h[2][2],
        h[0][1] + h[1][0],
        h[0][2] + h[2][0],
        h[1][2] + h[2][1],
    ])
}

/// Copies the strict upper triangle onto the lower one.
fn mirror_upper<const N: usize>(m: &mut [[f64; N]; N]) {
    for i in 0..N {
        for j in i + 1..N {
            m[j][i] = m[i][j];
        }
    }
}
