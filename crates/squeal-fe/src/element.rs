//! Element matrices of the isoparametric quadratic solids, written once for any
//! [`ReferenceElement`] (the `*_of` functions, which fill caller-provided buffers sized by
//! the element's node count `N`: `3N × 3N` stiffness, `N × N` scalar mass, row-major), and
//! their fixed-size forms for the 10-node tetrahedron (canonical node ordering of
//! [`squeal_mesh::tet10`]; midside nodes may be off the edge midpoints). The tet10 forms
//! are the generic code with `N = 10`: the same operations in the same order.
//!
//! Each element's quadrature rules are its own ([`ReferenceElement::stiffness_rule`],
//! [`ReferenceElement::mass_rule`]; for the 20-node hexahedron's reduced rule and its
//! hourglass modes see [`squeal_element::hex20`]). The rest of this documentation is about
//! the tet10, whose curved elements need a rule of their own.
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
//! (converged: 12³ and 20³ points agree to 4e-15), measured in `tests/fe/curved.rs`: on the
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
use squeal_element::{ReferenceElement, Tet10};

/// Node coordinates of one tet10 element in canonical order.
pub type ElementCoords = [[f64; 3]; 10];

/// Shape function gradients of a tet10 with respect to `x` and `det J` (see
/// [`physical_gradients_of`]).
pub fn physical_gradients(
    x: &ElementCoords,
    xi: [f64; 3],
    point: usize,
) -> Result<([[f64; 3]; 10], f64), ElementError> {
    physical_gradients_of::<Tet10, 10>(x, xi, point)
}

/// Shape function gradients with respect to `x` (`g[a][j] = ∂N_a/∂x_j`) and `det J` at the
/// reference point `xi`; an error if `det J ≤ 0` (`point` names the quadrature point).
pub fn physical_gradients_of<E: ReferenceElement<N>, const N: usize>(
    x: &[[f64; 3]; N],
    xi: [f64; 3],
    point: usize,
) -> Result<([[f64; 3]; N], f64), ElementError> {
    let g_ref = E::shape_gradients(xi);
    let mut j = [[0.0; 3]; 3];
    for (xn, gn) in x.iter().zip(&g_ref) {
        for r in 0..3 {
            for c in 0..3 {
                j[r][c] += xn[r] * gn[c];
            }
        }
    }
    let det = squeal_element::det3(&j);
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
/// Element Method vol. 1, eq. 6.9) of a tet10. The 4-point rule ([`Quadrature::four_point`])
/// is exact for straight-sided elements; for curved ones see the module documentation.
pub fn element_stiffness(
    x: &ElementCoords,
    c: &Voigt6,
    rule: &Quadrature,
) -> Result<[[f64; 30]; 30], ElementError> {
    let mut flat = vec![0.0; 900];
    stiffness_of::<Tet10, 10>(x, c, rule, &mut flat)?;
    Ok(std::array::from_fn(|i| {
        std::array::from_fn(|j| flat[30 * i + j])
    }))
}

/// Element stiffness `K_e = Σ_q w_q det J_q B_qᵀ C B_q` into `k`, row-major `3N × 3N`
/// (local dof `3 a + d`); `k` is overwritten. Computed on the upper triangle and mirrored.
pub fn stiffness_of<E: ReferenceElement<N>, const N: usize>(
    x: &[[f64; 3]; N],
    c: &Voigt6,
    rule: &Quadrature,
    k: &mut [f64],
) -> Result<(), ElementError> {
    let n3 = 3 * N;
    let k = &mut k[..n3 * n3];
    k.fill(0.0);
    for (q, (xi, w)) in rule.points.iter().zip(&rule.weights).enumerate() {
        let (g, det) = physical_gradients_of::<E, N>(x, *xi, q)?;
        let cb: [[[f64; 3]; 6]; N] = std::array::from_fn(|b| c_times_b(c, g[b], w * det));
        for a in 0..N {
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
                        k[(3 * a + p) * n3 + 3 * b + d] += v;
                    }
                }
            }
        }
    }
    mirror_upper(k, n3);
    Ok(())
}

