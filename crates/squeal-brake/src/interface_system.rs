//! System vectors for the interface reduction: the assembled brake's real modes at the
//! frictionless static equilibrium, the static response to each in-band mode's friction
//! forces, and the equilibrium with its first derivative in μ — the basis commercial complex
//! eigenvalue analysis projects onto, here used only for the contact faces' motion.
//!
//! # The vectors
//!
//! With `x_0` the static equilibrium at μ = 0 (eq (14)) and `K_t0 = K + K_NL(x_0, 0)` its
//! symmetric tangent (eq (20), the normal springs `Σ_p k_t,p g_p g_pᵀ`), the real modes
//! `K_t0 φ_j = ω_j² M φ_j` are the frictionless brake's. Friction adds, eqs (18)–(19),
//! `μ K_f` with `K_f = Σ_p k_t,p h_p g_pᵀ` (the tangential force of each pair's normal
//! spring), so a mode's friction forces `K_f φ_j` load the brake in directions the modes need
//! not span; their static response
//!
//! `r_j = K_t0⁻¹ K_f φ_j`  (one per in-band mode)
//!
//! is the first correction of the mode under friction (the residual vectors of modal
//! truncation augmentation: Dickens, Nakagawa & Wittbrodt, Comput. Struct. 62(6), 1997). The
//! static equilibrium moves with μ (`K x + Σ_p F_n,p (g_p + μ h_p) = F_piston`); at μ = 0 it is
//! `x_0` and it moves first as
//!
//! `dx/dμ = −K_t0⁻¹ Σ_p F_n,p(x_0) h_p`,
//!
//! so `x_0` and `dx/dμ` join the vectors: with them in the span the reduced brake's
//! frictionless equilibrium is the unreduced one, and its tangent springs with it. (With
//! connectors on the vibration only, `Brake::k_vibration`, the static solve has `K − K_vib`,
//! so `dx/dμ` is solved with `K_t0 − K_vib`.)
//!
//! Every vector depends on μ only through these two terms: the basis is computed once, at
//! μ = 0, and the sweep's μ-dependence (equilibrium and friction coupling) is carried by the
//! residual and static vectors. The brake's coordinates are not replaced by these vectors:
//! each part keeps its fixed-interface modes and pistons, and only its contact face's motion
//! is restricted to the span of the vectors' face rows (the pipeline's `interface` module,
//! [`squeal_reduce::interface_modes::face_basis`]); that span holds every vector, so the
//! reduced brake reproduces its in-band frictionless modes exactly and is a Rayleigh–Ritz
//! projection of the unreduced-interface brake.
//!
//! # Only the modes that are used
//!
//! Of the real modes only those up to the band's top (with their residuals) and, for the
//! higher levels of `"auto"`, those up to 2, 4, … times it are used. [`system_vectors_to`]
//! computes just these, the lowest modes of `(K_t0, M)` below a frequency, by the partial
//! solve of [`crate::partial_modes`] (shift-invert block Lanczos on the Cholesky factor of
//! `K_t0`, the count of modes from the inertia of `K_t0 − ω_c² M`), when its flop estimate
//! is below half the whole decomposition's; the same Cholesky factor then solves the residual
//! and static vectors above (one factorization of `K_t0`). The vectors are the whole
//! decomposition's to round-off (the same count, frequencies and span:
//! `crates/squeal-pipeline/tests/pipeline/partial_system.rs`); below the estimate's break-even (small
//! brakes) the whole decomposition is kept, with the same bits as before.

use crate::equilibrium::{NewtonOptions, static_equilibrium};
use crate::error::BrakeError;
use crate::modal::{ModalBasis, modal_basis};
use crate::model::Brake;
use crate::partial_modes;
use faer::linalg::solvers::Solve;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, Par};

/// The system vectors of a brake, computed once.
#[derive(Clone, Debug)]
pub struct SystemVectors {
    /// The real modes at the frictionless equilibrium (`K_t0`, `M`), ascending.
    pub modes: ModalBasis,
    /// `r_j = K_t0⁻¹ K_f φ_j` for the lowest `residuals.ncols()` modes (columns).
    pub residuals: Mat<f64>,
    /// `x_0` and `dx/dμ` at μ = 0.
    pub statics: [Vec<f64>; 2],
}

