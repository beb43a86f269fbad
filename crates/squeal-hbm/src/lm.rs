//! Levenberg-Marquardt for `min ||r(z)||^2`, square or overdetermined, with analytic Jacobian.
//!
//! Section 4.1.2 of the paper solves the (constrained) harmonic balance equations with a
//! nonlinear least-squares method; this is that solver.
//!
//! # Algorithm
//! Each trial step solves the damped, scaled normal equations
//! `(J^T J + lambda D^2) h = -J^T r` by a dense Cholesky factorization (faer), where
//! `D = diag(d_j)` is Moré's scaling (Moré 1978, "The Levenberg-Marquardt algorithm:
//! implementation and theory", LNM 630): `d_j` is the largest norm of Jacobian column `j`
//! seen so far, which makes the iteration invariant to the units of each unknown
//! (harmonic amplitudes in metres next to a frequency in rad/s). The damping `lambda`
//! follows the gain ratio `rho = (||r||^2 - ||r(z+h)||^2) / (h^T (lambda D^2 h - J^T r))`
//! (actual over predicted decrease): a step is accepted iff `rho > 0`, then
//! `lambda *= max(1/3, 1 - (2 rho - 1)^3)`; on rejection `lambda *= nu`, `nu *= 2`
//! (Nielsen 1999; Madsen, Nielsen & Tingleff 2004, "Methods for non-linear least squares
//! problems", Alg. 3.16). The smooth update avoids the oscillation of the classical
//! "x10 / /10" rule and needs no inner loop, unlike Moré's trust-region `lambda` search.
//!
//! **Gauss–Newton first** ([`LmOptions::newton_damping`], off by default): for a square
//! system, while `lambda` is at most that bound, the first trial at each new Jacobian is the
//! undamped step `J h = -r` by one LU factorization of `J` with partial pivoting (`n^3/3`
//! multiply–adds) instead of forming `J^T J` (`n^2 m / 2`) and its damped Cholesky factor
//! (`n^3/6`). It is accepted if it decreases `||r||` (gain ratio against the Gauss–Newton
//! model's decrease `||r||^2`, then `lambda` updated as for a damped step); otherwise the
//! damped step at the current `lambda` follows, with `J^T J` formed then. Near a regular root
//! the damped steps' `lambda` shrinks to its floor and Levenberg–Marquardt is Gauss–Newton
//! anyway, so this saves the normal equations' algebra on the steps that would have been
//! (nearly) Gauss–Newton steps; the iterates differ from the damped ones by round-off and by
//! the damping's `lambda D^2` term.
//!
//! Normal equations instead of a QR of `[J; sqrt(lambda) D]`: for the square
//! `(n (2H+1) + 1)`-unknown systems of harmonic balance they cost about half the flops
//! (`J^T J` once per Jacobian, one Cholesky per trial), and `lambda > 0` keeps the matrix
//! positive definite even where `J` is singular (the time-shift invariance of an
//! autonomous system without phase condition). The price is the squared condition
//! number, which the column scaling largely removes.
//!
//! # Stopping
//! Converged: `||r|| <= abs_tol` or `||r|| <= rel_tol ||r(z0)||`. Not converged (typed
//! [`LmError::NotConverged`] with the full report): a step `||D h|| <= step_tol (||D z|| +
//! step_tol)` (no progress possible), a vanishing scaled gradient
//! `max_j |J_j^T r| / (||J_j|| ||r||) <= gradient_tol` (a local minimum with nonzero
//! residual), `max_iterations` trial steps, or `lambda > max_damping`. Set
//! [`LmOptions::accept_stationary`] to accept the small-step and small-gradient stops for
//! genuine least-squares fits.
//!
//! # Determinism
//! All reductions are sequential in a fixed order (faer with `Par::Seq`), so results do not
//! depend on the thread count.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt;
use faer::linalg::lu::partial_pivoting::factor::lu_in_place;
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::linalg::triangular_solve::{
    solve_unit_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Accum, Mat, MatMut, Par};

/// Upper bound on `n_residuals * n_params` (the dense Jacobian must fit in 2 GiB).
pub const MAX_JACOBIAN_ENTRIES: usize = 1 << 28;

