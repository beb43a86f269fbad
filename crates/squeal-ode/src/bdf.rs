//! The variable-order, variable-step BDF/NDF stepper.
//!
//! Quasi-constant step size in backward-difference form, as in Shampine &
//! Reichelt, "The MATLAB ODE suite", SIAM J. Sci. Comput. 18 (1997) 1-22
//! (ode15s) and scipy's `integrate.BDF`:
//! - the history is the array `D` of backward differences of the solution at
//!   equally spaced points `t_n - j h`; a step-size change by `rho`
//!   re-interpolates it (`D <- (R U)^T D`, S&R Sec. 2.3);
//! - the corrector of order k solves
//!   `(y - y_pred) - c f(t_new, y) + psi = 0`, `c = h / alpha_k`,
//!   `psi = sum_{j=1..k} gamma_j D_j / alpha_k` (S&R Eq. (2)-(4) with the NDF
//!   coefficients `alpha_k = (1 - kappa_k) gamma_k`);
//! - simplified Newton with the matrix `I - c J`, LU-factorized (faer,
//!   sequential for bit-reproducibility) and reused while `c` stays within
//!   30% of the factorized one (CVODE's rule); the contraction rate measured
//!   with a factorization is remembered so that a first iteration can be
//!   accepted (CVODE's `crate`); on a Newton failure the LU is refreshed,
//!   then the Jacobian, then the step is halved;
//! - local error `err = (kappa_k gamma_k + 1/(k+1)) * nabla^{k+1} y_{n+1}`
//!   (S&R Eq. (5)), step and order selection from the error estimates of
//!   orders k-1, k, k+1 after k+1 steps of constant size.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::lu::partial_pivoting::factor::lu_in_place;
use faer::linalg::triangular_solve::{
    solve_unit_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{ColMut, Mat, MatMut, MatRef, Par};

use crate::error::OdeError;
use crate::options::{BdfOptions, BdfStats, MAX_ORDER};

mod newton;
#[allow(unused_imports)]
use newton::*;

/// Largest system dimension accepted (two dense `n x n` matrices are kept:
/// 2 x 800 MB at this bound).
pub const MAX_DIM: usize = 10_000;

/// Smallest step-size reduction after a failed error test.
const MIN_FACTOR: f64 = 0.2;
/// Largest step-size increase after a successful step.
const MAX_FACTOR: f64 = 10.0;
/// Step-size reduction after a Newton failure with a fresh Jacobian.
const NEWTON_FAIL_FACTOR: f64 = 0.5;
/// Rows of the difference array: orders 0..=MAX_ORDER+2.
const D_ROWS: usize = MAX_ORDER + 3;
/// An LU of `I - c_lu J` is reused for `c` while `|c / c_lu - 1| <= 0.3`
/// (CVODE's `DGMAX` rule); Newton then converges somewhat slower, and a
/// failure triggers a refactorization before a new Jacobian.
const LU_REUSE_TOL: f64 = 0.3;
/// Decay of the remembered Newton contraction rate (CVODE's `CRDOWN`).
const RATE_DECAY: f64 = 0.3;

/// A first-order system `y' = f(t, y)` with an analytic dense Jacobian.
pub trait OdeSystem {
    /// Number of states.
    fn dim(&self) -> usize;
    /// Right-hand side: write `f(t, y)` into `dy` (length `dim`).
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]);
    /// Jacobian `df/dy` (`dim x dim`, entry (i, j) = `d f_i / d y_j`) written
    /// into `jac`. Every entry must be written.
    fn jacobian(&self, t: f64, y: &[f64], jac: MatMut<'_, f64>);
}

impl<S: OdeSystem + ?Sized> OdeSystem for &S {
    fn dim(&self) -> usize {
        (**self).dim()
    }
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        (**self).rhs(t, y, dy)
    }
    fn jacobian(&self, t: f64, y: &[f64], jac: MatMut<'_, f64>) {
        (**self).jacobian(t, y, jac)
    }
}

