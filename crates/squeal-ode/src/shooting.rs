//! Periodic orbits of an autonomous system by shooting: Newton on the initial state and the
//! period, with the monodromy matrix of the variational equations and a phase condition.
//!
//! **Equations.** For `y' = f(y)` with flow `φ(x, t)`, a periodic orbit is a pair `(x, T)`
//! with `r(x, T) = φ(x, T) - x = 0`. These `n` equations in `n + 1` unknowns are one short and
//! their Jacobian in `x` is singular on the orbit: every point of the orbit solves them, and
//! `f(x)` is an eigenvector of the monodromy matrix `M = ∂φ/∂x (x, T)` for the multiplier 1.
//! A phase condition picks one point: the new start lies on the hyperplane through the current
//! start `x_k` normal to the flow there, `p(x) = (W² f(x_k))ᵀ (x - x_k) = 0` (`W` the diagonal
//! of [`ShootingOptions::weights`], the components' scales). Newton's step `(δx, δT)` solves
//!
//! ```text
//! [ M - I           f(φ(x_k, T_k)) ] [δx]   [-r(x_k, T_k)]
//! [ (W² f(x_k))ᵀ    0              ] [δT] = [ 0          ]
//! ```
//!
//! with `∂φ/∂T = f(φ)`. `M` is the solution at `T` of the variational equations
//! `Y' = J(φ(x, t)) Y`, `Y(0) = I` (`J = ∂f/∂y`). The bordered matrix is regular when 1 is a
//! simple multiplier (the orbit is isolated): its eigenvector `f(x)` is excluded by the phase
//! row, and `f(φ)` fills the missing direction.
//!
//! **Chord iterations.** `M` only steers the iteration: the solution is where the residual
//! `r`, computed at the flow's tolerance, vanishes. An `M` from an earlier iterate (or from an
//! approximate orbit) gives linear convergence at a rate of about `‖(M - I)⁻¹ ΔM‖`; the caller's
//! monodromy is recomputed only when the residual falls by less than
//! [`ShootingOptions::refresh`] in one step.
//!
//! **Measures.** The periodicity residual is `‖W r‖₂ / A` with `A = (T/2π) ‖W f(x)‖₂`, the
//! amplitude of the oscillation in the weighted norm (for `x = a cos ωt` with the velocity
//! weighted by `1/ω`, `A = a`). It says how periodic the computed trajectory is, not how close it
//! is to the exact orbit: the integration error of one period is estimated by solving again at
//! another tolerance (the caller's job).

use crate::bdf::{Bdf, OdeSystem};
use crate::error::OdeError;
use crate::options::{BdfOptions, BdfStats};
use faer::Mat;
use faer::linalg::solvers::Solve;
use squeal_hbm::{FourierSums, Periodic};
use std::f64::consts::PI;

/// Errors of [`shoot`].
#[derive(Debug, thiserror::Error)]
pub enum ShootingError {
    /// A period's integration failed.
    #[error("integrating one period: {0}")]
    Ode(#[from] OdeError),
    /// The caller's monodromy matrix could not be computed.
    #[error("the monodromy matrix: {0}")]
    Monodromy(Box<dyn std::error::Error + Send + Sync>),
    /// The monodromy matrix does not have the system's dimension.
    #[error("the monodromy matrix is {rows} x {cols}, the system has dimension {dim}")]
    MonodromyShape {
        /// Rows given.
        rows: usize,
        /// Columns given.
        cols: usize,
        /// The system's dimension.
        dim: usize,
    },
    /// The start, the period or the options are not usable (why, in words).
    #[error("shooting: {0}")]
    Invalid(String),
    /// Newton's bordered matrix is singular or the step is not finite (1 is not a simple
    /// multiplier, or the flow vanishes at the start: an equilibrium).
    #[error("the Newton step is not finite at iteration {iteration} (residual {residual:.3e})")]
    Singular {
        /// Iteration (1-based).
        iteration: usize,
        /// Relative periodicity residual then.
        residual: f64,
    },
    /// The residual did not reach [`ShootingOptions::tol`].
    #[error(
        "no periodic orbit to {tol:.1e}: relative periodicity residual {residual:.3e} after {iterations} iterations"
    )]
    NotConverged {
        /// Iterations made.
        iterations: usize,
        /// Smallest relative periodicity residual reached.
        residual: f64,
        /// The tolerance asked.
        tol: f64,
    },
}