/// A residual `r(z)` of `n_residuals` entries in `n_params` unknowns, with its Jacobian.
pub trait LeastSquaresProblem {
    /// Error of a failed evaluation (aborts the solve).
    type Error;

    /// Number of unknowns.
    fn n_params(&self) -> usize;

    /// Number of residual entries (any number; usually `>= n_params`).
    fn n_residuals(&self) -> usize;

    /// Writes `r(z)`. A NaN or infinite entry is not an error: the solver rejects the trial
    /// step and increases the damping (return `Err` only for unrecoverable failures).
    fn residual(&mut self, z: &[f64], r: &mut [f64]) -> Result<(), Self::Error>;

    /// Writes `J = dr/dz` (`n_residuals x n_params`); every entry must be set.
    fn jacobian(&mut self, z: &[f64], jac: MatMut<'_, f64>) -> Result<(), Self::Error>;
}

/// Options of [`solve`]. Tolerances are in the units of the residual (absolute) or
/// relative to the initial residual norm.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct LmOptions {
    /// Converged when `||r|| <= abs_tol`.
    pub abs_tol: f64,
    /// Converged when `||r|| <= rel_tol ||r(z0)||`.
    pub rel_tol: f64,
    /// Stop (not converged) when `||D h|| <= step_tol (||D z|| + step_tol)`.
    pub step_tol: f64,
    /// Stop (not converged) when the scaled gradient is below this (stationary point).
    pub gradient_tol: f64,
    /// Maximum number of trial steps (each = one linear solve and one residual evaluation).
    pub max_iterations: usize,
    /// Initial damping `lambda_0` relative to the scaled `J^T J` (Nielsen's `tau`).
    pub initial_damping: f64,
    /// Lower bound on `lambda` (keeps the Cholesky factorization away from exact singularity).
    pub min_damping: f64,
    /// Stop (not converged) when `lambda` exceeds this.
    pub max_damping: f64,
    /// Treat the small-step and small-gradient stops as success (least-squares fits with a
    /// nonzero minimum). Off by default: harmonic balance wants a root.
    pub accept_stationary: bool,
    /// Square systems only: while `lambda` is at most this, the first trial at each new
    /// Jacobian is a Gauss–Newton step by an LU factorization of `J` (module docs); `0`
    /// (the default) never tries one.
    pub newton_damping: f64,
}

impl Default for LmOptions {
    fn default() -> Self {
        Self {
            abs_tol: 1e-10,
            rel_tol: 1e-10,
            step_tol: 1e-14,
            gradient_tol: 1e-12,
            max_iterations: 200,
            initial_damping: 1e-3,
            min_damping: 1e-15,
            max_damping: 1e16,
            accept_stationary: false,
            newton_damping: 0.0,
        }
    }
}

/// Why the solver stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LmStop {
    /// `||r|| <= abs_tol` (converged).
    AbsoluteResidual,
    /// `||r|| <= rel_tol ||r0||` (converged).
    RelativeResidual,
    /// The scaled step became negligible before the residual tolerance was met.
    SmallStep,
    /// The scaled gradient vanished with a nonzero residual (local minimum).
    SmallGradient,
    /// `max_iterations` trial steps were used.
    MaxIterations,
    /// The damping grew beyond `max_damping` (no descent found).
    DampingOverflow,
}

impl LmStop {
    /// True for the residual criteria.
    pub fn is_converged(self) -> bool {
        matches!(self, LmStop::AbsoluteResidual | LmStop::RelativeResidual)
    }
}

impl std::fmt::Display for LmStop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let s = match self {
            LmStop::AbsoluteResidual => "residual below absolute tolerance",
            LmStop::RelativeResidual => "residual below relative tolerance",
            LmStop::SmallStep => "step too small to make progress",
            LmStop::SmallGradient => "gradient vanished at a nonzero residual (local minimum)",
            LmStop::MaxIterations => "maximum number of iterations reached",
            LmStop::DampingOverflow => "damping overflow (no descent direction found)",
        };
        f.write_str(s)
    }
}

