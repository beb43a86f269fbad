//! Complex eigenvalues of the brake linearized about its equilibrium, eqs (20)–(22).
//!
//! Eq (21)'s state matrix is built in the frictionless modal coordinates `x = Φ q` (module
//! [`crate::modal`]), where `Φᵀ M Φ = I`, `Φᵀ K_t0 Φ = Ω²` and `Φᵀ C Φ = D`:
//! `q'' + (D + ΔC) q' + (Ω² + ΔK) q = 0` with `ΔK = Φᵀ (K_t(μ) - K_t0) Φ` (friction coupling
//! and the change of the contact tangent stiffness with μ) and `ΔC = Φᵀ C_NL Φ` (zero unless a
//! contact element depends on the velocities), both from the one linearization of
//! [`crate::linearized`]. With the scaled state `z = [Ω q; q']` the state matrix is
//!
//! `A = [[0, Ω], [-(Ω + ΔK Ω⁻¹), -(D + ΔC)]]`,
//!
//! similar to eq (21)'s (same eigenvalues) but with entries of order ω instead of ω², which
//! keeps the eigenvalues' absolute accuracy near `ε ω_max` rather than `ε ω_max²`: this matters
//! for the small real parts near a Hopf point.

use crate::damping::ModalDamping;
use crate::equilibrium::Equilibrium;
use crate::error::BrakeError;
use crate::linearized::LinearizedBrake;
use crate::modal::ModalBasis;
use crate::model::Brake;
use faer::diag::Diag;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::evd::{ComputeEigenvectors, evd_real, evd_scratch};
use faer::{Mat, Par, c64};
use std::sync::Arc;

/// The frictionless reference: equilibrium at μ = 0, its tangent stiffness, modal basis and
/// the modal damping `D` of eq (12).
#[derive(Clone, Debug)]
pub struct Reference {
    /// The static equilibrium of eq (14) at μ = 0.
    pub equilibrium: Equilibrium,
    /// The tangent stiffness `K_t0 = K + K_NL(x0, μ = 0)` there (symmetric).
    pub kt0: Mat<f64>,
    /// The undamped modes of `(K_t0, M)`, mass-normalized.
    pub basis: ModalBasis,
    /// The modal damping `D` of eq (12) in that basis (s⁻¹).
    pub damping: ModalDamping,
}

/// Eigenvalues of eq (21) with `Im λ >= 0` (one of each conjugate pair) and their modes.
#[derive(Clone, Debug)]
pub struct Spectrum {
    /// Friction coefficient μ of the linearization.
    pub mu: f64,
    /// `λ = a + iω` (eq 22), ascending in `ω`.
    pub values: Vec<c64>,
    /// Modal coordinates `q` of each mode (column `j` for `values[j]`), with `Σ|q|² = 1`; the
    /// physical shape is `x = Φ q`, mass-normalized. A projected sweep
    /// ([`crate::projected`]) gives the coordinates on its basis instead ([`Spectrum::ritz`]).
    pub modes: Mat<c64>,
    /// The basis of a projection `modes` are coordinates on (`None`: the modal basis itself).
    pub ritz: Option<Arc<Ritz>>,
}

/// The basis of a projection in modal coordinates: the first `kept` frictionless modes, then
/// `residual` (`(n - kept) × s`, orthonormal columns) on the others.
#[derive(Clone, Debug, PartialEq)]
pub struct Ritz {
    /// Frictionless modes kept as they are (the lowest ones).
    pub kept: usize,
    /// The static-correction vectors on the dropped modes, column by column.
    pub residual: Mat<f64>,
}

impl Ritz {
    /// Modal coordinates `[q_kept; R q_res]` of coordinates `q` on the basis.
    pub fn lift(&self, q: impl Fn(usize) -> c64) -> Vec<c64> {
        let (m, t, s) = (self.kept, self.residual.nrows(), self.residual.ncols());
        let mut out: Vec<c64> = (0..m).map(&q).collect();
        out.resize(m + t, c64::new(0.0, 0.0));
        for k in 0..s {
            let a = q(m + k);
            let col = self.residual.col(k);
            for i in 0..t {
                out[m + i] += a * col[i];
            }
        }
        out
    }
}

impl Spectrum {
    /// Frequency `Im λ / 2π` (Hz) of mode `j`.
    pub fn frequency_hz(&self, j: usize) -> f64 {
        self.values[j].im / (2.0 * std::f64::consts::PI)
    }

    /// Modal coordinates `q` of mode `j` (lifted from a projection's basis).
    pub fn modal(&self, j: usize) -> Vec<c64> {
        match &self.ritz {
            Some(r) => r.lift(|i| self.modes[(i, j)]),
            None => (0..self.modes.nrows())
                .map(|i| self.modes[(i, j)])
                .collect(),
        }
    }

