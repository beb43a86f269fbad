//! Craig–Bampton reduction (eqs 1–7 of Coudeyras, Sinou & Nacivet 2009) and reduced-model files.

// Index loops over the three directions read like the formulas they implement.
#![allow(clippy::needless_range_loop)]
#![warn(missing_docs)]

pub mod brake;
pub mod check;
pub mod coupling;
pub mod craig_bampton;
pub mod dampers;
pub mod error;
pub mod export;
pub mod held;
pub mod interface;
pub mod interface_modes;
pub mod part_tie;
pub mod rom;
pub mod springs;
pub mod summary;
pub mod tie;
pub mod unreduced;

pub use error::ReduceError;