/// One trial step of the iteration (the paper's Figures 6-7 plot such histories).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LmIteration {
    /// Trial number, starting at 1.
    pub iteration: usize,
    /// `||r||` at the current iterate after this trial (unchanged if rejected).
    pub residual_norm: f64,
    /// `||r(z + h)||` of the trial point (infinite if not finite or not evaluated).
    pub trial_residual_norm: f64,
    /// Damping `lambda` used for this trial.
    pub damping: f64,
    /// Euclidean norm of the unscaled step `h` (NaN if the damped system was not solvable).
    pub step_norm: f64,
    /// Gain ratio `rho` (actual over predicted decrease).
    pub gain_ratio: f64,
    /// Whether the step was accepted.
    pub accepted: bool,
}

/// Result of [`solve`]: the final iterate and how it was reached.
#[derive(Clone, Debug, PartialEq)]
pub struct LmReport {
    /// Final iterate `z`.
    pub x: Vec<f64>,
    /// Residual `r(z)` at the final iterate.
    pub residual: Vec<f64>,
    /// `||r(z)||`.
    pub residual_norm: f64,
    /// `||r(z0)||`.
    pub initial_residual_norm: f64,
    /// Number of trial steps.
    pub iterations: usize,
    /// Number of accepted steps.
    pub accepted_steps: usize,
    /// Number of Jacobian evaluations.
    pub jacobian_evaluations: usize,
    /// Why the iteration stopped.
    pub stop: LmStop,
    /// One entry per trial step.
    pub history: Vec<LmIteration>,
}

