//! The integration tests of squeal-fe in one test binary: each file is a module, so
//! the release build compiles and links them once, not once per file (docs/benchmarks.md,
//! "Test suite and CI time"). One file's tests:
//! `cargo test --release -p squeal-fe --test fe FILE::`.

mod common;

mod assembly;
mod bundled;
mod cantilever;
mod curved;
mod dofmap;
mod element;
mod export;
mod fv52;
mod mass;
mod material;
mod patch;
mod quadrature;
mod rigid;
mod solid;