/// Variable-order (1..=5), variable-step BDF/NDF stepper with dense output.
///
/// Create with [`Bdf::new`], advance with [`Bdf::step`] until
/// [`Bdf::is_finished`]; between steps, [`Bdf::interpolate`] evaluates the
/// interpolating polynomial anywhere in the last step `[t_prev, t]`.
pub struct Bdf<S: OdeSystem> {
    system: S,
    n: usize,
    opts: BdfOptions,
    rtol: f64,
    atol: Vec<f64>,
    coef: Coefficients,
    newton_tol: f64,
    t: f64,
    t_prev: f64,
    t_end: f64,
    h: f64,
    order: usize,
    n_equal_steps: usize,
    /// Backward differences, row j (length n) at `d[j * n..(j + 1) * n]`.
    d: Vec<f64>,
    jac: Mat<f64>,
    jac_current: bool,
    newton: NewtonMatrix,
    y_predict: Vec<f64>,
    psi: Vec<f64>,
    y_new: Vec<f64>,
    dsum: Vec<f64>,
    f: Vec<f64>,
    dy: Vec<f64>,
    scale: Vec<f64>,
    stats: BdfStats,
    finished: bool,
}

impl<S: OdeSystem> Bdf<S> {
    /// Start an integration of `system` from `y0` at `t0` towards `t_end > t0`.
    /// Evaluates `f(t0, y0)` and the Jacobian once.
    pub fn new(
        system: S,
        t0: f64,
        y0: &[f64],
        t_end: f64,
        options: &BdfOptions,
    ) -> Result<Self, OdeError> {
        let mut bdf = Self::allocate(system, t0, y0, t_end, options)?;
        let n = bdf.n;
        bdf.system.rhs(t0, y0, &mut bdf.f);
        bdf.stats.rhs_evals += 1;
        if !all_finite(&bdf.f) {
            return Err(OdeError::NonFinite {
                what: "right-hand side",
                t: t0,
            });
        }
        bdf.update_jacobian(t0, y0)?;
        bdf.h = match (options.fixed_step, options.first_step) {
            (Some(fixed), _) => fixed.h,
            (None, Some(h)) => h.min(options.max_step),
            (None, None) => bdf.select_initial_step(y0)?,
        };
        bdf.d[..n].copy_from_slice(y0);
        for i in 0..n {
            bdf.d[n + i] = bdf.h * bdf.f[i];
        }
        Ok(bdf)
    }

    /// Start a fixed-order, fixed-step run (`options.fixed_step` required)
    /// from an exact history: `past[j] = y(t0 - j h)` for `j = 0..=order`.
    /// The backward differences are formed from it, so the method has its
    /// full order from the first step (used by the convergence tests).
    pub fn with_history(
        system: S,
        t0: f64,
        past: &[Vec<f64>],
        t_end: f64,
        options: &BdfOptions,
    ) -> Result<Self, OdeError> {
        let Some(fixed) = options.fixed_step else {
            return Err(OdeError::InvalidOption {
                name: "fixed_step",
                reason: "with_history needs a fixed order and step".into(),
            });
        };
        if past.len() != fixed.order + 1 {
            return Err(OdeError::DimensionMismatch {
                what: "history (order + 1 states)",
                expected: fixed.order + 1,
                got: past.len(),
            });
        }
        let y0 = &past[0];
        let mut bdf = Self::allocate(system, t0, y0, t_end, options)?;
        let n = bdf.n;
        for y in past {
            if y.len() != n {
                return Err(OdeError::DimensionMismatch {
                    what: "history state",
                    expected: n,
                    got: y.len(),
                });
            }
            if !all_finite(y) {
                return Err(OdeError::NonFinite {
                    what: "initial state",
                    t: t0,
                });
            }
        }
        bdf.update_jacobian(t0, y0)?;
        bdf.h = fixed.h;
        // Difference table: after pass j, tab[i] = nabla^j y(t0 - i h).
        let mut tab: Vec<Vec<f64>> = past.to_vec();
        bdf.d[..n].copy_from_slice(y0);
        for j in 1..=fixed.order {
            for i in 0..=fixed.order - j {
                for c in 0..n {
                    tab[i][c] -= tab[i + 1][c];
                }
            }
            bdf.d[j * n..(j + 1) * n].copy_from_slice(&tab[0]);
        }
        Ok(bdf)
    }