/// Options of [`shoot`].
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct ShootingOptions {
    /// Options of each period's BDF integration.
    pub bdf: BdfOptions,
    /// Scale of each state component in the norms and the phase condition (empty: all 1).
    pub weights: Vec<f64>,
    /// Relative periodicity residual at which the orbit is accepted (module docs).
    pub tol: f64,
    /// Newton iterations (each one period's integration).
    pub max_iterations: usize,
    /// Newton steps always taken before the residual may stop the iteration (a start already
    /// within [`ShootingOptions::tol`] still moves to the orbit of this tolerance's flow).
    pub min_iterations: usize,
    /// Recompute the monodromy when one step divides the residual by less than `1 / refresh`
    /// (not within 10 [`ShootingOptions::tol`], near the integration's noise floor).
    pub refresh: f64,
    /// Harmonics of the trajectory's Fourier series ([`Flow::trajectory`]).
    pub harmonics: usize,
    /// Samples per period of that series (more than `2 harmonics`).
    pub samples: usize,
}

impl Default for ShootingOptions {
    fn default() -> Self {
        Self {
            bdf: BdfOptions {
                rtol: 1e-10,
                atol: crate::Atol::Scalar(1e-12),
                ..BdfOptions::default()
            },
            weights: Vec::new(),
            tol: 1e-9,
            max_iterations: 12,
            min_iterations: 0,
            refresh: 0.1,
            harmonics: 20,
            samples: 128,
        }
    }
}

/// One period's integration from a start.
#[derive(Clone, Debug)]
pub struct Flow {
    /// `φ(x, T)`.
    pub end: Vec<f64>,
    /// Fourier series of every state component over `[0, T)` (samples by dense output).
    pub trajectory: Periodic,
    /// The integrator's counters.
    pub stats: BdfStats,
}

/// Integrates `sys` from `x0` over `period`, sampling `samples` equally spaced states for a
/// Fourier series of `harmonics` harmonics.
pub fn flow<S: OdeSystem>(
    sys: &S,
    x0: &[f64],
    period: f64,
    bdf: &BdfOptions,
    harmonics: usize,
    samples: usize,
) -> Result<Flow, ShootingError> {
    let n = sys.dim();
    let mut sums = FourierSums::new(n, harmonics, samples, 1, 0.0, period)
        .map_err(|e| ShootingError::Invalid(e.to_string()))?;
    let mut stepper = Bdf::new(sys, 0.0, x0, period, bdf)?;
    let mut y = vec![0.0; n];
    loop {
        while let Some(t) = sums.next_time() {
            if t > stepper.t() {
                break;
            }
            stepper.interpolate(t.max(stepper.t_prev()), &mut y)?;
            sums.add(&y);
        }
        if stepper.is_finished() {
            break;
        }
        stepper.step()?;
    }
    Ok(Flow {
        end: stepper.y().to_vec(),
        trajectory: sums.periodic(),
        stats: *stepper.stats(),
    })
}