/// The system vectors of `brake`, with friction residual vectors for its modes up to
/// `residuals_to_hz` (the band's top), and every real mode (the whole dense decomposition).
pub fn system_vectors(
    brake: &Brake,
    newton: &NewtonOptions,
    residuals_to_hz: f64,
) -> Result<SystemVectors, BrakeError> {
    system_vectors_to(brake, newton, residuals_to_hz, f64::INFINITY)
}

/// As [`system_vectors`], with the real modes up to `modes_to_hz` at least (and up to
/// `residuals_to_hz`): the lowest ones by the partial solve of [`crate::partial_modes`] (its
/// Cholesky factor of `K_t0` serving the residuals' solves too) when its flop count is below
/// half the whole decomposition's, else all of them as [`system_vectors`] computes them (the
/// same bits). [`SystemVectors::complete`] says which.
pub fn system_vectors_to(
    brake: &Brake,
    newton: &NewtonOptions,
    residuals_to_hz: f64,
    modes_to_hz: f64,
) -> Result<SystemVectors, BrakeError> {
    let n = brake.size();
    let eq = static_equilibrium(brake, 0.0, None, newton)?;
    let kt0 = brake.tangent_stiffness(&eq.x, 0.0);
    let kt0 = Mat::from_fn(n, n, |i, j| 0.5 * (kt0[(i, j)] + kt0[(j, i)]));
    let tau = std::f64::consts::TAU;
    let to_hz = modes_to_hz.max(residuals_to_hz);
    let partial = if to_hz.is_finite() {
        let count = partial_modes::count_below(&kt0, &brake.m, (tau * to_hz).powi(2));
        let cheaper = 2.0 * partial_modes::partial_flops(n, count) < partial_modes::dense_flops(n);
        match (cheaper, partial_modes::cholesky(&kt0)) {
            (true, Some(l)) => {
                partial_modes::lowest_modes(&brake.m, &kt0, &l, count)?.map(|modes| (modes, l))
            }
            _ => None,
        }
    } else {
        None
    };
    let (modes, solver) = match partial {
        Some((modes, l)) => (modes, Factor::Cholesky(l)),
        None => (
            modal_basis(&brake.m, &kt0)?,
            Factor::Lu(kt0.partial_piv_lu()),
        ),
    };
    // K_f = ∂F_nl/∂x at μ = 1 less at μ = 0: the friction part of eq (19).
    let (j1, _) = brake.nonlinear_jacobian(&eq.x, 1.0, false);
    let (j0, _) = brake.nonlinear_jacobian(&eq.x, 0.0, false);
    let kf = &j1 - &j0;
    let r = modes
        .omega
        .iter()
        .filter(|w| **w / tau <= residuals_to_hz)
        .count();
    let phi = Mat::from_fn(n, r, |i, j| modes.phi[(i, j)]);
    let residuals = solver.solve(&crate::dense_par::product(kf.as_ref(), phi.as_ref()));
    // Σ F_n h at x_0: the nonlinear force at μ = 1 less at μ = 0.
    let (mut f1, mut f0) = (vec![0.0; n], vec![0.0; n]);
    brake.add_nonlinear_force(&eq.x, None, 1.0, &mut f1);
    brake.add_nonlinear_force(&eq.x, None, 0.0, &mut f0);
    let ft = Mat::from_fn(n, 1, |i, _| f0[i] - f1[i]);
    let dx = match &brake.k_vibration {
        None => solver.solve(&ft),
        // Connectors on the vibration only (`Brake::k_vibration`, a caliper's pistons) are out
        // of the static solve: the equilibrium moves with `K_t0 − K_vib`.
        Some(kv) => {
            let ks = Mat::from_fn(n, n, |i, j| kt0[(i, j)] - 0.5 * (kv[(i, j)] + kv[(j, i)]));
            ks.partial_piv_lu().solve(&ft)
        }
    };
    let finite = |a: &Mat<f64>| (0..a.ncols()).all(|j| (0..n).all(|i| a[(i, j)].is_finite()));
    if !finite(&residuals) || !finite(&dx) {
        return Err(BrakeError::StiffnessNotPositive);
    }
    Ok(SystemVectors {
        modes,
        residuals,
        statics: [eq.x, (0..n).map(|i| dx[(i, 0)]).collect()],
    })
}

