//! The integration tests of squeal-reduce in one test binary: each file is a module, so
//! the release build compiles and links them once, not once per file (docs/benchmarks.md,
//! "Test suite and CI time"). One file's tests:
//! `cargo test --release -p squeal-reduce --test reduce FILE::`.

mod common;

mod brake;
mod dampers;
mod determinism;
mod errors;
mod footprints;
mod held;
mod interface_bundled;
mod kept;
mod nodal;
mod part_ties;
mod parts;
mod reduce_bundled;
mod tie;
mod verification;
