//! The integration tests of squeal-chbm in one test binary: each file is a module, so
//! the release build compiles and links them once, not once per file (docs/benchmarks.md,
//! "Test suite and CI time"). One file's tests:
//! `cargo test --release -p squeal-chbm --test chbm FILE::`.

mod common;

mod branch;
mod dlft_floquet;
mod dlft_two_dof;
mod multi;
mod nlmode;
mod stick_slip_belt;
mod two_dof;