/// The scalar consistent mass `m_ab = ρ Σ_q w_q det J_q N_a N_b` of a tet10 (the element
/// mass matrix is `m_ab I₃`). The 14-point rule ([`Quadrature::fourteen_point`]) is exact
/// for straight-sided elements.
pub fn element_mass_scalar(
    x: &ElementCoords,
    density: f64,
    rule: &Quadrature,
) -> Result<[[f64; 10]; 10], ElementError> {
    let mut flat = [0.0; 100];
    mass_scalar_of::<Tet10, 10>(x, density, rule, &mut flat)?;
    Ok(std::array::from_fn(|i| {
        std::array::from_fn(|j| flat[10 * i + j])
    }))
}

/// The scalar consistent mass `m_ab = ρ Σ_q w_q det J_q N_a N_b` into `m`, row-major `N × N`;
/// `m` is overwritten. The element mass matrix is `m_ab I₃`.
pub fn mass_scalar_of<E: ReferenceElement<N>, const N: usize>(
    x: &[[f64; 3]; N],
    density: f64,
    rule: &Quadrature,
    m: &mut [f64],
) -> Result<(), ElementError> {
    let m = &mut m[..N * N];
    m.fill(0.0);
    for (q, (xi, w)) in rule.points.iter().zip(&rule.weights).enumerate() {
        let (_, det) = physical_gradients_of::<E, N>(x, *xi, q)?;
        let n = E::shape(*xi);
        let s = density * w * det;
        for a in 0..N {
            let sa = s * n[a];
            for b in a..N {
                m[a * N + b] += sa * n[b];
            }
        }
    }
    mirror_upper(m, N);
    Ok(())
}

/// Consistent element mass `M_e = ∫ ρ Nᵀ N dV` of a tet10 as a 30×30 matrix (see
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

/// Volume `Σ_q w_q det J_q` of a tet10 (exact for straight-sided elements with any rule, for
/// curved ones with a rule of degree 3 or more).
pub fn element_volume(x: &ElementCoords, rule: &Quadrature) -> Result<f64, ElementError> {
    volume_of::<Tet10, 10>(x, rule)
}

/// Volume `Σ_q w_q det J_q` of an element; an error if `det J ≤ 0` at a point.
pub fn volume_of<E: ReferenceElement<N>, const N: usize>(
    x: &[[f64; 3]; N],
    rule: &Quadrature,
) -> Result<f64, ElementError> {
    let mut v = 0.0;
    for (q, (xi, w)) in rule.points.iter().zip(&rule.weights).enumerate() {
        v += w * physical_gradients_of::<E, N>(x, *xi, q)?.1;
    }
    Ok(v)
}

/// Strain `ε = B u` of a tet10 (see [`strain_of`]).
pub fn strain_at(
    x: &ElementCoords,
    u: &[[f64; 3]; 10],
    xi: [f64; 3],
) -> Result<[f64; 6], ElementError> {
    strain_of::<Tet10, 10>(x, u, xi)
}

/// Strain `ε = B u` (Voigt order `11, 22, 33, 12, 13, 23`, engineering shear) at reference
/// point `xi`, for nodal displacements `u`.
pub fn strain_of<E: ReferenceElement<N>, const N: usize>(
    x: &[[f64; 3]; N],
    u: &[[f64; 3]; N],
    xi: [f64; 3],
) -> Result<[f64; 6], ElementError> {
    let (g, _) = physical_gradients_of::<E, N>(x, xi, 0)?;
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

/// Copies the strict upper triangle of the row-major `n × n` matrix `m` onto the lower one.
fn mirror_upper(m: &mut [f64], n: usize) {
    for i in 0..n {
        for j in i + 1..n {
            m[j * n + i] = m[i * n + j];
        }
    }
}
