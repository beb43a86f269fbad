//! The nonlinear reduced brake of Coudeyras, Sinou & Nacivet (2009), sections 2.2 and 3.
//!
//! - [`contact`]: contact elements behind one interface; the paper's cubic penalty contact
//!   with Coulomb friction in permanent sliding (eqs 8–10) is the first.
//! - [`model`]: the brake of eq (11), `M x'' + C x' + K x + F_nl(x, x') = F_piston`, its
//!   contact pairs (each with its own normal, sliding direction and element), their forces
//!   and Jacobians (eqs 17–19).
//! - [`damping`]: the modal damping `D` of eq (12), diagonal or full.
//! - [`equilibrium`]: the static equilibrium of eq (14) by Newton's method with a line search,
//!   by continuation in the clamp force so that pairs with initial gaps close under load.
//! - [`modal`]: the undamped, frictionless modal basis and the damping of eqs (12)–(13).
//! - [`spectrum`]: the complex eigenvalues of the linearized brake (eqs 20–22).
//! - [`tracking`]: following modes across a parameter sweep by eigenvector correlation.
//! - [`sweep`]: friction sweeps, the Hopf point `mu0` and its refinement.
//! - [`projected`]: the sweep on the frictionless modes below a converged cut-off.
//! - [`linearized`]: the one linearized brake, a quadratic eigenproblem with a low-rank
//!   coupling (dense when the damping is full).
//! - [`continuation`]: exact continuation of its eigenpairs from one friction value to the next.
//! - [`harmonic`]: the brake for harmonic balance: its contact force, its linear part
//!   condensed on the nonlinear dofs (eqs 30–35), the eigenvalue CHBM's constraint follows.
//! - [`criticality`]: the first Lyapunov coefficient at μ0 (super- or subcritical) and the
//!   small-amplitude asymptote of the branch of limit cycles.
//! - [`hopf`]: the Hopf point by Newton's method on the continued eigenvalue.
//! - [`studies`]: parametric studies (pressure, contact stiffness, pair damping), the
//!   damping-induced destabilization at small friction, and mode-shape measures.
//! - [`vibration_only`]: stiffness acting on the vibration about the equilibrium only (a
//!   hydraulic piston), out of eq (14) and of the harmonic balance's 0th harmonic.

#![warn(missing_docs)]
// Index loops over dofs read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

pub mod analysis;
pub mod assemble;
pub mod connections;
pub mod contact;
pub mod continuation;
pub mod criticality;
pub mod damping;
pub mod dense_par;
pub mod dynamics;
pub mod equilibrium;
pub mod error;
pub mod harmonic;
pub mod hessenberg_rqi;
pub mod hopf;
pub mod interface_reduced;
pub mod interface_system;
mod jacobian;
pub mod linearized;
pub mod modal;
pub mod modal_brake;
pub mod model;
pub mod partial_modes;
pub mod participation;
pub mod projected;
pub mod projected_equilibrium;
pub mod projected_hopf;
pub mod sensitivity;
pub mod spectrum;
pub mod studies;
pub mod sweep;
mod sweep_continued;
pub mod tracking;
pub mod vibration_only;

pub use contact::{ContactLaw, Kinematics, Law, PenaltyCoulomb, Response};
pub use damping::ModalDamping;
pub use error::BrakeError;
pub use model::{Brake, ContactPair, SparseVec};
