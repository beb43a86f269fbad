//! The integration tests of squeal-hbm in one test binary: each file is a module, so
//! the release build compiles and links them once, not once per file (docs/benchmarks.md,
//! "Test suite and CI time"). One file's tests:
//! `cargo test --release -p squeal-hbm --test hbm FILE::`.

mod common;

mod aft;
mod chbm;
mod continuation;
mod duffing;
mod lm;
mod stick_slip_belt;
mod torus;
mod torus_lyapunov;
mod van_der_pol;
