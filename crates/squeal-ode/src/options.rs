//! Integrator options and statistics.

use crate::error::OdeError;

/// Highest BDF/NDF order supported (as in ode15s and scipy's `BDF`).
pub const MAX_ORDER: usize = 5;

/// Absolute tolerance: one value for all components, or one per component.
#[derive(Debug, Clone, PartialEq)]
pub enum Atol {
    /// Same absolute tolerance for every component.
    Scalar(f64),
    /// One absolute tolerance per component (length = system dimension).
    PerComponent(Vec<f64>),
}

/// Fixed order and fixed step size, for convergence tests: no error control,
/// no step or order change. Start such a run with
/// [`Bdf::with_history`](crate::Bdf::with_history) to get the full order from
/// the first step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedStep {
    /// Step size (> 0).
    pub h: f64,
    /// Order, 1..=5.
    pub order: usize,
}

/// Options of the BDF/NDF integrator. The local error of each accepted step
/// satisfies `rms(err_i / (atol_i + rtol * |y_i|)) <= 1` (Shampine & Reichelt
/// 1997, scipy `BDF`).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct BdfOptions {
    /// Relative tolerance (> 0; raised to 100 machine epsilons if smaller).
    pub rtol: f64,
    /// Absolute tolerance (>= 0 each).
    pub atol: Atol,
    /// Highest order used, 1..=5. Orders 1 and 2 are A-stable; 3..5 are not
    /// (BDF5 is A(51.8 deg)-stable), which matters for lightly damped
    /// high-frequency modes.
    pub max_order: usize,
    /// Use the numerical differentiation formulas (NDF, Klopfenstein-Shampine,
    /// as ode15s and scipy) instead of plain BDF.
    pub ndf: bool,
    /// First step size; `None` selects it automatically (Hairer, Norsett &
    /// Wanner I, Sec. II.4).
    pub first_step: Option<f64>,
    /// Largest step size.
    pub max_step: f64,
    /// Smallest step size before giving up (the floor is 10 ulp of t anyway).
    pub min_step: f64,
    /// Maximum number of accepted steps since the start.
    pub max_steps: usize,
    /// Maximum Newton iterations per attempt.
    pub max_newton_iter: usize,
    /// After an accepted step, a proposed step-size increase by a factor below
    /// this is not made (keeps the LU factorization; ode15s-like hysteresis).
    /// 1.0 reproduces scipy's `BDF` exactly.
    pub min_increase: f64,
    /// Fixed order and step (tests only); `None` for normal adaptive runs.
    pub fixed_step: Option<FixedStep>,
}

impl Default for BdfOptions {
    fn default() -> Self {
        Self {
            rtol: 1e-3,
            atol: Atol::Scalar(1e-6),
            max_order: MAX_ORDER,
            ndf: true,
            first_step: None,
            max_step: f64::INFINITY,
            min_step: 0.0,
            max_steps: 10_000_000,
            max_newton_iter: 4,
            min_increase: 1.2,
            fixed_step: None,
        }
    }
}

fn invalid(name: &'static str, reason: impl Into<String>) -> OdeError {
    OdeError::InvalidOption {
        name,
        reason: reason.into(),
    }
}

/// Largest Newton iteration count accepted (bounds the loop, not memory).
const MAX_NEWTON_ITER_LIMIT: usize = 100;

impl BdfOptions {
    /// Check ranges and expand `atol` to one value per component.
    pub(crate) fn validate(&self, dim: usize) -> Result<Vec<f64>, OdeError> {
        if !(self.rtol.is_finite() && self.rtol > 0.0) {
            return Err(invalid("rtol", "must be finite and > 0"));
        }
        let atol = match &self.atol {
            Atol::Scalar(a) => vec![*a; dim],
            Atol::PerComponent(v) => {
                if v.len() != dim {
                    return Err(OdeError::DimensionMismatch {
                        what: "atol",
                        expected: dim,
                        got: v.len(),
                    });
                }
                v.clone()
            }
        };
        if atol.iter().any(|a| !(a.is_finite() && *a >= 0.0)) {
            return Err(invalid("atol", "must be finite and >= 0"));
        }
        if !(1..=MAX_ORDER).contains(&self.max_order) {
            return Err(invalid("max_order", "must be in 1..=5"));
        }
        if let Some(h) = self.first_step
            && !(h.is_finite() && h > 0.0)
        {
            return Err(invalid("first_step", "must be finite and > 0"));
        }
        if self.max_step.is_nan() || self.max_step <= 0.0 {
            return Err(invalid("max_step", "must be > 0"));
        }
        if !(self.min_step >= 0.0 && self.min_step.is_finite() && self.min_step <= self.max_step) {
            return Err(invalid("min_step", "must be finite, >= 0 and <= max_step"));
        }
        if !(1..=MAX_NEWTON_ITER_LIMIT).contains(&self.max_newton_iter) {
            return Err(invalid("max_newton_iter", "must be in 1..=100"));
        }
        if !(self.min_increase.is_finite() && self.min_increase >= 1.0) {
            return Err(invalid("min_increase", "must be finite and >= 1"));
        }
        if let Some(f) = self.fixed_step {
            if !(f.h.is_finite() && f.h > 0.0) {
                return Err(invalid("fixed_step.h", "must be finite and > 0"));
            }
            if !(1..=MAX_ORDER).contains(&f.order) {
                return Err(invalid("fixed_step.order", "must be in 1..=5"));
            }
        }
        Ok(atol)
    }
}

/// Counters of one integration (cumulative since the stepper was created).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BdfStats {
    /// Accepted steps.
    pub steps: usize,
    /// Steps rejected by the local error test.
    pub rejected_error: usize,
    /// Step attempts abandoned because Newton did not converge with a fresh
    /// Jacobian (the step size is then halved).
    pub rejected_newton: usize,
    /// Right-hand-side evaluations.
    pub rhs_evals: usize,
    /// Jacobian evaluations.
    pub jac_evals: usize,
    /// LU factorizations of `I - c J`.
    pub lu_decomps: usize,
    /// Newton iterations (one linear solve each).
    pub newton_iters: usize,
    /// Accepted steps per order: `order_histogram[k - 1]` for order k.
    pub order_histogram: [usize; MAX_ORDER],
}
