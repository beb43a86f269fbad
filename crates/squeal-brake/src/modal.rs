//! The undamped, frictionless modal basis Φ of the reduced brake and the damping of
//! eqs (12)–(13).
//!
//! Φ holds the modes of the brake linearized about its frictionless equilibrium,
//! `K_t0 φ = ω² M φ` with `K_t0 = K + K_NL(x0, μ = 0)` (contact springs included, symmetric),
//! mass-normalized so `Φᵀ M Φ = I` and `Φ⁻¹ = Φᵀ M`. Eq (12): `C = Φ⁻ᵀ D Φ⁻¹ = M Φ D Φᵀ M`
//! with `D` diagonal: a global modal damping ratio ζ on every mode (`2 ζ ω_j`) plus eq (13)'s
//! `D1`, `D2` on the two modes that coalesce.

use crate::damping::ModalDamping;
use crate::error::BrakeError;
use faer::linalg::solvers::Solve;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, Par, Side};

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
    // Above the size the projected sweep starts at, the triangular solves are faer's blocked
    // ones (a 2000-dof brake: seconds less than the column loops, whose bits the bundled brakes'
    // pinned numbers come from and keep).
    let blocked = n > crate::sweep::PROJECT_ABOVE;
    let lower = |b: &Mat<f64>| {
        if blocked {
            let mut x = b.clone();
            solve_lower_triangular_in_place(l.as_ref(), x.as_mut(), Par::Seq);
            x
        } else {
            solve_lower(&l, b)
        }
    };
    // A = L⁻¹ K L⁻ᵀ, computed as L⁻¹ (L⁻¹ K)ᵀ using K's symmetry, then symmetrized.
    let linv_k = lower(k);
    let a0 = lower(&linv_k.transpose().to_owned());
    // faer 0.24.4's dense self-adjoint eigensolver loses accuracy for n >= 129 when the matrix
    // norm is far from 1 (relative residuals ~1e-3 on the 158-dof brake, whose norm is
    // ~ω_max² ~ 1e11): solve the problem scaled to unit norm, and check the residuals.
    let scale = a0.norm_max().max(f64::MIN_POSITIVE);
    let a = Mat::from_fn(n, n, |i, j| 0.5 * (a0[(i, j)] + a0[(j, i)]) / scale);
    let evd = a
        .self_adjoint_eigen(Side::Lower)
        .map_err(|_| BrakeError::EigenNoConvergence)?;
    let s = evd.S();
    let mut omega = Vec::with_capacity(n);
    for j in 0..n {
        let w2 = s[j] * scale;
        if w2.is_nan() || w2 <= 0.0 {
            return Err(BrakeError::StiffnessNotPositive);
        }
        omega.push(w2.sqrt());
    }
    let worst = max_residual(&a, evd.U(), s);
    if worst.is_nan() || worst > 1e-12 {
        return Err(BrakeError::EigenInaccurate { residual: worst });
    }
    // φ = L⁻ᵀ y.
    let phi = if blocked {
        let mut y = evd.U().to_owned();
        solve_upper_triangular_in_place(l.transpose(), y.as_mut(), Par::Seq);
        y
    } else {
        l.transpose().to_owned().partial_piv_lu().solve(evd.U())
    };
    Ok(ModalBasis { phi, omega })
}

/// Largest `||A y - s y||` over the eigenpairs of a symmetric `A` of unit max-norm.
fn max_residual(a: &Mat<f64>, y: faer::MatRef<'_, f64>, s: faer::diag::DiagRef<'_, f64>) -> f64 {
    let n = a.nrows();
    let ay = a * y;
    (0..n)
        .map(|j| {
            (0..n)
                .map(|i| (ay[(i, j)] - s[j] * y[(i, j)]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .fold(0.0, f64::max)
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
    /// `D` of eq (12) for a basis (diagonal). An extra on a mode the basis does not have is
    /// an error, not ignored.
    pub fn modal(&self, basis: &ModalBasis) -> Result<ModalDamping, BrakeError> {
        let mut d: Vec<f64> = basis
            .omega
            .iter()
            .map(|w| 2.0 * self.global_ratio * w)
            .collect();
        for &(j, v) in &self.extra {
            let n = d.len();
            let slot = d.get_mut(j).ok_or(BrakeError::ModeOutOfRange {
                mode: j + 1,
                modes: n,
            })?;
            *slot += v;
        }
        Ok(ModalDamping::Diagonal(d))
    }
}

/// Eq (12): `C = M Φ D Φᵀ M`.
pub fn damping_matrix(m: &Mat<f64>, basis: &ModalBasis, d: &ModalDamping) -> Mat<f64> {
    let mphi = m * &basis.phi;
    &mphi * d.to_dense() * mphi.transpose()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 158-dof pencil with the brake's scales (K ~ 1e11, M ~ 1e-2): faer 0.24.4's eigensolver
    /// is wrong on it unscaled (residuals ~1e-3); the basis must be accurate to round-off.
    #[test]
    fn badly_scaled_158_dof_pencil_gets_an_accurate_basis() {
        let n = 158;
        let k = Mat::from_fn(n, n, |i, j| {
            let base = if i == j {
                2.0 + (i as f64 * 0.37).sin()
            } else {
                0.0
            };
            let off = if i.abs_diff(j) == 1 {
                -0.9
            } else if i.abs_diff(j) == 7 {
                0.05
            } else {
                0.0
            };
            1e11 * (base + off + 1.0 / (1.0 + (i + j) as f64))
        });
        let k = Mat::from_fn(n, n, |i, j| {
            0.5 * (k[(i, j)] + k[(j, i)]) + if i == j { 1e11 * n as f64 * 0.02 } else { 0.0 }
        });
        let m = Mat::from_fn(n, n, |i, j| {
            if i == j {
                1e-2 * (1.0 + 0.5 * (i as f64 * 0.11).cos())
            } else if i.abs_diff(j) == 1 {
                1e-3
            } else {
                0.0
            }
        });
        let b = modal_basis(&m, &k).unwrap();
        let kp = &k * &b.phi;
        let mp = &m * &b.phi;
        for j in 0..n {
            let w2 = b.omega[j].powi(2);
            let r: f64 = (0..n)
                .map(|i| (kp[(i, j)] - w2 * mp[(i, j)]).powi(2))
                .sum::<f64>()
                .sqrt();
            let s: f64 = (0..n).map(|i| kp[(i, j)].powi(2)).sum::<f64>().sqrt();
            // Backward stable: residual ~ n ε relative.
            assert!(r / s < 1e-11, "mode {j}: relative residual {:.1e}", r / s);
        }
    }

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
        let c = damping_matrix(&m, &b, &ModalDamping::Diagonal(d.to_vec()));
        let back = b.phi.transpose() * &c * &b.phi;
        for i in 0..2 {
            for j in 0..2 {
                assert!((back[(i, j)] - if i == j { d[i] } else { 0.0 }).abs() < 1e-13);
            }
        }
    }
}
