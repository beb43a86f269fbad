//! The coarse bundled brake for the sweep tests and benchmarks: `meshes/disc_coarse.inp` and
//! `meshes/pad_coarse.inp` reduced by Craig–Bampton (50 fixed-interface modes each, patch
//! interface: 158 dofs), with the bundled scene's contact (`meshes/brake.toml`: the pad
//! compression curve's `k_l = 1.25e10 Pa/m`, `k_nl = 2.0e19 Pa/m³`), 3 kN of piston force and
//! 1 % modal damping. Built once per test binary (a few seconds).

#![allow(dead_code)]

use squeal_brake::Brake;
use squeal_brake::assemble::{BrakeParams, Stiffness, assemble};
use squeal_brake::equilibrium::NewtonOptions;
use squeal_brake::modal::Damping;
use squeal_brake::spectrum::Reference;
use squeal_brake::sweep::{Band, SweepOptions, reference};
use squeal_fe::{MaterialTable, Restraint};
use squeal_reduce::craig_bampton::{PartSpec, ReduceOptions, reduce_part};
use squeal_reduce::interface::Axis;
use squeal_reduce::rom::{InterfaceKind, MeshInfo, ReducedModel};
use std::path::PathBuf;
use std::sync::OnceLock;

/// The brake, its frictionless reference and the scene's band.
pub struct Coarse {
    pub brake: Brake,
    pub reference: Reference,
    pub band: Band,
}

/// Reduces one coarse part as `src/setup.rs` does for the bundled scene.
fn reduce(name: &str) -> squeal_reduce::rom::ReducedPart {
    let file = format!("{name}_coarse.inp");
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../meshes")
        .join(&file);
    let mesh = squeal_mesh::read(&path).unwrap().mesh;
    let (restraints, piston) = if name == "disc" {
        (vec![Restraint::clamp("CLAMP")], None)
    } else {
        (
            vec![Restraint::set("ABUTMENT", [true, true, false])],
            Some("PISTON".to_string()),
        )
    };
    let spec = PartSpec {
        name: name.into(),
        mesh: MeshInfo {
            path: file,
            sha256: String::new(),
            nodes: mesh.num_nodes(),
            elements: mesh.num_elements(),
        },
        restraints,
        interface: InterfaceKind::Patch,
        contact_set: "CONTACT".into(),
        contact_face_set: "CONTACT_FACE".into(),
        grid: [3, 3],
        axis: Axis::default(),
        piston_set: piston,
        normal_direction: 2,
        modes: 50,
    };
    let materials = MaterialTable::from_mesh(&mesh, &[]).unwrap();
    let opts = ReduceOptions {
        keep_basis: false,
        ..ReduceOptions::default()
    };
    reduce_part(&mesh, &materials, &spec, &opts, &mut |_| {})
        .unwrap()
        .0
}

fn build() -> Coarse {
    let rom = ReducedModel {
        tool_version: "sweep tests".into(),
        parts: vec![reduce("disc"), reduce("pad")],
    };
    let params = BrakeParams {
        normal: [0.0, 0.0, 1.0],
        sliding: [1.0, 0.0, 0.0],
        stiffness: Stiffness::PerArea {
            linear: 1.25e10,
            cubic: 2.0e19,
            point_area: None,
        },
        pairing_tolerance: 1e-3,
        piston_force: 3000.0,
    };
    let (brake, _, _) = assemble(&rom, &params).unwrap();
    let damping = Damping {
        global_ratio: 0.01,
        extra: vec![],
    };
    let reference = reference(&brake, &damping, &NewtonOptions::default()).unwrap();
    let valid_max_hz = rom
        .parts
        .iter()
        .filter_map(|p| p.info.fixed_interface_hz.last().copied())
        .fold(f64::INFINITY, f64::min);
    Coarse {
        brake,
        reference,
        band: Band {
            valid_max_hz,
            user: Some((1000.0, 16000.0)),
        },
    }
}

/// The coarse brake, built on first use.
pub fn coarse() -> &'static Coarse {
    static BRAKE: OnceLock<Coarse> = OnceLock::new();
    BRAKE.get_or_init(build)
}

/// Sweep options of the bundled scene on the coarse brake.
pub fn options(c: &Coarse) -> SweepOptions {
    SweepOptions {
        band: c.band,
        ..SweepOptions::default()
    }
}

/// `count` friction values evenly spaced on `[lo, hi]`.
pub fn mus(lo: f64, hi: f64, count: usize) -> Vec<f64> {
    (0..count)
        .map(|k| lo + (hi - lo) * k as f64 / (count - 1) as f64)
        .collect()
}