/// A periodic orbit found by [`shoot`].
#[derive(Clone, Debug)]
pub struct PeriodicOrbit {
    /// Its start `x` (on the phase condition's hyperplane).
    pub x0: Vec<f64>,
    /// Its period `T`.
    pub period: f64,
    /// Relative periodicity residual `‖W (φ(x, T) - x)‖ / A` (module docs).
    pub residual: f64,
    /// The residual of every iterate, the first (the start) to the last (this orbit).
    pub residuals: Vec<f64>,
    /// The amplitude scale `A` of the residual.
    pub amplitude: f64,
    /// The last period's integration: Fourier series of the orbit and its counters.
    pub flow: Flow,
    /// The last monodromy matrix used (computed at an earlier iterate, see
    /// [`PeriodicOrbit::monodromy_at`]).
    pub monodromy: Mat<f64>,
    /// The iteration whose start the monodromy was computed at (0: the start).
    pub monodromy_at: usize,
    /// Monodromy matrices computed.
    pub monodromies: usize,
    /// Accepted BDF steps of every period integrated.
    pub steps: usize,
}

fn weighted_norm(w: &[f64], v: &[f64]) -> f64 {
    w.iter()
        .zip(v)
        .map(|(a, b)| (a * b).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Checks the start and the options; returns the weights (all 1 when none are given).
fn checked(
    n: usize,
    x0: &[f64],
    period: f64,
    opts: &ShootingOptions,
) -> Result<Vec<f64>, ShootingError> {
    if x0.len() != n {
        return Err(OdeError::DimensionMismatch {
            what: "shooting start",
            expected: n,
            got: x0.len(),
        }
        .into());
    }
    if !(period.is_finite() && period > 0.0) {
        return Err(ShootingError::Invalid(format!(
            "the period must be a positive number (got {period})"
        )));
    }
    if !(opts.tol.is_finite() && opts.tol > 0.0 && opts.max_iterations > 0) {
        return Err(ShootingError::Invalid(
            "the tolerance must be positive and at least one iteration allowed".into(),
        ));
    }
    let w = if opts.weights.is_empty() {
        vec![1.0; n]
    } else {
        opts.weights.clone()
    };
    if w.len() != n || w.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
        return Err(ShootingError::Invalid(format!(
            "{} weights given for {n} states, each must be positive",
            opts.weights.len()
        )));
    }
    Ok(w)
}

/// The Newton step of the module docs: `(δx, δT)` from the bordered system.
fn newton_step(
    m: &Mat<f64>,
    r: &[f64],
    f_end: &[f64],
    phase_row: &[f64],
) -> Option<(Vec<f64>, f64)> {
    let n = r.len();
    let a = Mat::<f64>::from_fn(n + 1, n + 1, |i, j| match (i < n, j < n) {
        (true, true) => m[(i, j)] - if i == j { 1.0 } else { 0.0 },
        (true, false) => f_end[i],
        (false, true) => phase_row[j],
        (false, false) => 0.0,
    });
    let rhs = Mat::<f64>::from_fn(n + 1, 1, |i, _| if i < n { -r[i] } else { 0.0 });
    let d = a.partial_piv_lu().solve(&rhs);
    let dx: Vec<f64> = (0..n).map(|i| d[(i, 0)]).collect();
    let dt = d[(n, 0)];
    (dx.iter().all(|v| v.is_finite()) && dt.is_finite()).then_some((dx, dt))
}

/// Finds the periodic orbit of the autonomous `sys` near the start `(x0, period)` by Newton's
/// method (module docs). `monodromy(x, T, flow)` returns `∂φ/∂x (x, T)` (or an approximation:
/// it only steers) given the start, the period and that period's integration; it is called at
/// the first iterate and again whenever convergence is slow.
pub fn shoot<S, F, E>(
    sys: &S,
    x0: &[f64],
    period: f64,
    opts: &ShootingOptions,
    monodromy: &mut F,
) -> Result<PeriodicOrbit, ShootingError>
where
    S: OdeSystem,
    F: FnMut(&[f64], f64, &Flow) -> Result<Mat<f64>, E>,
    E: Into<Box<dyn std::error::Error + Send + Sync>>,
{
    let n = sys.dim();
    let w = checked(n, x0, period, opts)?;
    let (mut x, mut t) = (x0.to_vec(), period);
    let mut residuals = Vec::new();
    let mut current: Option<(Mat<f64>, usize)> = None;
    let (mut monodromies, mut steps, mut best) = (0, 0, f64::INFINITY);
    let (mut f_start, mut f_end) = (vec![0.0; n], vec![0.0; n]);
    for it in 0..opts.max_iterations {
        let fl = flow(sys, &x, t, &opts.bdf, opts.harmonics, opts.samples)?;
        steps += fl.stats.steps;
        let r: Vec<f64> = fl.end.iter().zip(&x).map(|(a, b)| a - b).collect();
        sys.rhs(0.0, &x, &mut f_start);
        sys.rhs(t, &fl.end, &mut f_end);
        let amplitude = t / (2.0 * PI) * weighted_norm(&w, &f_start);
        let res = weighted_norm(&w, &r) / amplitude;
        if !res.is_finite() {
            return Err(ShootingError::Singular {
                iteration: it + 1,
                residual: res,
            });
        }
        residuals.push(res);
        best = best.min(res);
        if res <= opts.tol && it >= opts.min_iterations {
            let (m, at) = current.unwrap_or_else(|| (Mat::zeros(0, 0), it));
            return Ok(PeriodicOrbit {
                x0: x,
                period: t,
                residual: res,
                residuals,
                amplitude,
                flow: fl,
                monodromy: m,
                monodromy_at: at,
                monodromies,
                steps,
            });
        }
        // A fresh matrix at the first iterate; later only when convergence is slow and the
        // matrix is older than the previous iterate (a newer one would be about the same).
        let slow = residuals.len() >= 2 && res > opts.refresh * residuals[residuals.len() - 2];
        // Within 10 tol the residual is near the integration's noise floor, where no
        // monodromy helps: the iteration goes on with the one it has.
        let near = res <= 10.0 * opts.tol;
        let stale = current
            .as_ref()
            .is_none_or(|c| slow && !near && c.1 + 1 < it);
        if stale {
            let m = monodromy(&x, t, &fl).map_err(|e| ShootingError::Monodromy(e.into()))?;
            if m.nrows() != n || m.ncols() != n {
                return Err(ShootingError::MonodromyShape {
                    rows: m.nrows(),
                    cols: m.ncols(),
                    dim: n,
                });
            }
            monodromies += 1;
            current = Some((m, it));
        }
        let Some((m, _)) = current.as_ref() else {
            return Err(ShootingError::Invalid("no monodromy matrix".into()));
        };
        let phase_row: Vec<f64> = (0..n).map(|i| w[i] * w[i] * f_start[i]).collect();
        let Some((dx, dt)) = newton_step(m, &r, &f_end, &phase_row) else {
            return Err(ShootingError::Singular {
                iteration: it + 1,
                residual: res,
            });
        };
        for (xi, d) in x.iter_mut().zip(&dx) {
            *xi += d;
        }
        t += dt;
        if !(t.is_finite() && t > 0.0) {
            return Err(ShootingError::Singular {
                iteration: it + 1,
                residual: res,
            });
        }
    }
    Err(ShootingError::NotConverged {
        iterations: opts.max_iterations,
        residual: best,
        tol: opts.tol,
    })
}

/// The augmented system `[y; Y]' = [f(y); J(y) Y]` of the variational equations for `cols`
/// columns (`Y` stored by columns), for [`variational_monodromy`] and [`tangent`]. Its
/// Jacobian drops the second derivatives of `f` (the BDF's Newton then converges a little
/// slower, to the same tolerance).
struct Augmented<'a, S> {
    sys: &'a S,
    n: usize,
    cols: usize,
}

