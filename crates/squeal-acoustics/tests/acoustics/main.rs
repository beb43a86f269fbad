//! The integration tests of squeal-acoustics in one test binary: each file is a module, so
//! the release build compiles and links them once, not once per file (docs/benchmarks.md,
//! "Test suite and CI time"). One file's tests:
//! `cargo test --release -p squeal-acoustics --test acoustics FILE::`.

mod common;

mod api;
mod closed_forms;