    /// Validate inputs and allocate all work storage.
    fn allocate(
        system: S,
        t0: f64,
        y0: &[f64],
        t_end: f64,
        options: &BdfOptions,
    ) -> Result<Self, OdeError> {
        let n = system.dim();
        if n == 0 || n > MAX_DIM {
            return Err(OdeError::InvalidOption {
                name: "dim",
                reason: format!("system dimension {n} not in 1..={MAX_DIM}"),
            });
        }
        if y0.len() != n {
            return Err(OdeError::DimensionMismatch {
                what: "y0",
                expected: n,
                got: y0.len(),
            });
        }
        if !(t0.is_finite() && t_end.is_finite() && t_end > t0) {
            return Err(OdeError::InvalidOption {
                name: "t_end",
                reason: "t0 and t_end must be finite with t_end > t0".into(),
            });
        }
        if !all_finite(y0) {
            return Err(OdeError::NonFinite {
                what: "initial state",
                t: t0,
            });
        }
        let atol = options.validate(n)?;
        let rtol = options.rtol.max(100.0 * f64::EPSILON);
        let order = options.fixed_step.map_or(1, |f| f.order);
        Ok(Self {
            system,
            n,
            opts: options.clone(),
            rtol,
            atol,
            coef: Coefficients::new(options.ndf),
            newton_tol: (10.0 * f64::EPSILON / rtol).max(rtol.sqrt().min(0.03)),
            t: t0,
            t_prev: t0,
            t_end,
            h: 0.0,
            order,
            n_equal_steps: 0,
            d: vec![0.0; D_ROWS * n],
            jac: Mat::zeros(n, n),
            jac_current: false,
            newton: NewtonMatrix::new(n),
            y_predict: vec![0.0; n],
            psi: vec![0.0; n],
            y_new: vec![0.0; n],
            dsum: vec![0.0; n],
            f: vec![0.0; n],
            dy: vec![0.0; n],
            scale: vec![0.0; n],
            stats: BdfStats::default(),
            finished: false,
        })
    }

    /// Hairer, Norsett & Wanner I, Sec. II.4 starting step for order 1
    /// (scipy `select_initial_step`); `self.f` holds `f(t0, y0)`.
    fn select_initial_step(&mut self, y0: &[f64]) -> Result<f64, OdeError> {
        let span = self.t_end - self.t;
        for i in 0..self.n {
            self.scale[i] = self.atol[i] + self.rtol * y0[i].abs();
        }
        let d0 = rms_norm(y0, &self.scale);
        let d1 = rms_norm(&self.f, &self.scale);
        let h0 = if d0 < 1e-5 || d1 < 1e-5 {
            1e-6
        } else {
            0.01 * d0 / d1
        }
        .min(span);
        for i in 0..self.n {
            self.y_new[i] = y0[i] + h0 * self.f[i];
        }
        self.system.rhs(self.t + h0, &self.y_new, &mut self.dy);
        self.stats.rhs_evals += 1;
        for i in 0..self.n {
            self.dy[i] -= self.f[i];
        }
        let d2 = rms_norm(&self.dy, &self.scale) / h0;
        let h1 = if !d2.is_finite() {
            h0
        } else if d1 <= 1e-15 && d2 <= 1e-15 {
            (h0 * 1e-3).max(1e-6)
        } else {
            (0.01 / d1.max(d2)).sqrt()
        };
        Ok((100.0 * h0).min(h1).min(span).min(self.opts.max_step))
    }

    /// Evaluate the Jacobian at `(t, y)`; non-finite entries are an error.
    fn update_jacobian(&mut self, t: f64, y: &[f64]) -> Result<(), OdeError> {
        self.system.jacobian(t, y, self.jac.as_mut());
        self.stats.jac_evals += 1;
        let n = self.n;
        for j in 0..n {
            for i in 0..n {
                if !self.jac[(i, j)].is_finite() {
                    return Err(OdeError::NonFinite {
                        what: "Jacobian",
                        t,
                    });
                }
            }
        }
        self.jac_current = true;
        self.newton.c = None;
        Ok(())
    }

    /// Re-interpolate the differences of orders `0..=order` for a step size
    /// multiplied by `factor` (S&R Sec. 2.3: `D <- (R(factor) U)^T D`,
    /// `U = R(1)`). The interpolating polynomial is unchanged.
    fn change_d(&mut self, factor: f64) {
        let k = self.order;
        let r = compute_r(k, factor);
        let u = compute_r(k, 1.0);
        let mut ru = [[0.0; MAX_ORDER + 1]; MAX_ORDER + 1];
        for i in 0..=k {
            for j in 0..=k {
                ru[i][j] = (0..=k).map(|l| r[i][l] * u[l][j]).sum();
            }
        }
        let n = self.n;
        let mut new_rows = [0.0; MAX_ORDER + 1];
        for c in 0..n {
            for (i, row) in new_rows.iter_mut().enumerate().take(k + 1) {
                *row = (0..=k).map(|j| ru[j][i] * self.d[j * n + c]).sum();
            }
            for (i, row) in new_rows.iter().enumerate().take(k + 1) {
                self.d[i * n + c] = *row;
            }
        }
    }

