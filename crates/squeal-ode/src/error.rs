//! Typed errors of the integrator and of the steady-state detector.

use thiserror::Error;

/// Everything that can go wrong in `squeal-ode`. The integrator never returns
/// a silently wrong answer: it stops with one of these instead.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum OdeError {
    /// A vector given by the caller does not have the system's dimension.
    #[error("{what} has {got} components, the system has dimension {expected}")]
    DimensionMismatch {
        /// Which vector.
        what: &'static str,
        /// The system's dimension.
        expected: usize,
        /// The length found.
        got: usize,
    },
    /// An option is out of its valid range.
    #[error("invalid option `{name}`: {reason}")]
    InvalidOption {
        /// Name of the option field.
        name: &'static str,
        /// What is wrong with it.
        reason: String,
    },
    /// The initial state, the right-hand side or the Jacobian produced NaN or
    /// infinity, and reducing the step size did not cure it.
    #[error("non-finite {what} at t = {t:.6e} s")]
    NonFinite {
        /// `"initial state"`, `"right-hand side"` or `"Jacobian"`.
        what: &'static str,
        /// Time at which it happened.
        t: f64,
    },
    /// The local error test kept failing down to the smallest step size the
    /// floating-point time can represent (10 ulp of t) or `min_step`.
    #[error("step size {h:.3e} s too small at t = {t:.6e} s (error test failures)")]
    StepSizeTooSmall {
        /// Time of the last accepted step.
        t: f64,
        /// Step size that would have been needed.
        h: f64,
    },
    /// The Newton iteration failed to converge, even with a fresh Jacobian,
    /// down to the smallest step size (or at the fixed step size of a
    /// fixed-step run).
    #[error("Newton iteration failed to converge at t = {t:.6e} s with step size {h:.3e} s")]
    NewtonFailure {
        /// Time of the last accepted step.
        t: f64,
        /// Last step size tried.
        h: f64,
    },
    /// `max_steps` accepted steps were taken before reaching the end.
    #[error("too many steps: {max_steps} accepted steps reached at t = {t:.6e} s")]
    TooManySteps {
        /// Time reached.
        t: f64,
        /// The limit.
        max_steps: usize,
    },
    /// Dense output was requested outside the last step.
    #[error("t = {t} is outside the last step [{t_prev}, {t_cur}]")]
    OutOfRange {
        /// Requested time.
        t: f64,
        /// Start of the last step.
        t_prev: f64,
        /// End of the last step.
        t_cur: f64,
    },
    /// `step` was called after the end time had been reached.
    #[error("integration already reached its end time {t_end}")]
    Finished {
        /// The end time.
        t_end: f64,
    },
    /// The steady-state detector reached the end time without finding a
    /// steady oscillation.
    #[error(
        "no steady oscillation by t = {t:.4} s: {cycles} cycles seen; the last one lasted {last_period:.4e} s \
         and its {observable} went {last_peak_to_peak:.3e} {unit} from lowest to highest (peak-to-peak)"
    )]
    NotSteady {
        /// Time reached.
        t: f64,
        /// Number of complete cycles seen.
        cycles: usize,
        /// Period of the last complete cycle (NaN if none).
        last_period: f64,
        /// Peak-to-peak (`max - min`) of the observable over the last complete cycle (NaN if
        /// none), in `unit`.
        last_peak_to_peak: f64,
        /// What the observable is ([`crate::SteadyOptions::observable`]).
        observable: String,
        /// Its unit ([`crate::SteadyOptions::unit`]).
        unit: String,
    },
}