    /// Physical shape `x = Φ q` of mode `j`.
    pub fn shape(&self, basis: &ModalBasis, j: usize) -> Vec<c64> {
        let n = basis.phi.nrows();
        let q = self.modal(j);
        (0..n)
            .map(|i| {
                let mut s = c64::new(0.0, 0.0);
                for k in 0..n {
                    s += q[k] * basis.phi[(i, k)];
                }
                s
            })
            .collect()
    }
}

/// The scaled state matrix `[[0, Ω], [-(Ω + ΔK Ω⁻¹), -(D + ΔC)]]`.
pub fn state_matrix(
    basis: &ModalBasis,
    damping: &ModalDamping,
    dk: &Mat<f64>,
    dc: Option<&Mat<f64>>,
) -> Mat<f64> {
    state_matrix_of(&basis.omega, damping, dk, dc)
}

/// [`state_matrix`] for given frequencies `ω_j` (all of the basis, or the leading ones of a
/// projection).
pub(crate) fn state_matrix_of(
    w: &[f64],
    damping: &ModalDamping,
    dk: &Mat<f64>,
    dc: Option<&Mat<f64>>,
) -> Mat<f64> {
    let n = w.len();
    Mat::from_fn(2 * n, 2 * n, |i, j| match (i < n, j < n) {
        (true, true) => 0.0,
        (true, false) => {
            if i == j - n {
                w[i]
            } else {
                0.0
            }
        }
        (false, true) => {
            let r = i - n;
            let diag = if r == j { w[r] } else { 0.0 };
            -(diag + dk[(r, j)] / w[j])
        }
        (false, false) => {
            let (r, c) = (i - n, j - n);
            -(damping.entry(r, c) + dc.map_or(0.0, |m| m[(r, c)]))
        }
    })
}

/// Eigenvalues and modes of the brake linearized at `eq` (eqs 20–22).
pub fn spectrum(
    brake: &Brake,
    reference: &Reference,
    eq: &Equilibrium,
) -> Result<Spectrum, BrakeError> {
    let lin = LinearizedBrake::new(brake, reference)?;
    let (dk, dc) = lin.dense_change(&lin.coupling(brake, eq));
    spectrum_of(
        &reference.basis,
        &reference.damping,
        &dk,
        dc.as_ref(),
        eq.mu,
    )
}

/// Eigen-decomposition of the scaled state matrix for a given modal stiffness change.
pub fn spectrum_of(
    basis: &ModalBasis,
    damping: &ModalDamping,
    dk: &Mat<f64>,
    dc: Option<&Mat<f64>>,
    mu: f64,
) -> Result<Spectrum, BrakeError> {
    modal_spectrum(&basis.omega, damping, dk, dc, mu)
}

/// [`spectrum_of`] for given frequencies `ω_j`: the leading modes of a projection
/// ([`crate::projected`]) with `D`, `ΔK`, `ΔC` restricted to them.
pub fn modal_spectrum(
    omega: &[f64],
    damping: &ModalDamping,
    dk: &Mat<f64>,
    dc: Option<&Mat<f64>>,
    mu: f64,
) -> Result<Spectrum, BrakeError> {
    let n = omega.len();
    let a = state_matrix_of(omega, damping, dk, dc);
    let (s, u) = real_eigen(&a, true)?;
    let u = u.ok_or(BrakeError::EigenNoConvergence)?;
    let order = upper_half(&s, n);
    let mut values = Vec::with_capacity(n);
    let mut modes = Mat::<c64>::zeros(n, n);
    for (col, &k) in order.iter().enumerate() {
        values.push(s[k]);
        // q = Ω⁻¹ z₁, normalized.
        let mut norm2 = 0.0;
        for i in 0..n {
            let q = u[(i, k)] / omega[i];
            modes[(i, col)] = q;
            norm2 += q.norm_sqr();
        }
        let inv = 1.0 / norm2.sqrt().max(f64::MIN_POSITIVE);
        for i in 0..n {
            modes[(i, col)] *= inv;
        }
    }
    Ok(Spectrum {
        mu,
        values,
        modes,
        ritz: None,
    })
}

/// The eigenvalues of the state matrix with `Im λ >= 0` (one of each conjugate pair), as
/// [`spectrum_of`] orders them, without the modes (faster).
pub fn eigenvalues_of(
    basis: &ModalBasis,
    damping: &ModalDamping,
    dk: &Mat<f64>,
    dc: Option<&Mat<f64>>,
) -> Result<Vec<c64>, BrakeError> {
    let n = basis.omega.len();
    let a = state_matrix(basis, damping, dk, dc);
    let (s, _) = real_eigen(&a, false)?;
    Ok(upper_half(&s, n).into_iter().map(|k| s[k]).collect())
}

