//! Harmonic balance core of squeal: the generic machinery under the Constrained Harmonic
//! Balance Method (CHBM) of Coudeyras, Sinou & Nacivet, JSV 319 (2009), section 4.1.
//!
//! * [`HarmonicLayout`]: the multi-harmonic vector `U~ = [U0c, U1c, U1s, ..., UHc, UHs]` of
//!   eq. (25) and point evaluation of the truncated series, eq. (23).
//! * [`Aft`]: the alternating frequency-time scheme, eq. (29), on `rustfft`, with the
//!   analytic Jacobians `dF~/dU~`, `dF~/domega` through the same transforms; sample-count
//!   rule and aliasing in the [`aft`] module docs.
//! * [`NonlinearForce`]: the pointwise force `f_nl(x, xdot)` with sparse local Jacobians
//!   (one FFT per pattern entry), [`FnForce`] for closures.
//! * [`DynamicStiffness`] / [`MckStiffness`]: the block-diagonal `Lambda(omega)` of eqs.
//!   (27)-(28); a condensed `Lambda_eq` (eq. 32) plugs in through the same trait.
//! * [`HarmonicBalance`]: the residual of eq. (26) and its Jacobian in `(U~, omega)`.
//! * [`lm`]: Levenberg-Marquardt with Moré scaling, typed stop reasons and the iteration
//!   history.
//! * [`solve_autonomous`] (unknown `omega`, [`PhaseCondition`]) and [`solve_forced`].
//! * [`AutonomousProblem`] with a [`CycleConstraint`]: the Constrained Harmonic Balance
//!   Method (section 4) is one, [`ReLambda`] (`f2 = Re λ`, eq. 47) on the describing-function
//!   linearization of the cycle ([`DescribingFunction`]), for any linear part that can follow
//!   its eigenvalues ([`LinearizedEigen`]; [`DenseEigen`] for dense `M`, `C`, `K`):
//!   [`solve_chbm`]. `examples/` has two short programs.
//! * [`continuation`]: branches of periodic solutions in a parameter (pseudo-arclength).
//! * [`torus`]: quasi-periodic harmonic balance on an invariant torus (two base frequencies,
//!   2-D AFT, two phase conditions), started at a Neimark–Sacker point.
//! * [`stick_slip`]: exact stick–slip friction contacts by the dynamic Lagrangian
//!   frequency–time method (Nacivet et al. 2003), [`solve_stick_slip`].
//! * [`Periodic`]: a periodic motion as Fourier coefficients (eq. 23), and [`FourierSums`],
//!   its coefficients from equally spaced samples.
//!
//! A limit cycle of van der Pol's oscillator `x'' - (1 - x^2) x' + x = 0`:
//! ```
//! use faer::Mat;
//! use squeal_hbm::*;
//! let layout = HarmonicLayout::new(1, 5)?;
//! let one = Mat::from_fn(1, 1, |_, _| 1.0);
//! let minus_one = Mat::from_fn(1, 1, |_, _| -1.0);
//! let linear = MckStiffness::new(one.as_ref(), minus_one.as_ref(), one.as_ref())?;
//! // f_nl = x^2 x', so that M x'' + C x' + K x + f_nl = 0 with C = -1.
//! let force = FnForce::new(1, vec![(0, 0)], true, |x: &[f64], v: &[f64], f: &mut [f64], jac: Option<LocalJacobian<'_>>| {
//!     f[0] = x[0] * x[0] * v[0];
//!     if let Some(j) = jac {
//!         j.dfdx[0] = 2.0 * x[0] * v[0];
//!         j.dfdxdot[0] = x[0] * x[0];
//!     }
//! });
//! let mut hb = HarmonicBalance::new(layout, linear, force, vec![0.0; layout.len()], None)?;
//! let mut u0 = vec![0.0; layout.len()];
//! u0[layout.index(1, Part::Cos, 0).unwrap()] = 2.0;
//! let phase = PhaseCondition::FirstSineZero { dof: 0 };
//! let sol = solve_autonomous(&mut hb, phase, &u0, 1.0, &LmOptions::default())?;
//! assert!((sol.period() - 6.66328686).abs() < 1e-3);
//! # Ok::<(), HbmError>(())
//! ```

pub mod aft;
mod chbm;
pub mod continuation;
mod error;
mod force;
mod hb;
mod layout;
mod linear;
pub mod lm;
mod periodic;
pub mod stick_slip;
pub mod torus;

pub use aft::{Aft, TimeSamples, default_samples, min_samples_exact};
pub use chbm::{
    ChbmResult, DenseEigen, DescribingFunction, EigenTrack, LinearUpdate, LinearizedEigen,
    ReLambda, initial_guess, reference_jacobian, solve_chbm,
};
pub use error::HbmError;
pub use force::{FnForce, LocalJacobian, NonlinearForce};
pub use hb::{
    AutonomousProblem, CycleConstraint, CycleEval, Evaluation, ForceDerivatives, ForcedProblem,
    HarmonicBalance, HbSolution, PhaseCondition, RowNorms, RowScales, Unconstrained,
    solve_autonomous, solve_forced,
};
pub use layout::{HarmonicLayout, MAX_COEFFICIENTS, Part};
pub use linear::{DynamicStiffness, MckStiffness};
pub use lm::{LeastSquaresProblem, LmError, LmIteration, LmOptions, LmReport, LmStop};
pub use periodic::{FourierSums, Periodic};
pub use stick_slip::{
    ContactState, FrictionContact, NormalLoad, StickSlipBalance, StickSlipProblem,
    default_stick_slip_samples, solve_stick_slip,
};
