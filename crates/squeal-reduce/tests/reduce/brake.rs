//! The brake-level entry point on the bundled coarse meshes: the 158-dof layout, the file
//! round trip, freshness of an existing file, and the automatic mode choice.

use super::common;

use common::{coarse, coarse_brake, coarse_inputs, mesh_path};
use squeal_fe::MaterialTable;
use squeal_reduce::brake::{
    Freshness, ModeChoice, PairingTolerance, TOOL_VERSION, freshness, pair_contact_points,
};
use squeal_reduce::craig_bampton::{PartSpec, ReduceOptions, reduce_part};
use squeal_reduce::rom::{DofLabel, InterfaceKind, PointRole, ReducedModel, read_header};
use std::path::PathBuf;

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("squeal-reduce-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn bundled_brake_has_158_dofs_in_the_papers_layout() {
    for interface in [InterfaceKind::Patch, InterfaceKind::Node] {
        let model = coarse_brake(interface);
        // Sec. 2.1: 9 contact points x 3 + 50 modes on the disc, the same plus 4 piston
        // dofs on the pad.
        assert_eq!(model.size(), 158);
        let disc = model.part("disc").unwrap();
        let pad = model.part("pad").unwrap();
        assert_eq!(model.parts[0].info.name, "disc");
        assert_eq!((disc.size(), pad.size()), (77, 81));
        let count = |p: &squeal_reduce::rom::ReducedPart, role: PointRole| {
            p.info.points.iter().filter(|q| q.role == role).count()
        };
        assert_eq!(count(disc, PointRole::Contact), 9);
        assert_eq!(count(pad, PointRole::Contact), 9);
        assert_eq!(count(pad, PointRole::Piston), 4);
        // Dof labels: points first (x, y, z per contact point, z per piston), then modes.
        assert_eq!(
            pad.info.dofs[27],
            DofLabel::Point {
                point: 9,
                direction: 2
            }
        );
        assert_eq!(pad.info.dofs[31], DofLabel::Mode { mode: 0 });
        assert_eq!(pad.info.fixed_interface_hz.len(), 50);
        // The contact points face each other: the 9 pairs are found with their own indices
        // (both parts number patches the same way).
        let positions = |p: &squeal_reduce::rom::ReducedPart| -> Vec<[f64; 3]> {
            p.info
                .points
                .iter()
                .filter(|q| q.role == PointRole::Contact)
                .map(|q| q.position)
                .collect()
        };
        let (pairs, tol) = pair_contact_points(
            &positions(disc),
            &positions(pad),
            PairingTolerance::Relative(0.05),
        )
        .unwrap();
        for (k, p) in pairs.iter().enumerate() {
            assert_eq!((p.disc_point, p.pad_point), (k, k));
            // Node interface: the same node coordinates bit for bit; patches: centroids
            // of the same footprint, equal to the arcs' discretisation (1e-5 m measured
            // in tests/reduce/interface_bundled.rs), far inside 5% of the 16.7 mm spacing.
            assert!(p.distance < 1e-5 && tol > 5e-4, "{p:?} {tol}");
        }
        // Record of the options.
        let build = disc.info.build.as_ref().unwrap();
        assert_eq!(build.modes, ModeChoice::Fixed(50));
        assert_eq!(build.restraints, vec![("CLAMP".to_string(), [true; 3])]);
        assert_eq!(model.tool_version, TOOL_VERSION);
    }
}

