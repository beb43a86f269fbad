//! The Constrained Harmonic Balance Method (CHBM) of Coudeyras, Sinou & Nacivet (2009),
//! section 4, for the reduced brake of [`squeal_brake`].
//!
//! - [`condensed`]: harmonic balance condensed on the nonlinear dofs, eqs (30)–(35).
//! - [`contact`]: the contact and friction forces of eqs (8)–(10) for the AFT scheme (eq 29).
//! - [`constraint`]: the equivalent linearization (eq 45) and the eigenvalue of eqs (43)–(44)
//!   whose real part is the constraint `f2` of eq (47), with its derivative.
//! - [`solve`]: unknowns, initial guess from the unstable mode (eq 48), the Levenberg–Marquardt
//!   solve of eqs (46)–(47), recovery of all dofs and diagnostics.
//! - [`timeint`]: the reference of issue #6, BDF time integration of the full brake from the
//!   perturbed equilibrium to the steady limit cycle.
//! - [`start`]: the equilibrium and unstable mode at a friction level, where both start.
//! - [`compare`]: CHBM against the time integration (Tables 1–2, Figures 4–5 of the paper) and
//!   the robustness grid over friction and initial amplitude.
//! - [`cycle`]: Fourier coefficients of a cycle of every dof, phase alignment, the relative
//!   errors, the power per harmonic (eqs 49–50) and the energy balance of a cycle.

// Index loops over dofs and harmonics read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

pub mod compare;
pub mod condensed;
pub mod constraint;
pub mod contact;
pub mod cycle;
pub mod solve;
pub mod start;
pub mod timeint;

pub use solve::{ChbmError, ChbmOptions, ChbmSolution, ChbmStart, Outcome, check_jacobian, solve};
