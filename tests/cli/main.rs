//! The command-line tests (the `squeal` binary run on the bundled meshes) in one test binary:
//! each file is a module, so the release build compiles and links them once, not once per file
//! (docs/benchmarks.md, "Test suite and CI time"). One file's tests:
//! `cargo test --release --test cli FILE::`.

mod common;

mod caveats;
mod cli_trust;
mod compare_reference;
mod convergence_study;
mod interrupt;
mod microphone;
mod one_cycle;
mod regression;
mod report;
mod restraints;
mod shared_folder;
mod stability_scene;
mod stability_study;
mod study_shards;
mod two_mode_branch;
mod units_cli;
mod ventilated;
