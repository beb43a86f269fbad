//! The integration tests of squeal-brake in one test binary: each file is a module, so
//! the release build compiles and links them once, not once per file (docs/benchmarks.md,
//! "Test suite and CI time"). One file's tests:
//! `cargo test --release -p squeal-brake --test brake FILE::`.

mod dampers;
mod friction_law;
mod resweep;
mod threads;
mod two_dof;
mod vibration_only;
