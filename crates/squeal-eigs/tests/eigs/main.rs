//! The integration tests of squeal-eigs in one test binary: each file is a module, so
//! the release build compiles and links them once, not once per file (docs/benchmarks.md,
//! "Test suite and CI time"). One file's tests:
//! `cargo test --release -p squeal-eigs --test eigs FILE::`.

mod common;

mod analytic;
mod arpack;
mod block_and_ordering;
mod constraints;
mod slicing;
mod solves;