impl<S: OdeSystem> OdeSystem for Augmented<'_, S> {
    fn dim(&self) -> usize {
        self.n * (self.cols + 1)
    }

    fn rhs(&self, t: f64, z: &[f64], dz: &mut [f64]) {
        let n = self.n;
        let (y, cols) = z.split_at(n);
        self.sys.rhs(t, y, &mut dz[..n]);
        let mut j = Mat::<f64>::zeros(n, n);
        self.sys.jacobian(t, y, j.as_mut());
        for c in 0..self.cols {
            let col = &cols[c * n..(c + 1) * n];
            for i in 0..n {
                dz[n + c * n + i] = (0..n).map(|k| j[(i, k)] * col[k]).sum();
            }
        }
    }

    fn jacobian(&self, t: f64, z: &[f64], mut jac: faer::MatMut<'_, f64>) {
        let n = self.n;
        let mut j = Mat::<f64>::zeros(n, n);
        self.sys.jacobian(t, &z[..n], j.as_mut());
        jac.fill(0.0);
        for b in 0..=self.cols {
            for i in 0..n {
                for k in 0..n {
                    jac[(b * n + i, b * n + k)] = j[(i, k)];
                }
            }
        }
    }
}

/// Integrates the state from `x0` and the variational equations from the columns `y0`
/// (`n × cols`, by columns) together over `period`; returns the columns at `period`.
fn variational<S: OdeSystem>(
    sys: &S,
    x0: &[f64],
    y0: &[f64],
    period: f64,
    bdf: &BdfOptions,
    column_atol: f64,
) -> Result<Vec<f64>, OdeError> {
    let n = sys.dim();
    if x0.len() != n || !y0.len().is_multiple_of(n.max(1)) {
        return Err(OdeError::DimensionMismatch {
            what: "variational start",
            expected: n,
            got: x0.len(),
        });
    }
    let cols = y0.len() / n;
    let aug = Augmented { sys, n, cols };
    let mut z0 = x0.to_vec();
    z0.extend_from_slice(y0);
    let atol = match &bdf.atol {
        crate::Atol::Scalar(a) => {
            let mut all = vec![*a; n];
            all.extend(std::iter::repeat_n(column_atol, n * cols));
            all
        }
        crate::Atol::PerComponent(v) => {
            let mut all = v.clone();
            all.extend(std::iter::repeat_n(column_atol, n * cols));
            all
        }
    };
    let bdf = BdfOptions {
        atol: crate::Atol::PerComponent(atol),
        ..bdf.clone()
    };
    let mut stepper = Bdf::new(&aug, 0.0, &z0, period, &bdf)?;
    while !stepper.is_finished() {
        stepper.step()?;
    }
    Ok(stepper.y()[n..].to_vec())
}

