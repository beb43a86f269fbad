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
//! solver of the same scipy lineage, but (1) its Jacobian interface is a
//! Jacobian-vector product closure: a dense Jacobian is rebuilt from `n`
//! products per evaluation, so a user's dense analytic Jacobian must be
//! cached and re-multiplied (`n` mat-vecs of size `n` = O(n^3) per
//! evaluation); (2) it always pulls in nalgebra 0.35 and petgraph; (3) it has
//! no fixed-order/fixed-step mode for convergence tests and no order
//! histogram. The algorithm itself is ~600 lines, so it is written here on
//! faer with the project's error and determinism rules (see the crate's
//! report for the measured comparison on the 316-state benchmark).
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
//! let opts = BdfOptions { rtol: 1e-8, atol: squeal_ode::Atol::Scalar(1e-10), ..Default::default() };
//! let mut bdf = Bdf::new(Decay, 0.0, &[1.0], 2.0, &opts).unwrap();
//! while !bdf.is_finished() { bdf.step().unwrap(); }
//! assert!((bdf.y()[0] - (-2.0f64).exp()).abs() < 1e-6);
//! ```
//!
//! Damping: BDF/NDF formulas of order >= 2 damp an undamped oscillation
//! slightly (numerical dissipation ~ C h^k); the `harmonic` test quantifies
//! the amplitude and phase error per 100 periods against `rtol`.

mod bdf;
mod error;
mod options;
mod solve;
mod steady;

pub use bdf::{Bdf, MAX_DIM, OdeSystem};
pub use error::OdeError;
pub use options::{Atol, BdfOptions, BdfStats, FixedStep, MAX_ORDER};
pub use solve::{Solution, solve};
pub use steady::{
    CycleRecord, Fourier, MAX_HARMONICS, MAX_SAMPLES_PER_CYCLE, OscillationMonitor,
    SteadyOptions, SteadyState, run_to_steady_state,
};