/// The factorization of `K_t0` the residual and static vectors are solved with.
enum Factor {
    /// The partial solve's `L` (`K_t0 = L Lᵀ`).
    Cholesky(Mat<f64>),
    /// The whole decomposition's path: a partial-pivoting LU.
    Lu(faer::linalg::solvers::PartialPivLu<f64>),
}

impl Factor {
    /// `K_t0⁻¹ b`.
    fn solve(&self, b: &Mat<f64>) -> Mat<f64> {
        match self {
            Factor::Cholesky(l) => {
                // Several columns on rayon's threads, one sequentially (the same bits:
                // crate::dense_par).
                let mut x = b.clone();
                let par = if b.ncols() > 1 {
                    crate::dense_par::par_for(l.nrows())
                } else {
                    Par::Seq
                };
                solve_lower_triangular_in_place(l.as_ref(), x.as_mut(), par);
                solve_upper_triangular_in_place(l.transpose(), x.as_mut(), par);
                x
            }
            Factor::Lu(lu) => lu.solve(b),
        }
    }
}

impl SystemVectors {
    /// Whether [`Self::modes`] holds every real mode of the brake (the whole decomposition),
    /// not only the lowest ones.
    pub fn complete(&self) -> bool {
        self.modes.phi.ncols() == self.modes.phi.nrows()
    }

    /// The columns `[φ_1 … φ_modes, r_1 … r_residuals, x_0, dx/dμ]` (`n × (modes + residuals
    /// + 2)`, `modes` and `residuals` at most as many as there are).
    pub fn columns(&self, modes: usize, residuals: usize) -> Mat<f64> {
        let n = self.modes.phi.nrows();
        let modes = modes.min(self.modes.phi.ncols());
        let residuals = residuals.min(self.residuals.ncols());
        Mat::from_fn(n, modes + residuals + 2, |i, j| {
            if j < modes {
                self.modes.phi[(i, j)]
            } else if j < modes + residuals {
                self.residuals[(i, j - modes)]
            } else {
                self.statics[j - modes - residuals][i]
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One pair between a disc dof and a pad dof along the normal and the sliding direction:
    /// the residual of each mode is `K_t0⁻¹ K_f φ`, checked by applying `K_t0`.
    #[test]
    fn residuals_solve_the_friction_load() {
        let n = 4;
        let k = Mat::from_fn(n, n, |i, j| if i == j { 2e6 + 1e5 * i as f64 } else { 0.0 });
        let m = Mat::from_fn(n, n, |i, j| if i == j { 1.0 + 0.5 * i as f64 } else { 0.0 });
        let mut f = vec![0.0; n];
        f[3] = -100.0;
        let brake = Brake {
            m,
            k,
            f_piston: f,
            c: None,
            k_vibration: None,
            pairs: vec![crate::model::tests::one_pair(0.0)],
        };
        let v = system_vectors(&brake, &NewtonOptions::default(), f64::INFINITY).unwrap();
        assert_eq!(v.residuals.ncols(), 4);
        let eq = static_equilibrium(&brake, 0.0, None, &NewtonOptions::default()).unwrap();
        let kt0 = brake.tangent_stiffness(&eq.x, 0.0);
        let (j1, _) = brake.nonlinear_jacobian(&eq.x, 1.0, false);
        let kf = &j1 - &brake.nonlinear_jacobian(&eq.x, 0.0, false).0;
        for j in 0..4 {
            let phi = Mat::from_fn(n, 1, |i, _| v.modes.phi[(i, j)]);
            let r = Mat::from_fn(n, 1, |i, _| v.residuals[(i, j)]);
            let lhs = &kt0 * &r;
            let rhs = &kf * &phi;
            let scale = rhs.norm_max().max(1e-300);
            // A 4 x 4 LU solve: round-off of a few ulps of the O(k) entries.
            assert!((&lhs - &rhs).norm_max() <= 1e-12 * scale * 1e3, "{j}");
        }
        // The static vector is the equilibrium.
        assert_eq!(v.statics[0], eq.x);
        assert_eq!(v.columns(9, 2).ncols(), 4 + 2 + 2);
    }
}
