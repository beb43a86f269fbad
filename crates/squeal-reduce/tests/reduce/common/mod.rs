//! Shared fixtures of the integration tests: the bundled coarse meshes, reduced once per test
//! binary.

#![allow(dead_code)]

pub mod blocks;

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
    static NODAL: OnceLock<ReducedModel> = OnceLock::new();
    let cell = match interface {
        InterfaceKind::Patch => &PATCH,
        InterfaceKind::Node => &NODE,
        InterfaceKind::Nodal => &NODAL,
    };
    cell.get_or_init(|| reduce(&coarse_inputs(interface)))
}

/// Adds the two 40 mm piston footprints on the coarse pad's back face (z = 35 mm, centres at
/// r = 110 mm, 77.5 and 102.5 degrees, the bundled pistons') to `mesh` as node sets `FOOT_1`,
/// `FOOT_2` (faces facing +z whose corner centroid is inside the circle).
pub fn add_footprints(mesh: &mut squeal_mesh::Mesh) {
    use squeal_mesh::select::{Circle, Rule, boundary_faces};
    let boundary = boundary_faces(mesh);
    for (k, deg) in [77.5f64, 102.5].into_iter().enumerate() {
        let t = deg.to_radians();
        let rule = Rule {
            facing: Some(([0.0, 0.0, 1.0], 1.0)),
            circle: Some(Circle {
                centre: [0.11 * t.cos(), 0.11 * t.sin(), 0.035],
                diameter: 0.04,
            }),
            tolerance: 1e-7,
            ..Rule::default()
        };
        let s = rule.apply(mesh, &boundary).unwrap();
        assert!(s.nodes.len() > 1);
        mesh.node_sets.insert(format!("FOOT_{}", k + 1), s.nodes);
    }
}