    /// Change the step size by `factor` (differences re-interpolated, LU
    /// stale, constant-step counter reset).
    fn rescale(&mut self, factor: f64) {
        self.h *= factor;
        self.change_d(factor);
        self.n_equal_steps = 0;
    }

    /// Simplified Newton iteration for the corrector (scipy
    /// `solve_bdf_system`): stops when the predicted remaining error
    /// `rate/(1-rate) |dy|` is below `newton_tol`, fails when the rate is >= 1
    /// or convergence within the iteration budget is predicted impossible.
    fn newton_solve(&mut self, t_new: f64, c: f64) -> NewtonOutcome {
        let n = self.n;
        let max_iter = self.opts.max_newton_iter;
        self.y_new.copy_from_slice(&self.y_predict);
        self.dsum.fill(0.0);
        let mut dy_norm_old: Option<f64> = None;
        for k in 0..max_iter {
            self.system.rhs(t_new, &self.y_new, &mut self.f);
            self.stats.rhs_evals += 1;
            if !all_finite(&self.f) {
                return NewtonOutcome {
                    converged: false,
                    iterations: k + 1,
                    non_finite: true,
                };
            }
            for i in 0..n {
                self.dy[i] = c * self.f[i] - self.psi[i] - self.dsum[i];
            }
            self.newton.solve(&mut self.dy);
            self.stats.newton_iters += 1;
            let dy_norm = rms_norm(&self.dy, &self.scale);
            if !dy_norm.is_finite() {
                break;
            }
            let measured = dy_norm_old.map(|old| dy_norm / old);
            if let Some(r) = measured {
                let decayed = self.newton.rate.map_or(0.0, |old| RATE_DECAY * old);
                self.newton.rate = Some(r.max(decayed));
            }
            // Without a measured rate yet, the one remembered from earlier
            // steps with the same LU (CVODE) lets a first iteration converge.
            let rate = measured.or(if k == 0 { self.newton.rate } else { None });
            if let Some(rate) = measured
                && (rate >= 1.0
                    || rate.powi((max_iter - k) as i32) / (1.0 - rate) * dy_norm > self.newton_tol)
            {
                break;
            }
            for i in 0..n {
                self.y_new[i] += self.dy[i];
                self.dsum[i] += self.dy[i];
            }
            let done = dy_norm == 0.0
                || rate.is_some_and(|r| r < 1.0 && r / (1.0 - r) * dy_norm < self.newton_tol);
            if done {
                return NewtonOutcome {
                    converged: true,
                    iterations: k + 1,
                    non_finite: false,
                };
            }
            dy_norm_old = Some(dy_norm);
        }
        NewtonOutcome {
            converged: false,
            iterations: max_iter,
            non_finite: false,
        }
    }

    /// Newton with fallbacks: refactor if the LU belongs to another `c`, then
    /// re-evaluate the Jacobian at the predictor if it is not current.
    fn corrector(&mut self, t_new: f64, c: f64) -> Result<NewtonOutcome, OdeError> {
        loop {
            let reusable = self
                .newton
                .c
                .is_some_and(|c_lu| (c / c_lu - 1.0).abs() <= LU_REUSE_TOL);
            if !reusable {
                self.newton.factor(self.jac.as_ref(), c);
                self.stats.lu_decomps += 1;
            }
            let outcome = self.newton_solve(t_new, c);
            if outcome.converged {
                return Ok(outcome);
            }
            if self.newton.c != Some(c) {
                self.newton.c = None;
            } else if !self.jac_current {
                let y_predict = std::mem::take(&mut self.y_predict);
                let res = self.update_jacobian(t_new, &y_predict);
                self.y_predict = y_predict;
                res?;
            } else {
                return Ok(outcome);
            }
        }
    }

