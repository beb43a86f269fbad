//! The integration tests of squeal-pipeline in one test binary: each file is a module, so
//! the release build compiles and links them once, not once per file (docs/benchmarks.md,
//! "Test suite and CI time"). One file's tests:
//! `cargo test --release -p squeal-pipeline --test pipeline FILE::`.

mod common;

mod assembly;
mod branch_torus;
mod caliper;
mod contact_law;
mod corner;
mod full_corner;
mod full_model;
mod gaps;
mod hex_pad;
mod interface_modes;
mod interface_parts;
mod part_ties_corner;
mod partial_system;
mod projected_refinement;
mod rotation;
mod scene_sets;
mod sensitivities;
mod sound;
mod stick_dlft;
mod stick_walk;
mod sweep_methods;
mod torus;
mod two_mode_brake;
mod two_pad;
