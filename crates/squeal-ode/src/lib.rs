//! # squeal-ode: stiff time integration to a steady limit cycle
//!
//! A variable-order (1..=5), variable-step BDF/NDF integrator with error
//! control and dense output, modelled on MATLAB's ode15s (Shampine & Reichelt,
//! "The MATLAB ODE suite", SIAM J. Sci. Comput. 18 (1997) 1-22) as
//! implemented in scipy's `integrate.BDF`, plus a steady-state detector for
//! self-excited oscillators. Issue #6 uses it to check the Constrained
//! Harmonic Balance Method (Coudeyras, Sinou & Nacivet, JSV 2009, Sec. 5,
//! where ode15s is the "variable order solver") against a time integration
//! of the full nonlinear brake (316 stiff first-order states).
//!
//! ## Why not diffsol
//! diffsol 0.18 (well kept, MIT, builds here with faer 0.24) has an NDF/BDF
//! solver of the same scipy lineage. It was evaluated on the 316-state
//! brake-like benchmark (`benches/brake_like.rs`, 50 cycles, same system and
//! tolerances, machine shared with other builds): diffsol 41 s at rtol 1e-6
//! (360 steps/cycle, 4136 linear-solver setups) against 4.3 s here with the
//! same maximum order 5 (375 steps/cycle) and 0.5 s here with `max_order = 2`
//! (100 steps/cycle). Reasons to write it here: (1) diffsol's Jacobian
//! interface is a Jacobian-vector product closure and it rebuilds the dense
//! Jacobian from `n` products at every setup, so a user's dense analytic
//! Jacobian has to be re-multiplied column by column; (2) its maximum order
//! is fixed at 5, while lightly damped stiff oscillators need order 2 (see
//! below); (3) no fixed-order/fixed-step mode for convergence tests, no
//! order histogram; (4) it always pulls in nalgebra 0.35 and petgraph.
//!
//! ## Lightly damped stiff oscillators: use `max_order = 2`
//! BDF/NDF of order 3..5 are not A-stable: lightly damped high-frequency
//! modes (1% damping, 1-150 kHz in the benchmark) fall into their unstable
//! regions and the error control fights the instability with rejections
//! (order 5 at rtol 1e-6 over 1000 cycles: 60155 rejected steps, 31810 LU
//! factorizations). Order 2 is A-stable and runs the same problem with
//! 3084 rejections and 6040 LUs, 3x faster. Order 2 costs accuracy per step:
//! at rtol 1e-6 the steady limit-cycle frequency came out 3.8e-5 low and the
//! amplitude 1.9e-5 low against an rtol 1e-8 order-5 run (numerical
//! dispersion and dissipation of BDF2); the run reached the steady state
//! after 351 cycles in 12 s.
//!
//! ## Use
//! ```
//! use squeal_ode::{Bdf, BdfOptions, OdeSystem};
//! use faer::MatMut;
//! struct Decay;
//! impl OdeSystem for Decay {
//!     fn dim(&self) -> usize { 1 }
//!     fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) { dy[0] = -y[0]; }
//!     fn jacobian(&self, _t: f64, _y: &[f64], mut jac: MatMut<'_, f64>) { jac[(0, 0)] = -1.0; }
//! }
//! let mut opts = BdfOptions::default();
//! opts.rtol = 1e-8;
//! opts.atol = squeal_ode::Atol::Scalar(1e-10);
//! let mut bdf = Bdf::new(Decay, 0.0, &[1.0], 2.0, &opts).unwrap();
//! while !bdf.is_finished() { bdf.step().unwrap(); }
//! assert!((bdf.y()[0] - (-2.0f64).exp()).abs() < 1e-6);
//! ```
//!
//! Damping: BDF/NDF formulas of order >= 2 damp an undamped oscillation
//! slightly (numerical dissipation ~ C h^k); the `harmonic` test quantifies
//! the amplitude and phase error per 100 periods against `rtol`.

// Index loops mirror the formulas (D_j, R_ij, ...) more plainly than iterator chains.
#![allow(clippy::needless_range_loop)]

mod bdf;
mod error;
mod options;
pub mod shooting;
mod solve;
mod steady;

pub use bdf::{Bdf, MAX_DIM, OdeSystem};
pub use error::OdeError;
pub use options::{Atol, BdfOptions, BdfStats, FixedStep, MAX_ORDER};
pub use shooting::{
    Flow, PeriodicOrbit, ShootingError, ShootingOptions, flow, shoot, tangent,
    variational_monodromy,
};
pub use solve::{Solution, solve};
pub use steady::{
    CycleRecord, MAX_HARMONICS, MAX_SAMPLES_PER_CYCLE, OscillationMonitor, SteadyOptions,
    SteadyState, run_to_steady_state,
};