/// `∂φ/∂x (x0, T)` by integrating the state and the `n` columns of the variational equations
/// together (`n (n + 1)` states: for small systems; larger ones bring their own). The columns
/// start as unit vectors; their absolute tolerance is `rtol`.
pub fn variational_monodromy<S: OdeSystem>(
    sys: &S,
    x0: &[f64],
    period: f64,
    bdf: &BdfOptions,
) -> Result<Mat<f64>, OdeError> {
    let n = sys.dim();
    let mut y0 = vec![0.0; n * n];
    for c in 0..n {
        y0[c * n + c] = 1.0;
    }
    let z = variational(sys, x0, &y0, period, bdf, bdf.rtol)?;
    Ok(Mat::from_fn(n, n, |i, c| z[c * n + i]))
}

/// `M v = ∂φ/∂x (x0, T) v`: one column of the variational equations, integrated along the
/// trajectory with the state (`2 n` states), its absolute tolerance `column_atol`. On a
/// periodic orbit `M f(x0) = f(x0)` exactly (the multiplier 1): with `v = f(x0)` this is the
/// Floquet check of [`PeriodicOrbit`]s that cannot afford the whole matrix.
pub fn tangent<S: OdeSystem>(
    sys: &S,
    x0: &[f64],
    period: f64,
    v: &[f64],
    bdf: &BdfOptions,
    column_atol: f64,
) -> Result<Vec<f64>, OdeError> {
    if v.len() != sys.dim() {
        return Err(OdeError::DimensionMismatch {
            what: "tangent vector",
            expected: sys.dim(),
            got: v.len(),
        });
    }
    variational(sys, x0, v, period, bdf, column_atol)
}
