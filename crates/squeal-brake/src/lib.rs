//! The nonlinear reduced brake of Coudeyras, Sinou & Nacivet (2009), sections 2.2 and 3.
//!
//! - [`model`]: the brake of eq (11), `M x'' + C x' + K x + F_nl(x) = F_piston`, with the
//!   cubic penalty contact of eq (8) and Coulomb friction of eq (9) between paired contact
//!   points, and their Jacobian (eqs 17–19).
//! - [`equilibrium`]: the static equilibrium of eq (14) by Newton's method with a line search.
//! - [`modal`]: the undamped, frictionless modal basis and the damping of eqs (12)–(13).
//! - [`spectrum`]: the complex eigenvalues of the linearized brake (eqs 20–22).
//! - [`tracking`]: following modes across a parameter sweep by eigenvector correlation.
//! - [`sweep`]: friction sweeps, the Hopf point `mu0` and its refinement.
//! - [`lowrank`]: the linearized brake as a diagonal-plus-rank-`P` quadratic eigenproblem.
//! - [`continuation`]: exact continuation of its eigenpairs from one friction value to the next.
//! - [`hopf`]: the Hopf point by Newton's method on the continued eigenvalue.
//! - [`studies`]: parametric studies (pressure, contact stiffness, pair damping), the
//!   damping-induced destabilization at small friction, and mode-shape measures.

// Index loops over dofs read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

pub mod analysis;
pub mod assemble;
pub mod continuation;
pub mod dynamics;
pub mod equilibrium;
pub mod error;
pub mod hopf;
pub mod lowrank;
pub mod modal;
pub mod modal_brake;
pub mod model;
pub mod spectrum;
pub mod studies;
pub mod sweep;
pub mod tracking;

pub use error::BrakeError;
pub use model::{Brake, ContactPair, SparseVec};
