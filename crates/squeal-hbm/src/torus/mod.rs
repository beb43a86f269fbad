//! Quasi-periodic harmonic balance: solutions on an invariant torus with two base frequencies,
//! both unknown (issue 24, item 1).
//!
//! A periodic solution of an autonomous system loses stability at a Neimark–Sacker point when a
//! pair of Floquet multipliers leaves the unit circle; past it (supercritical case) the motion
//! is quasi-periodic, `x(t) = X(ω1 t, ω2 t)` with `X` on a two-torus. The method is eq. (26)
//! with the one-angle Fourier series of eq. (23) replaced by a two-dimensional one:
//!
//! * [`TorusBasis`]: the truncated basis `k = (k1, k2)` by total order or by a box, in the
//!   block layout of eq. (25), and the series at a point (the analogue of eq. 23).
//! * [`TorusAft`]: eq. (29) on a grid of the two angles with two-dimensional FFTs
//!   (`rustfft`), and its exact Jacobians in `U`, `ω1`, `ω2`.
//! * [`TorusLinear`]: the linear part element by element at `w = k·ω`, as a dynamic stiffness
//!   ([`MckTorus`], eqs. 27–28) or in receptance form (a force that sees few coordinates).
//! * [`TorusBalance`], [`TorusPhase`], [`TorusFamily`]: the residual and Jacobian, the two
//!   phase conditions (one per angle), and the family in a parameter that
//!   [`crate::continuation`] follows (pseudo-arclength, the same corrector as the periodic
//!   branches).
//! * [`start_from_cycle`]: the start at a Neimark–Sacker point from the cycle and the critical
//!   Floquet vector (computed here from the same equations, by inverse iteration on the
//!   modulation's block of the Jacobian: Hill's matrix in real form).
//! * [`lyapunov`]: the torus' stability from its Lyapunov exponents along the known flow.
//! * [`transverse`]: the same, the torus' own (tangent) directions known, only the transverse
//!   exponents integrated, for as long as the verdict needs (what `squeal branch` uses).
//! * [`measure`]: the amplitude envelope and the spectral peaks, measured alike on a torus'
//!   signal and on a time integration.
//!
//! References: Schilder, Vogt, Schreiber & Osinga (2006), Fourier methods for quasi-periodic
//! oscillations, IJNME 67; Guskov, Sinou & Thouverez (2008), Multi-dimensional harmonic balance
//! applied to rotor dynamics, Mech. Res. Commun. 35; Coudeyras, Nacivet & Sinou (2009),
//! Periodic and quasi-periodic solutions for multi-instabilities involved in brake squeal,
//! JSV 328.

// Index loops over dofs, elements and angles read like the formulas they implement.
#![allow(clippy::needless_range_loop)]

mod aft;
mod balance;
mod basis;
mod force;
mod linear;
pub mod lyapunov;
pub mod measure;
mod start;
pub mod transverse;

pub use aft::{TorusAft, default_grid};
pub use balance::{TorusBalance, TorusFamily, TorusPhase, TorusScales};
pub use basis::{TorusBasis, Truncation};
pub use force::{Square, TorusForce};
pub use linear::{LinearBlocks, MckTorus, TorusLinear};
pub use start::{INVERSE_ITERATIONS, TorusStart, start_from_cycle};