    /// Advance by one accepted step (never past `t_end`).
    pub fn step(&mut self) -> Result<(), OdeError> {
        if self.finished {
            return Err(OdeError::Finished { t_end: self.t_end });
        }
        if self.stats.steps >= self.opts.max_steps {
            return Err(OdeError::TooManySteps {
                t: self.t,
                max_steps: self.opts.max_steps,
            });
        }
        let fixed = self.opts.fixed_step.is_some();
        let min_step = self.min_step();
        if !fixed && self.h > self.opts.max_step {
            self.rescale(self.opts.max_step / self.h);
        } else if !fixed && self.h < min_step {
            self.rescale(min_step / self.h);
        }
        self.jac_current = false;
        let mut last_failure = Failure::ErrorTest;
        loop {
            if self.h < min_step {
                return Err(self.failure_error(last_failure));
            }
            let mut t_new = self.t + self.h;
            if t_new > self.t_end - 1e-3 * self.h {
                t_new = self.t_end;
                let factor = (t_new - self.t) / self.h;
                self.rescale(factor);
            }
            let h = self.h;
            self.predict();
            let c = h / self.coef.alpha[self.order];
            let outcome = self.corrector(t_new, c)?;
            if !outcome.converged {
                if fixed {
                    return Err(OdeError::NewtonFailure { t: self.t, h });
                }
                self.stats.rejected_newton += 1;
                last_failure = if outcome.non_finite {
                    Failure::NonFinite
                } else {
                    Failure::Newton
                };
                self.rescale(NEWTON_FAIL_FACTOR);
                continue;
            }
            // scipy's safety factor; a first iteration accepted on the
            // remembered rate counts as two so that it does not enlarge h.
            let maxit = self.opts.max_newton_iter as f64;
            let iters = outcome.iterations.max(2) as f64;
            let safety = 0.9 * (2.0 * maxit + 1.0) / (2.0 * maxit + iters);
            for i in 0..self.n {
                self.scale[i] = self.atol[i] + self.rtol * self.y_new[i].abs();
            }
            let error_norm = self.coef.error_const[self.order] * rms_norm(&self.dsum, &self.scale);
            if !fixed && error_norm > 1.0 {
                let exponent = -1.0 / (self.order + 1) as f64;
                let factor = MIN_FACTOR.max(safety * error_norm.powf(exponent));
                self.stats.rejected_error += 1;
                last_failure = Failure::ErrorTest;
                self.rescale(factor);
                continue;
            }
            self.accept(t_new);
            if !fixed && !self.finished {
                self.select_step_and_order(error_norm, safety);
            }
            return Ok(());
        }
    }

    /// Floor of the step size: `min_step` or 10 ulp of t.
    fn min_step(&self) -> f64 {
        let ulp = f64::from_bits(self.t.abs().to_bits() + 1) - self.t.abs();
        (10.0 * ulp).max(self.opts.min_step)
    }

    fn failure_error(&self, failure: Failure) -> OdeError {
        match failure {
            Failure::ErrorTest => OdeError::StepSizeTooSmall {
                t: self.t,
                h: self.h,
            },
            Failure::Newton => OdeError::NewtonFailure {
                t: self.t,
                h: self.h,
            },
            Failure::NonFinite => OdeError::NonFinite {
                what: "right-hand side",
                t: self.t,
            },
        }
    }

    /// Predictor `y_pred = sum_{j<=k} D_j`, Newton weights and `psi`.
    fn predict(&mut self) {
        let n = self.n;
        let k = self.order;
        let alpha = self.coef.alpha[k];
        for i in 0..n {
            let mut yp = 0.0;
            let mut psi = 0.0;
            for j in 0..=k {
                let dj = self.d[j * n + i];
                yp += dj;
                psi += self.coef.gamma[j] * dj;
            }
            self.y_predict[i] = yp;
            self.psi[i] = psi / alpha;
            self.scale[i] = self.atol[i] + self.rtol * yp.abs();
        }
    }

    /// Accept `y_new` at `t_new` and update the differences:
    /// `D_{k+2} = d - D_{k+1}`, `D_{k+1} = d`, `D_i += D_{i+1}` for `i <= k`
    /// with `d = nabla^{k+1} y_{n+1} = y_new - y_pred`.
    fn accept(&mut self, t_new: f64) {
        let n = self.n;
        let k = self.order;
        for i in 0..n {
            let d = self.dsum[i];
            self.d[(k + 2) * n + i] = d - self.d[(k + 1) * n + i];
            self.d[(k + 1) * n + i] = d;
        }
        for j in (0..=k).rev() {
            for i in 0..n {
                self.d[j * n + i] += self.d[(j + 1) * n + i];
            }
        }
        self.t_prev = self.t;
        self.t = t_new;
        self.n_equal_steps += 1;
        self.stats.steps += 1;
        self.stats.order_histogram[k - 1] += 1;
        if t_new >= self.t_end {
            self.finished = true;
        }
    }

