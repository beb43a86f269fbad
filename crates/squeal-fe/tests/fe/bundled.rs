//! The bundled coarse brake meshes (meshes/*.inp, read with squeal-mesh): masses per element
//! set against the closed-form volumes of meshes/README.md, materials from the sections, and
//! rigid motions of the curved, unstructured meshes.

use super::common;
use common::{frobenius, matvec, norm};
use squeal_fe::{DofMap, MaterialTable, Quadrature, assemble, mesh_volume, total_mass};
use squeal_mesh::Mesh;
use std::f64::consts::PI;

fn read(name: &str) -> Mesh {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../meshes")
        .join(name);
    squeal_mesh::read(&path).unwrap().mesh
}

/// The mesh restricted to one element set (same nodes).
fn subset(mesh: &Mesh, set: &str) -> Mesh {
    let mut m = mesh.clone();
    let keep = mesh.element_set(set).unwrap();
    m.blocks.tet10 = keep
        .iter()
        .map(|&e| mesh.blocks.tet10[e as usize])
        .collect();
    m.element_ids = keep.iter().map(|&e| mesh.element_ids[e as usize]).collect();
    m.element_sets.clear();
    m.sections.clear();
    m
}

#[test]
fn bundled_masses_match_the_closed_form_volumes() {
    // README: disc = π[(0.140² - 0.080²) 0.020 + (0.086² - 0.080²) 0.029 + (0.086² - 0.033²) 0.006].
    let disc_volume = PI
        * ((0.140f64.powi(2) - 0.080f64.powi(2)) * 0.020
            + (0.086f64.powi(2) - 0.080f64.powi(2)) * 0.029
            + (0.086f64.powi(2) - 0.033f64.powi(2)) * 0.006);
    // Pad: 50° sectors of r = 85..135 mm, lining 10 mm and backplate 5 mm thick.
    let sector = 50.0 / 360.0 * PI * (0.135f64.powi(2) - 0.085f64.powi(2));
    let rule = Quadrature::fourteen_point();
    // Midside nodes on the circles make the volume exact to the README's 9e-6 (disc) and
    // 1.3e-7 (pad) at the coarse level; 2e-5 leaves margin.
    let disc = read("disc_coarse.inp");
    let materials = MaterialTable::from_mesh(&disc, &[]).unwrap();
    let m = total_mass(&disc, &materials, &rule).unwrap();
    eprintln!(
        "disc_coarse mass {m:.6} kg, relative error {:.1e}",
        m / (7200.0 * disc_volume) - 1.0
    );
    assert!(
        (m / (7200.0 * disc_volume) - 1.0).abs() < 2e-5,
        "disc mass {m}"
    );
    let pad = read("pad_coarse.inp");
    for (set, rho, thickness) in [("LINING", 2500.0, 0.010), ("BACKPLATE", 7850.0, 0.005)] {
        let part = subset(&pad, set);
        let v = mesh_volume(&part, &rule).unwrap();
        eprintln!(
            "pad_coarse {set} volume {v:.7e} m³, relative error {:.1e}",
            v / (sector * thickness) - 1.0
        );
        assert!(
            (v / (sector * thickness) - 1.0).abs() < 2e-5,
            "{set} volume {v}"
        );
        let materials = MaterialTable::from_mesh(&pad, &[]).unwrap();
        let e = pad.element_set(set).unwrap()[0] as usize;
        assert_eq!(materials.of_element(e).unwrap().material.density(), rho);
    }
    // The whole pad's assembled M gives the same mass as the sum of the parts.
    let materials = MaterialTable::from_mesh(&pad, &[]).unwrap();
    let dofs = DofMap::new(&pad, &[]).unwrap();
    let sys = assemble(&pad, &materials, &dofs).unwrap();
    let ux = dofs.restrict(&vec![[1.0, 0.0, 0.0]; pad.num_nodes()]);
    let m_pad = common::dot(&ux, &matvec(&sys.m, &ux));
    let expect = sector * (2500.0 * 0.010 + 7850.0 * 0.005);
    assert!(
        (m_pad / expect - 1.0).abs() < 2e-5,
        "pad mass {m_pad} vs {expect}"
    );
}

#[test]
fn bundled_disc_has_six_rigid_motions() {
    let disc = read("disc_coarse.inp");
    let materials = MaterialTable::from_mesh(&disc, &[]).unwrap();
    let dofs = DofMap::new(&disc, &[]).unwrap();
    let sys = assemble(&disc, &materials, &dofs).unwrap();
    let knorm = frobenius(&sys.k);
    // A rotation about the disc's axis and a translation: curved, unstructured elements
    // still reproduce them exactly, up to round-off.
    let spin: Vec<[f64; 3]> = disc.nodes.iter().map(|x| [-x[1], x[0], 0.0]).collect();
    let shift: Vec<[f64; 3]> = disc.nodes.iter().map(|_| [0.3, -0.2, 1.0]).collect();
    for field in [spin, shift] {
        let u = dofs.restrict(&field);
        let ratio = norm(&matvec(&sys.k, &u)) / (knorm * norm(&u));
        eprintln!("disc_coarse rigid motion: |K u| / (|K| |u|) = {ratio:.1e}");
        assert!(ratio < 1e-14, "|K u| / (|K| |u|) = {ratio:e}");
    }
}
