//! Shared fixtures of the integration tests: the bundled coarse meshes, reduced once per test
//! binary.

#![allow(dead_code)]

use squeal_reduce::brake::{BrakeInputs, LoadedPart, load_part, reduce_brake_loaded};
use squeal_reduce::rom::{InterfaceKind, ReducedModel};
use std::path::PathBuf;
use std::sync::OnceLock;

/// Path of a bundled mesh.
pub fn mesh_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../meshes")
        .join(name)
}

/// A bundled coarse part, read and hashed.
pub fn coarse(part: &str) -> LoadedPart {
    load_part(&mesh_path(&format!("{part}_coarse.inp"))).unwrap()
}

/// The bundled setup on the coarse meshes.
pub fn coarse_inputs(interface: InterfaceKind) -> BrakeInputs {
    BrakeInputs {
        interface,
        ..BrakeInputs::bundled(mesh_path("disc_coarse.inp"), mesh_path("pad_coarse.inp"))
    }
}

/// The coarse brake reduced with `inputs`.
pub fn reduce(inputs: &BrakeInputs) -> ReducedModel {
    reduce_brake_loaded(inputs, coarse("disc"), vec![coarse("pad")], &mut |_, _| {})
        .unwrap()
        .0
}

/// The coarse brake, 50 modes, reduced once per test binary for each interface.
pub fn coarse_brake(interface: InterfaceKind) -> &'static ReducedModel {
    static PATCH: OnceLock<ReducedModel> = OnceLock::new();
    static NODE: OnceLock<ReducedModel> = OnceLock::new();
    let cell = match interface {
        InterfaceKind::Patch => &PATCH,
        InterfaceKind::Node => &NODE,
    };
    cell.get_or_init(|| reduce(&coarse_inputs(interface)))
}