/// [`eigenvalues_of`] for given frequencies `ω_j` (the whole modal basis's, without its
/// shapes).
pub fn modal_eigenvalues(
    omega: &[f64],
    damping: &ModalDamping,
    dk: &Mat<f64>,
    dc: Option<&Mat<f64>>,
) -> Result<Vec<c64>, BrakeError> {
    let a = state_matrix_of(omega, damping, dk, dc);
    let (s, _) = real_eigen(&a, false)?;
    Ok(upper_half(&s, omega.len())
        .into_iter()
        .map(|k| s[k])
        .collect())
}

/// Indices of the `n` eigenvalues of largest imaginary part (one of each conjugate pair),
/// ascending in `Im λ`, ties by index.
pub(crate) fn upper_half(s: &[c64], n: usize) -> Vec<usize> {
    let mut order: Vec<usize> = (0..s.len()).collect();
    order.sort_by(|&a, &b| {
        s[b].im
            .total_cmp(&s[a].im)
            .then(s[b].re.total_cmp(&s[a].re))
            .then(a.cmp(&b))
    });
    order.truncate(n);
    order.sort_by(|&a, &b| s[a].im.total_cmp(&s[b].im).then(a.cmp(&b)));
    order
}

/// Eigenvalues and (optionally) right eigenvectors of a real square matrix, by faer's dense
/// real eigensolver run sequentially so that the bits do not depend on the thread count.
/// A complex pair's vectors are `u_j ± i u_(j+1)` of the real quasi-triangular form's vectors.
pub fn real_eigen(a: &Mat<f64>, vectors: bool) -> Result<(Vec<c64>, Option<Mat<c64>>), BrakeError> {
    let n = a.nrows();
    let mut s_re = Diag::<f64>::zeros(n);
    let mut s_im = Diag::<f64>::zeros(n);
    let mut u_real = vectors.then(|| Mat::<f64>::zeros(n, n));
    let want = if vectors {
        ComputeEigenvectors::Yes
    } else {
        ComputeEigenvectors::No
    };
    let par = Par::Seq;
    let scratch = evd_scratch::<f64>(n, ComputeEigenvectors::No, want, par, Default::default());
    evd_real(
        a.as_ref(),
        s_re.as_mut(),
        s_im.as_mut(),
        None,
        u_real.as_mut().map(|u| u.as_mut()),
        par,
        MemStack::new(&mut MemBuffer::new(scratch)),
        Default::default(),
    )
    .map_err(|_| BrakeError::EigenNoConvergence)?;
    let values: Vec<c64> = (0..n).map(|j| c64::new(s_re[j], s_im[j])).collect();
    let modes = u_real.map(|ur| {
        let mut u = Mat::<c64>::zeros(n, n);
        let mut j = 0;
        while j < n {
            if s_im[j] == 0.0 || j + 1 == n {
                for i in 0..n {
                    u[(i, j)] = c64::new(ur[(i, j)], 0.0);
                }
                j += 1;
            } else {
                for i in 0..n {
                    u[(i, j)] = c64::new(ur[(i, j)], ur[(i, j + 1)]);
                    u[(i, j + 1)] = c64::new(ur[(i, j)], -ur[(i, j + 1)]);
                }
                j += 2;
            }
        }
        u
    });
    Ok((values, modes))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modal::modal_basis;

    #[test]
    fn undamped_frictionless_spectrum_is_the_modal_basis() {
        // With ΔK = 0 and D = 0 the eigenvalues are ±iω_j exactly (up to round-off).
        let m = Mat::from_fn(3, 3, |i, j| if i == j { 1.0 + i as f64 } else { 0.1 });
        let k = Mat::from_fn(
            3,
            3,
            |i, j| if i == j { 1e6 * (3 + i) as f64 } else { -2e5 },
        );
        let b = modal_basis(&m, &k).unwrap();
        let d = ModalDamping::Diagonal(vec![0.0; 3]);
        let sp = spectrum_of(&b, &d, &Mat::zeros(3, 3), None, 0.0).unwrap();
        for j in 0..3 {
            // Backward-stable eigensolver on a matrix of norm ~ω_max: errors ~ 1e-15 ω_max.
            assert!(
                sp.values[j].re.abs() < 1e-12 * b.omega[2],
                "re {}",
                sp.values[j].re
            );
            assert!((sp.values[j].im - b.omega[j]).abs() < 1e-12 * b.omega[2]);
        }
    }
}
