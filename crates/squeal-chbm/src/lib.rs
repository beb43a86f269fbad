//! The Constrained Harmonic Balance Method (CHBM) of Coudeyras, Sinou & Nacivet (2009),
//! section 4, for the reduced brake of [`squeal_brake`].
//!
//! CHBM itself is a method of [`squeal_hbm`] ([`squeal_hbm::solve_chbm`]: any linear part, any
//! nonlinear force, the constraint `f2 = Re λ`); the brake's condensed linear part, contact
//! force and eigenvalue tracking are in [`squeal_brake::harmonic`]. This crate adds:
//!
//! - [`system`]: the researcher's front door: a friction system from `M`, `C`, `K` and its
//!   contact pairs, its Hopf point, a limit cycle, the branch with Floquet multipliers.
//! - [`solve`](mod@solve): the start from the unstable mode (eq 48), the harmonic ladder and restarts,
//!   recovery of all dofs (eq 35) and diagnostics.
//! - [`timeint`]: the reference of issue #6, BDF time integration of the full brake from the
//!   perturbed equilibrium to the steady limit cycle.
//! - [`start`]: the equilibrium and unstable mode at a friction level, where both start.
//! - [`compare`]: CHBM against the time integration (Tables 1–2, Figures 4–5 of the paper) and
//!   the robustness grid over friction and initial amplitude.
//! - [`cycle`]: Fourier coefficients of a cycle of every dof, phase alignment, the relative
//!   errors, the power per harmonic (eqs 49–50) and the energy balance of a cycle.
//! - [`physics`]: the checks a cycle of the model takes for granted: open fractions from the
//!   roots of the continuous penetration, and the sliding margin of the disc's surface speed
//!   over the pads' tangential vibration.
//! - [`torus`]: quasi-periodic squeal past a Neimark–Sacker point: the torus branch by the
//!   quasi-periodic harmonic balance of [`squeal_hbm::torus`] in the brake's contact
//!   coordinates.
//! - [`nlmode`]: complex nonlinear modes by the extended periodic motion concept (Krack 2015):
//!   frequency, modal damping and shape of the squeal mode against its amplitude at one μ; the
//!   limit cycles are the roots of the damping.
//! - [`multi`]: several unstable modes at one μ (the generalized CHBM of Coudeyras, Nacivet &
//!   Sinou 2009): one constraint per unstable eigenvalue, each mode's cycle and which one
//!   attracts, and the reference time integration from all of them with its spectrum.
//! - [`stick_branch`]: where a cycle's sliding margin falls below 1, the branch continued with
//!   contact elements that stick (regularized Coulomb) and the cycles recomputed;
//!   [`stick_check`]: such a cycle against BDF time integration of the same law.

#![warn(missing_docs)]
// Index loops over dofs and harmonics read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

pub mod alone;
pub mod bifurcation;
pub mod branch;
pub mod compare;
pub mod cycle;
pub mod floquet;
pub mod multi;
pub mod nlmode;
pub mod physics;
pub mod shooting;
pub mod solve;
pub mod start;
pub mod stick_branch;
pub mod stick_check;
pub mod stick_dlft;
pub mod stick_dlft_starts;
pub mod stick_dlft_walk;
pub mod stick_floquet;
pub mod stick_orbit;
pub mod system;
pub mod timeint;
pub mod torus;
pub mod torus_stability;

pub use solve::{
    ChbmError, ChbmOptions, ChbmSolution, ChbmStart, Guess, Outcome, RESTART_AMPLITUDES,
    check_jacobian, solve, solve_from_guess, solve_with_restarts,
};
pub use system::{Contact, FrictionSystem, Settings, SystemError};
