//! The undamped, frictionless modal basis Φ of the reduced brake and the damping of
//! eqs (12)–(13).
//!
//! Φ holds the modes of the brake linearized about its frictionless equilibrium,
//! `K_t0 φ = ω² M φ` with `K_t0 = K + K_NL(x0, μ = 0)` (contact springs included, symmetric),
//! mass-normalized so `Φᵀ M Φ = I` and `Φ⁻¹ = Φᵀ M`. Eq (12): `C = Φ⁻ᵀ D Φ⁻¹ = M Φ D Φᵀ M`
//! with `D` diagonal: a global modal damping ratio ζ on every mode (`2 ζ ω_j`) plus eq (13)'s
//! `D1`, `D2` on the two modes that coalesce.

use crate::error::BrakeError;
use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

/// Mass-normalized modes, frequencies ascending.
#[derive(Clone, Debug)]
pub struct ModalBasis {
    /// `n x n`, columns `φ_j` with `Φᵀ M Φ = I`.
    pub phi: Mat<f64>,
    /// Natural circular frequencies ω_j (rad/s), ascending.
    pub omega: Vec<f64>,
}

/// Modes of the symmetric pencil `(k, m)`; `k` must be symmetric positive definite (the brake
/// held by its contact) and `m` symmetric positive definite.
pub fn modal_basis(m: &Mat<f64>, k: &Mat<f64>) -> Result<ModalBasis, BrakeError> {
    let n = m.nrows();
    let llt = m
        .llt(Side::Lower)
        .map_err(|_| BrakeError::MassNotPositive)?;
    let l = llt.L().to_owned();
    // A = L⁻¹ K L⁻ᵀ, computed as L⁻¹ (L⁻¹ K)ᵀ using K's symmetry, then symmetrized.
    let linv_k = solve_lower(&l, k);
    let a0 = solve_lower(&l, &linv_k.transpose().to_owned());
    let a = Mat::from_fn(n, n, |i, j| 0.5 * (a0[(i, j)] + a0[(j, i)]));
    let evd = a
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| BrakeError::Eigen(format!("{e:?}")))?;
    let s = evd.S();
    let mut omega = Vec::with_capacity(n);
    for j in 0..n {
        let w2 = s[j];
        if w2.is_nan() || w2 <= 0.0 {
            return Err(BrakeError::StiffnessNotPositive);
        }
        omega.push(w2.sqrt());
    }
    // φ = L⁻ᵀ y.
    let phi = l.transpose().to_owned().partial_piv_lu().solve(evd.U());
    Ok(ModalBasis { phi, omega })
}

/// `L⁻¹ B` for lower-triangular `L` (forward substitution, column by column).
fn solve_lower(l: &Mat<f64>, b: &Mat<f64>) -> Mat<f64> {
    let n = l.nrows();
    let mut x = b.clone();
    for c in 0..b.ncols() {
        for i in 0..n {
            let mut s = x[(i, c)];
            for k in 0..i {
                s -= l[(i, k)] * x[(k, c)];
            }
            x[(i, c)] = s / l[(i, i)];
        }
    }
    x
}

/// The modal damping of eq (13) plus a global ratio.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Damping {
    /// Modal damping ratio ζ on every mode: `D_jj += 2 ζ ω_j`.
    pub global_ratio: f64,
    /// Eq (13): `(mode index, D_jj)` added on given modes (s⁻¹), e.g. the coalescing pair.
    pub extra: Vec<(usize, f64)>,
}

impl Damping {
    /// The diagonal of `D` for a basis.
    pub fn diagonal(&self, basis: &ModalBasis) -> Vec<f64> {
        let mut d: Vec<f64> = basis
            .omega
            .iter()
            .map(|w| 2.0 * self.global_ratio * w)
            .collect();
        for &(j, v) in &self.extra {
            if j < d.len() {
                d[j] += v;
            }
        }
        d
    }
}

/// Eq (12): `C = M Φ D Φᵀ M`.
pub fn damping_matrix(m: &Mat<f64>, basis: &ModalBasis, d: &[f64]) -> Mat<f64> {
    let n = m.nrows();
    let mphi = m * &basis.phi;
    let scaled = Mat::from_fn(n, n, |i, j| mphi[(i, j)] * d[j]);
    &scaled * mphi.transpose()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_mass_chain_modes_and_damping_round_trip() {
        // m = diag(1, 2), k = [[3, -1], [-1, 1]]: det(k - w2 m) = 2 w2^2 - 7 w2 + 2 = 0.
        let m = Mat::from_fn(2, 2, |i, j| if i == j { (i + 1) as f64 } else { 0.0 });
        let k = Mat::from_fn(2, 2, |i, j| [[3.0, -1.0], [-1.0, 1.0]][i][j]);
        let b = modal_basis(&m, &k).unwrap();
        let disc = (49.0f64 - 16.0).sqrt();
        let exact = [(7.0 - disc) / 4.0, (7.0 + disc) / 4.0];
        for j in 0..2 {
            // Dense symmetric eigensolver: accurate to a few ulps of ||k||.
            assert!(
                (b.omega[j].powi(2) - exact[j]).abs() < 1e-13,
                "{} vs {}",
                b.omega[j].powi(2),
                exact[j]
            );
        }
        let ptmp = b.phi.transpose() * &m * &b.phi;
        for i in 0..2 {
            for j in 0..2 {
                assert!((ptmp[(i, j)] - if i == j { 1.0 } else { 0.0 }).abs() < 1e-14);
            }
        }
        // Φᵀ C Φ = D by construction of eq (12).
        let d = [0.3, 1.7];
        let c = damping_matrix(&m, &b, &d);
        let back = b.phi.transpose() * &c * &b.phi;
        for i in 0..2 {
            for j in 0..2 {
                assert!((back[(i, j)] - if i == j { d[i] } else { 0.0 }).abs() < 1e-13);
            }
        }
    }
}
