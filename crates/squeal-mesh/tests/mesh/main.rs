//! The integration tests of squeal-mesh in one test binary: each file is a module, so
//! the release build compiles and links them once, not once per file (docs/benchmarks.md,
//! "Test suite and CI time"). One file's tests:
//! `cargo test --release -p squeal-mesh --test mesh FILE::`.

mod formats;
mod inp;
mod messages;
mod msh;
mod solid_readers;
