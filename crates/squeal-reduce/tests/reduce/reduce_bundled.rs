//! Craig–Bampton reduction of the bundled coarse parts.

use squeal_fe::{MaterialTable, Restraint};
use squeal_reduce::craig_bampton::{PartSpec, ReduceOptions, reduce_part};
use squeal_reduce::rom::{InterfaceKind, MeshInfo, PartRole};
use std::path::PathBuf;

fn spec(name: &str, interface: InterfaceKind) -> (squeal_mesh::Mesh, PartSpec) {
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
    let info = MeshInfo {
        path: file,
        sha256: String::new(),
        nodes: mesh.num_nodes(),
        elements: mesh.num_elements(),
    };
    let role = if name == "disc" {
        PartRole::Disc
    } else {
        PartRole::Pad
    };
    let spec = PartSpec {
        restraints,
        interface,
        contact_set: "CONTACT".into(),
        contact_face_set: "CONTACT_FACE".into(),
        piston_set: piston,
        ..PartSpec::new(name, role, info, 50)
    };
    (mesh, spec)
}

#[test]
fn pad_reduces_to_81_dofs_with_its_normal_rigid_motion() {
    for interface in [InterfaceKind::Patch, InterfaceKind::Node] {
        let (mesh, spec) = spec("pad", interface);
        let materials = MaterialTable::from_mesh(&mesh, &[]).unwrap();
        let (part, report) = reduce_part(
            &mesh,
            &materials,
            &spec,
            &ReduceOptions::default(),
            &mut |_| {},
        )
        .unwrap();
        assert_eq!(part.size(), 27 + 4 + 50);
        eprintln!(
            "{interface:?}: {:?} coupling {:e} dev {:e}",
            part.info.fixed_interface_hz[..5].to_vec(),
            report.coupling,
            report.modal_mass_deviation
        );
        // The pad is held in plane only: translating every boundary coordinate by 1 along z
        // (modal amplitudes 0) is a rigid motion, K̂ r = 0 to round-off of ||K̂||.
        let n = part.size();
        let r: Vec<f64> = (0..n)
            .map(|i| {
                if i < 31 && (i >= 27 || i % 3 == 2) {
                    1.0
                } else {
                    0.0
                }
            })
            .collect();
        let kmax = (0..n).map(|i| part.k[(i, i)]).fold(0.0, f64::max);
        for i in 0..n {
            let kr: f64 = (0..n).map(|j| part.k[(i, j)] * r[j]).sum();
            assert!(kr.abs() < 1e-9 * kmax, "row {i}: {kr:e} vs {kmax:e}");
        }
        assert!(
            report.coupling < 1e-10,
            "K_CN coupling {:e}",
            report.coupling
        );
    }
}

#[test]
fn disc_reduces_to_77_dofs() {
    let (mesh, spec) = spec("disc", InterfaceKind::Patch);
    let materials = MaterialTable::from_mesh(&mesh, &[]).unwrap();
    let (part, report) = reduce_part(
        &mesh,
        &materials,
        &spec,
        &ReduceOptions::default(),
        &mut |_| {},
    )
    .unwrap();
    assert_eq!(part.size(), 27 + 50);
    eprintln!(
        "disc: {:?} ... {:?}",
        &part.info.fixed_interface_hz[..6],
        part.info.fixed_interface_hz.last()
    );
    eprintln!("timings {:?}", report.timings);
    assert!(
        report.coupling < 1e-10,
        "K_CN coupling {:e}",
        report.coupling
    );
}

#[test]
fn a_sturm_check_after_the_iteration_with_the_factor_freed_gives_the_same_part() {
    // The memory-saving order (Lanczos without the check, the Cholesky factor's values freed,
    // then the LBLᵀ count on its analysis) against the default (the count beside the
    // iteration): the reduced matrices are the same bits, only the check's bound may differ.
    for interface in [InterfaceKind::Patch, InterfaceKind::Node] {
        let (mesh, spec) = spec("pad", interface);
        let materials = MaterialTable::from_mesh(&mesh, &[]).unwrap();
        let run = |sturm_beside: bool| {
            let mut opts = ReduceOptions::default();
            opts.eig.sturm_beside = sturm_beside;
            reduce_part(&mesh, &materials, &spec, &opts, &mut |_| {}).unwrap()
        };
        let (beside, report_beside) = run(true);
        let (after, report_after) = run(false);
        assert!(report_beside.eig.sturm_beside && !report_after.eig.sturm_beside);
        assert_eq!(beside.k, after.k);
        assert_eq!(beside.m, after.m);
        let (bound, count) = report_after.sturm.unwrap();
        // The check covered the modes kept.
        assert!(count >= 50 && bound > (2.0 * std::f64::consts::PI * 1e3).powi(2));
        assert_eq!(report_after.eig.sturm, report_after.sturm);
    }
}