    /// After k+1 steps of equal size: compare the error estimates of orders
    /// k-1, k, k+1 (S&R Sec. 2.2, scipy) and pick the order allowing the
    /// largest step; change h unless the increase is below `min_increase`.
    fn select_step_and_order(&mut self, error_norm: f64, safety: f64) {
        let k = self.order;
        if self.n_equal_steps < k + 1 {
            return;
        }
        let n = self.n;
        let err_m = if k > 1 {
            self.coef.error_const[k - 1] * rms_norm(&self.d[k * n..(k + 1) * n], &self.scale)
        } else {
            f64::INFINITY
        };
        let err_p = if k < self.opts.max_order {
            self.coef.error_const[k + 1] * rms_norm(&self.d[(k + 2) * n..(k + 3) * n], &self.scale)
        } else {
            f64::INFINITY
        };
        let norms = [err_m, error_norm, err_p];
        let mut best = 1;
        let mut best_factor = 0.0;
        for (i, e) in norms.iter().enumerate() {
            let f = e.powf(-1.0 / (k + i) as f64);
            if f > best_factor {
                best_factor = f;
                best = i;
            }
        }
        let factor = MAX_FACTOR.min(safety * best_factor);
        if best == 1 && factor >= 1.0 && factor < self.opts.min_increase {
            return;
        }
        self.order = k + best - 1;
        self.rescale(factor);
    }

    /// Dense output: the interpolating polynomial of the last step at `t`
    /// (`t_prev <= t <= t_now`, up to 1e-9 of the step for rounding).
    pub fn interpolate(&self, t: f64, out: &mut [f64]) -> Result<(), OdeError> {
        if out.len() != self.n {
            return Err(OdeError::DimensionMismatch {
                what: "interpolation output",
                expected: self.n,
                got: out.len(),
            });
        }
        let slack = 1e-9 * (self.t - self.t_prev);
        if !(t >= self.t_prev - slack && t <= self.t + slack) {
            return Err(OdeError::OutOfRange {
                t,
                t_prev: self.t_prev,
                t_cur: self.t,
            });
        }
        self.eval_polynomial(t, out);
        Ok(())
    }

    /// `y(t) = D_0 + sum_{j=1..k} D_j prod_{m<j} (t - t_n + m h) / ((m+1) h)`
    /// (Newton form on the equally spaced virtual nodes). No range check:
    /// crate-internal callers stay within the interpolation nodes.
    pub(crate) fn eval_polynomial(&self, t: f64, out: &mut [f64]) {
        let n = self.n;
        out.copy_from_slice(&self.d[..n]);
        let mut p = 1.0;
        for j in 0..self.order {
            let node = self.t - j as f64 * self.h;
            p *= (t - node) / ((j + 1) as f64 * self.h);
            let row = &self.d[(j + 1) * n..(j + 2) * n];
            for (o, dj) in out.iter_mut().zip(row) {
                *o += p * dj;
            }
        }
    }

    /// Current time (end of the last accepted step).
    pub fn t(&self) -> f64 {
        self.t
    }
    /// Start of the last accepted step (= t0 before the first step).
    pub fn t_prev(&self) -> f64 {
        self.t_prev
    }
    /// End time given at creation.
    pub fn t_end(&self) -> f64 {
        self.t_end
    }
    /// Current state y(t).
    pub fn y(&self) -> &[f64] {
        &self.d[..self.n]
    }
    /// Step size proposed for the next step.
    pub fn step_size(&self) -> f64 {
        self.h
    }
    /// Order proposed for the next step.
    pub fn order(&self) -> usize {
        self.order
    }
    /// System dimension.
    pub fn dim(&self) -> usize {
        self.n
    }
    /// True once `t_end` has been reached.
    pub fn is_finished(&self) -> bool {
        self.finished
    }
    /// Counters so far.
    pub fn stats(&self) -> &BdfStats {
        &self.stats
    }
    /// The system being integrated.
    pub fn system(&self) -> &S {
        &self.system
    }
}

fn all_finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

#[cfg(test)]
mod tests;
