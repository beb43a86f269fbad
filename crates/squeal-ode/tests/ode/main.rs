//! The integration tests of squeal-ode in one test binary: each file is a module, so
//! the release build compiles and links them once, not once per file (docs/benchmarks.md,
//! "Test suite and CI time"). One file's tests:
//! `cargo test --release -p squeal-ode --test ode FILE::`.

mod common;

mod errors;
mod linear;
mod shooting;
mod stiff;