/// Failures of [`solve`].
#[derive(Debug, thiserror::Error)]
pub enum LmError<E> {
    /// Invalid option value.
    #[error("invalid Levenberg-Marquardt option: {0}")]
    BadOption(&'static str),
    /// Problem size is zero, inconsistent with `z0`, or too large.
    #[error("problem size: {0}")]
    BadSize(&'static str),
    /// `r(z0)` has a NaN or infinite entry.
    #[error("residual is not finite at the initial point")]
    NonFiniteStart,
    /// `J` has a NaN or infinite entry at an accepted iterate.
    #[error("Jacobian is not finite at iteration {iteration}")]
    NonFiniteJacobian {
        /// Trial count when it happened.
        iteration: usize,
    },
    /// The problem's residual or Jacobian evaluation failed.
    #[error("problem evaluation failed")]
    Problem(#[source] E),
    /// Stopped without meeting the residual tolerance; the report holds the last iterate.
    #[error("Levenberg-Marquardt did not converge: {}", .report.stop)]
    NotConverged {
        /// Last iterate, history and stop reason.
        report: Box<LmReport>,
    },
}

fn check_options<E>(o: &LmOptions) -> Result<(), LmError<E>> {
    let nonneg = |v: f64| v.is_finite() && v >= 0.0;
    if !nonneg(o.abs_tol)
        || !nonneg(o.rel_tol)
        || !nonneg(o.step_tol)
        || !nonneg(o.gradient_tol)
        || !nonneg(o.newton_damping)
    {
        return Err(LmError::BadOption("tolerances must be finite and >= 0"));
    }
    let pos = |v: f64| v.is_finite() && v > 0.0;
    if !pos(o.initial_damping) || !pos(o.min_damping) || !pos(o.max_damping) {
        return Err(LmError::BadOption("damping bounds must be finite and > 0"));
    }
    if o.min_damping > o.max_damping {
        return Err(LmError::BadOption(
            "min_damping must not exceed max_damping",
        ));
    }
    Ok(())
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|a| a * a).sum::<f64>().sqrt()
}

fn scaled_norm(d: &[f64], v: &[f64]) -> f64 {
    d.iter()
        .zip(v)
        .map(|(a, b)| (a * b) * (a * b))
        .sum::<f64>()
        .sqrt()
}

/// Working storage and state of one solve.
struct State {
    x: Vec<f64>,
    r: Vec<f64>,
    norm: f64,
    jac: Mat<f64>,
    /// Lower triangle of `J^T J` (valid when `jtj_ready`).
    jtj: Mat<f64>,
    jtj_ready: bool,
    /// Euclidean norms of the Jacobian's columns.
    col_norm: Vec<f64>,
    /// Gauss–Newton: the LU factors of `J` (`0 x 0` when not used), its row permutation.
    lu: Mat<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    lu_mem: MemBuffer,
    /// Damped matrix, then its Cholesky factor (lower triangle).
    factor: Mat<f64>,
    grad: Vec<f64>,
    scale: Vec<f64>,
    step: Vec<f64>,
    x_trial: Vec<f64>,
    r_trial: Vec<f64>,
    chol_mem: MemBuffer,
}

impl State {
    /// `jtj = J^T J` (lower), `grad = J^T r`, and Moré's scaling update.
    fn normal_equations(&mut self) {
        self.form_jtj();
        for j in 0..self.grad.len() {
            let col = self.jac.col(j);
            self.grad[j] = (0..self.r.len()).map(|i| col[i] * self.r[i]).sum();
            let col_norm = self.jtj[(j, j)].sqrt();
            self.col_norm[j] = col_norm;
            if col_norm > self.scale[j] {
                self.scale[j] = col_norm;
            }
        }
    }

    /// `grad = J^T r`, the column norms and Moré's scaling update, without `J^T J` (formed
    /// by [`State::form_jtj`] when a damped step needs it).
    fn gradient_only(&mut self) {
        self.jtj_ready = false;
        for j in 0..self.grad.len() {
            let col = self.jac.col(j);
            let (mut g, mut c) = (0.0, 0.0);
            for (&a, &r) in col.iter().zip(&self.r) {
                g += a * r;
                c += a * a;
            }
            self.grad[j] = g;
            self.col_norm[j] = f64::sqrt(c);
            if self.col_norm[j] > self.scale[j] {
                self.scale[j] = self.col_norm[j];
            }
        }
    }

    /// The lower triangle of `J^T J`.
    fn form_jtj(&mut self) {
        triangular::matmul(
            self.jtj.as_mut(),
            BlockStructure::TriangularLower,
            Accum::Replace,
            self.jac.transpose(),
            BlockStructure::Rectangular,
            self.jac.as_ref(),
            BlockStructure::Rectangular,
            1.0,
            Par::Seq,
        );
        self.jtj_ready = true;
    }

    /// Solves `J h = -r` (square `J`) into `step` by an LU factorization with partial
    /// pivoting; false if the step is not finite (a singular `J`).
    fn newton_step(&mut self) -> bool {
        let n = self.grad.len();
        self.lu.copy_from(self.jac.as_ref());
        lu_in_place(
            self.lu.as_mut(),
            &mut self.perm,
            &mut self.perm_inv,
            Par::Seq,
            MemStack::new(&mut self.lu_mem),
            Default::default(),
        );
        for (h, &p) in self.step.iter_mut().zip(&self.perm) {
            *h = -self.r[p];
        }
        let lu = self.lu.as_ref();
        let mut x = faer::MatMut::from_column_major_slice_mut(&mut self.step, n, 1);
        solve_unit_lower_triangular_in_place(lu, x.as_mut(), Par::Seq);
        solve_upper_triangular_in_place(lu, x.as_mut(), Par::Seq);
        self.step.iter().all(|v| v.is_finite())
    }

    /// `max_j |g_j| / (||J_j|| ||r||)` over nonzero columns.
    fn scaled_gradient(&self) -> f64 {
        let mut worst: f64 = 0.0;
        for j in 0..self.grad.len() {
            let col_norm = self.col_norm[j];
            if col_norm > 0.0 && self.norm > 0.0 {
                worst = worst.max(self.grad[j].abs() / (col_norm * self.norm));
            }
        }
        worst
    }

    /// Solves `(J^T J + lambda D^2) h = -g` into `step`; false if not positive definite.
    fn damped_step(&mut self, lambda: f64) -> bool {
        let n = self.grad.len();
        self.factor.copy_from_triangular_lower(self.jtj.as_ref());
        for j in 0..n {
            self.factor[(j, j)] += lambda * self.scale[j] * self.scale[j];
        }
        let stack = MemStack::new(&mut self.chol_mem);
        let ok = llt::factor::cholesky_in_place(
            self.factor.as_mut(),
            Default::default(),
            Par::Seq,
            stack,
            Default::default(),
        );
        if ok.is_err() {
            return false;
        }
        for j in 0..n {
            self.step[j] = -self.grad[j];
        }
        let stack = MemStack::new(&mut self.chol_mem);
        let rhs = faer::MatMut::from_column_major_slice_mut(&mut self.step, n, 1);
        llt::solve::solve_in_place(self.factor.as_ref(), rhs, Par::Seq, stack);
        self.step.iter().all(|v| v.is_finite())
    }
}

/// Minimizes `||r(z)||^2` from `z0` (see the module docs for the algorithm and the stops).
///
/// Returns the report when a residual tolerance is met (or, with `accept_stationary`, at a
/// stationary point); [`LmError::NotConverged`] otherwise.
pub fn solve<P: LeastSquaresProblem>(
    problem: &mut P,
    z0: &[f64],
    options: &LmOptions,
) -> Result<LmReport, LmError<P::Error>> {
    check_options(options)?;
    let (n, m) = (problem.n_params(), problem.n_residuals());
    if n == 0 || m == 0 {
        return Err(LmError::BadSize("no unknowns or no residuals"));
    }
    if z0.len() != n {
        return Err(LmError::BadSize(
            "initial point length differs from n_params",
        ));
    }
    if n.checked_mul(m).is_none_or(|e| e > MAX_JACOBIAN_ENTRIES)
        || n.saturating_mul(n) > MAX_JACOBIAN_ENTRIES
    {
        return Err(LmError::BadSize("Jacobian too large for a dense solve"));
    }
    let mut r = vec![0.0; m];
    problem.residual(z0, &mut r).map_err(LmError::Problem)?;
    if r.iter().any(|v| !v.is_finite()) {
        return Err(LmError::NonFiniteStart);
    }
    let norm0 = norm(&r);
    let chol_req = llt::factor::cholesky_in_place_scratch::<f64>(n, Par::Seq, Default::default())
        .or(llt::solve::solve_in_place_scratch::<f64>(n, 1, Par::Seq));
    let newton = options.newton_damping > 0.0 && m == n;
    let lu_n = if newton { n } else { 0 };
    let mut s = State {
        x: z0.to_vec(),
        r,
        norm: norm0,
        jac: Mat::zeros(m, n),
        jtj: Mat::zeros(n, n),
        jtj_ready: false,
        col_norm: vec![0.0; n],
        lu: Mat::zeros(lu_n, lu_n),
        perm: vec![0; lu_n],
        perm_inv: vec![0; lu_n],
        lu_mem: MemBuffer::new(StackReq::new::<usize>(lu_n)),
        factor: Mat::zeros(n, n),
        grad: vec![0.0; n],
        scale: vec![0.0; n],
        step: vec![0.0; n],
        x_trial: vec![0.0; n],
        r_trial: vec![0.0; m],
        chol_mem: MemBuffer::new(chol_req),
    };
    let mut history = Vec::new();
    let (mut iterations, mut accepted, mut jac_evals) = (0usize, 0usize, 0usize);
    let converged_by = |norm: f64| {
        if norm <= options.abs_tol {
            Some(LmStop::AbsoluteResidual)
        } else if norm <= options.rel_tol * norm0 {
            Some(LmStop::RelativeResidual)
        } else {
            None
        }
    };

    let stop = 'outer: {
        if let Some(stop) = converged_by(norm0) {
            break 'outer stop;
        }
        let mut need_jacobian = true;
        // Whether the current Jacobian's Gauss–Newton step was tried.
        let mut newton_tried = false;
        let mut lambda = options.initial_damping;
        let mut nu = 2.0;
        loop {
            if need_jacobian {
                problem
                    .jacobian(&s.x, s.jac.as_mut())
                    .map_err(LmError::Problem)?;
                jac_evals += 1;
                if !s.jac.is_all_finite() {
                    return Err(LmError::NonFiniteJacobian {
                        iteration: iterations,
                    });
                }
                if newton {
                    s.gradient_only();
                } else {
                    s.normal_equations();
                }
                newton_tried = false;
                for d in &mut s.scale {
                    if *d == 0.0 {
                        *d = 1.0;
                    }
                }
                need_jacobian = false;
                if s.scaled_gradient() <= options.gradient_tol {
                    break 'outer LmStop::SmallGradient;
                }
            }
            if iterations >= options.max_iterations {
                break 'outer LmStop::MaxIterations;
            }
            iterations += 1;
            // A Gauss–Newton trial (module docs) is recorded with damping 0.
            let gauss_newton = newton && !newton_tried && lambda <= options.newton_damping;
            let mut entry = LmIteration {
                iteration: iterations,
                residual_norm: s.norm,
                trial_residual_norm: f64::INFINITY,
                damping: if gauss_newton { 0.0 } else { lambda },
                step_norm: f64::NAN,
                gain_ratio: f64::NEG_INFINITY,
                accepted: false,
            };
            let solvable = if gauss_newton {
                newton_tried = true;
                s.newton_step()
            } else {
                if !s.jtj_ready {
                    s.form_jtj();
                }
                s.damped_step(lambda)
            };
            let mut small_step = false;
            if solvable {
                entry.step_norm = norm(&s.step);
                let dh = scaled_norm(&s.scale, &s.step);
                let dx = scaled_norm(&s.scale, &s.x);
                small_step = dh <= options.step_tol * (dx + options.step_tol);
                for j in 0..n {
                    s.x_trial[j] = s.x[j] + s.step[j];
                }
                problem
                    .residual(&s.x_trial, &mut s.r_trial)
                    .map_err(LmError::Problem)?;
                let trial_norm = norm(&s.r_trial);
                // The model's decrease: `||r||^2 - ||r + J h||^2`, all of `||r||^2` for the
                // Gauss–Newton step (`J h = -r`).
                let predicted: f64 = if gauss_newton {
                    s.norm * s.norm
                } else {
                    (0..n)
                        .map(|j| {
                            s.step[j] * (lambda * s.scale[j] * s.scale[j] * s.step[j] - s.grad[j])
                        })
                        .sum()
                };
                if trial_norm.is_finite() {
                    entry.trial_residual_norm = trial_norm;
                    if predicted > 0.0 {
                        entry.gain_ratio = (s.norm * s.norm - trial_norm * trial_norm) / predicted;
                    }
                }
            }
            if entry.gain_ratio > 0.0 {
                std::mem::swap(&mut s.x, &mut s.x_trial);
                std::mem::swap(&mut s.r, &mut s.r_trial);
                s.norm = entry.trial_residual_norm;
                entry.residual_norm = s.norm;
                entry.accepted = true;
                accepted += 1;
                history.push(entry);
                if let Some(stop) = converged_by(s.norm) {
                    break 'outer stop;
                }
                if small_step {
                    break 'outer LmStop::SmallStep;
                }
                let rho = entry.gain_ratio;
                lambda *= (1.0 - (2.0 * rho - 1.0).powi(3)).max(1.0 / 3.0);
                lambda = lambda.max(options.min_damping);
                nu = 2.0;
                need_jacobian = true;
            } else {
                history.push(entry);
                if gauss_newton {
                    // The damped step at the same lambda comes next.
                    continue;
                }
                if small_step {
                    break 'outer LmStop::SmallStep;
                }
                lambda *= nu;
                nu *= 2.0;
                if lambda.is_nan() || lambda > options.max_damping {
                    break 'outer LmStop::DampingOverflow;
                }
            }
        }
    };

    let report = LmReport {
        residual_norm: s.norm,
        x: s.x,
        residual: s.r,
        initial_residual_norm: norm0,
        iterations,
        accepted_steps: accepted,
        jacobian_evaluations: jac_evals,
        stop,
        history,
    };
    let stationary_ok =
        options.accept_stationary && matches!(stop, LmStop::SmallStep | LmStop::SmallGradient);
    if stop.is_converged() || stationary_ok {
        Ok(report)
    } else {
        Err(LmError::NotConverged {
            report: Box::new(report),
        })
    }
}