#[test]
fn file_round_trip_and_freshness() {
    let model = coarse_brake(InterfaceKind::Patch);
    let dir = temp_dir("fresh");
    let path = dir.join("brake.rom");
    let inputs = coarse_inputs(InterfaceKind::Patch);
    assert_eq!(freshness(&path, &inputs).unwrap(), Freshness::Missing);
    model.write(&path).unwrap();
    let back = ReducedModel::read(&path).unwrap();
    assert_eq!(&back, model);
    assert_eq!(read_header(&path).unwrap().parts[1].name, "pad");
    assert_eq!(freshness(&path, &inputs).unwrap(), Freshness::Fresh);

    // Other options: each difference is named.
    let mut other = inputs.clone();
    other.modes = ModeChoice::Fixed(40);
    let Freshness::Stale(reasons) = freshness(&path, &other).unwrap() else {
        panic!("40 modes asked for, 50 in the file");
    };
    assert!(reasons.iter().any(|r| r.contains("modes")), "{reasons:?}");
    other = inputs.clone();
    other.interface = InterfaceKind::Node;
    let Freshness::Stale(reasons) = freshness(&path, &other).unwrap() else {
        panic!("node interface asked for, patch in the file");
    };
    // Issue 22: the interface by the scene's name for it, not Rust's `Patch`/`Node`.
    assert!(
        reasons.contains(
            &"disc: interface \"patch\" in the file, \"node\" asked for ([model] interface)"
                .to_string()
        ),
        "{reasons:?}"
    );
    assert!(
        !reasons
            .iter()
            .any(|r| r.contains("Patch") || r.contains("Node")),
        "{reasons:?}"
    );

    // The same mesh under another name is the same mesh (by SHA-256); a changed byte is not.
    let copy = dir.join("pad.inp");
    std::fs::copy(mesh_path("pad_coarse.inp"), &copy).unwrap();
    other = inputs.clone();
    other.pad_mut().mesh = copy.clone();
    assert_eq!(freshness(&path, &other).unwrap(), Freshness::Fresh);
    let mut text = std::fs::read_to_string(&copy).unwrap();
    text.push_str("** edited\n");
    std::fs::write(&copy, text).unwrap();
    let Freshness::Stale(reasons) = freshness(&path, &other).unwrap() else {
        panic!("an edited mesh");
    };
    assert!(
        reasons.iter().any(|r| r.contains("pad: mesh")),
        "{reasons:?}"
    );

    // A file without bases does not serve inputs that keep them; garbage is stale.
    let mut bare = model.clone();
    for p in &mut bare.parts {
        p.basis = None;
    }
    bare.write(&path).unwrap();
    let Freshness::Stale(reasons) = freshness(&path, &inputs).unwrap() else {
        panic!("no basis");
    };
    assert!(reasons.iter().any(|r| r.contains("basis")), "{reasons:?}");
    let mut no_basis = inputs.clone();
    no_basis.keep_basis = false;
    assert_eq!(freshness(&path, &no_basis).unwrap(), Freshness::Fresh);
    std::fs::write(&path, b"\x10\0\0\0\0\0\0\0{\"a\":1}").unwrap();
    assert!(matches!(
        freshness(&path, &inputs).unwrap(),
        Freshness::Stale(_)
    ));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn automatic_choice_keeps_exactly_the_modes_below_the_cutoff() {
    // The pad's fixed-interface modes below 15 kHz, counted by a Sturm count, against the 50
    // lowest computed with a fixed count: the same modes, the same frequencies.
    let reference = &coarse_brake(InterfaceKind::Patch)
        .part("pad")
        .unwrap()
        .info
        .fixed_interface_hz;
    let cutoff = 15_000.0;
    let below = reference.iter().filter(|&&f| f < cutoff).count();
    assert!(below > 3 && below < 50);
    let loaded = coarse("pad");
    let materials = MaterialTable::from_mesh(&loaded.mesh, &[]).unwrap();
    let inputs = coarse_inputs(InterfaceKind::Patch);
    let spec = PartSpec {
        modes: 100,
        ..inputs.spec("pad", inputs.pad(), loaded.info.clone())
    };
    let opts = ReduceOptions {
        modes_below_hz: Some(cutoff),
        ..ReduceOptions::default()
    };
    let (part, report) = reduce_part(&loaded.mesh, &materials, &spec, &opts, &mut |_| {}).unwrap();
    assert_eq!(part.info.fixed_interface_hz.len(), below);
    assert_eq!(report.sturm.map(|s| s.1), Some(below));
    assert_eq!(part.size(), 31 + below);
    for (a, b) in part.info.fixed_interface_hz.iter().zip(reference) {
        // Two converged solves (residual tolerance 1e-10) of the same problem.
        assert!((a - b).abs() < 1e-9 * b, "{a} vs {b}");
    }
}

#[test]
fn matrix_market_export_reads_back_exactly_with_labelled_rows() {
    let model = coarse_brake(InterfaceKind::Patch);
    let dir = temp_dir("export");
    let written = squeal_reduce::export::write_matrix_market(model, &dir, "brake").unwrap();
    assert_eq!(written.len(), 3 * model.parts.len());
    for part in &model.parts {
        let name = &part.info.name;
        let n = part.size();
        for (what, mat) in [("K", &part.k), ("M", &part.m)] {
            let t = squeal_io::mtx::read(&dir.join(format!("brake_{name}_{what}.mtx"))).unwrap();
            assert_eq!((t.nrows, t.ncols, t.entries.len()), (n, n, n * n));
            // `{:e}` prints the shortest decimal that reads back to the same f64: the
            // export must be exact, not merely close.
            for &(i, j, v) in &t.entries {
                assert_eq!(v.to_bits(), mat[(i, j)].to_bits(), "{name} {what}[{i},{j}]");
            }
        }
        let csv = std::fs::read_to_string(dir.join(format!("brake_{name}_dofs.csv"))).unwrap();
        let rows: Vec<Vec<&str>> = csv
            .lines()
            .skip(1)
            .map(|l| l.split(',').collect())
            .collect();
        assert_eq!(rows.len(), n, "one line per reduced dof");
        for (i, (row, label)) in rows.iter().zip(&part.info.dofs).enumerate() {
            assert_eq!(row.len(), 11, "line {}", i + 2);
            assert_eq!(row[0], (i + 1).to_string());
            match *label {
                DofLabel::Mode { mode } => {
                    assert_eq!((row[1], row[3]), ("mode", (mode + 1).to_string().as_str()))
                }
                DofLabel::Point { direction, .. } => {
                    // The same direction code as `squeal fe export`: 1 = x, 2 = y, 3 = z.
                    assert_eq!(row[4], (direction + 1).to_string());
                }
                DofLabel::Along { direction, .. } => {
                    let d: Vec<f64> = row[5..8].iter().map(|s| s.parse().unwrap()).collect();
                    assert_eq!(d, direction.to_vec());
                }
                DofLabel::Rotation { axis, .. } => {
                    assert_eq!(
                        (row[1], row[4]),
                        ("rotation", (axis + 1).to_string().as_str())
                    );
                }
            }
        }
    }
    let pistons = model
        .part("pad")
        .unwrap()
        .info
        .points
        .iter()
        .filter(|p| p.role == PointRole::Piston)
        .count();
    assert_eq!(
        pistons, 4,
        "the bundled pad's four piston points are labelled"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
