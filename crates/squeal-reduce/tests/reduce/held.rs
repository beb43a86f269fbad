//! Issue 21, item 4: a part its restraints do not hold is refused before any reduction work,
//! with the rigid-body motions left free named (axis and a point of it) and what to add.
//!
//! The references are exact by symmetry: on a box the mean of the nodes is the box's centre
//! and a face's area centroid is the face's centre. The tolerance, 1e-9 m on coordinates of
//! up to 0.06 m, is far above the round-off of the 6 x 6 null space (about 1e-16 of the size)
//! and far below any wrong answer (a wrong axis is millimetres off).

use squeal_fe::{ElasticMaterial, MaterialTable, Restraint};
use squeal_mesh::Mesh;
use squeal_mesh::generate::box_tet10;
use squeal_reduce::craig_bampton::{PartSpec, ReduceError, ReduceOptions, reduce_part};
use squeal_reduce::held::{FreeMotion, free_motions, require_held};
use squeal_reduce::rom::{InterfaceKind, MeshInfo, PartRole};

const TOL: f64 = 1e-9;

/// A 60 x 40 x 10 mm "pad" of 6 x 4 x 1 cells: rubbing on ZMIN (a patch, which does not hold
/// it), pressed on ZMAX.
fn pad() -> Mesh {
    box_tet10([0.06, 0.04, 0.01], [6, 4, 1])
}

fn spec(restraints: Vec<Restraint>, footprints: Vec<String>, pistons: Option<&str>) -> PartSpec {
    PartSpec {
        restraints,
        interface: InterfaceKind::Patch,
        contact_set: "ZMIN".into(),
        contact_face_set: "ZMIN".into(),
        grid: [1, 1],
        piston_set: pistons.map(String::from),
        piston_footprints: footprints,
        ..PartSpec::new("pad", PartRole::Pad, MeshInfo::in_memory("pad"), 4)
    }
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    (0..3).all(|d| (a[d] - b[d]).abs() <= TOL)
}

fn rotation(m: &FreeMotion) -> ([f64; 3], [f64; 3]) {
    match m {
        FreeMotion::Rotation { axis, point } => (*axis, *point),
        other => panic!("a rotation expected, got {other}"),
    }
}

/// The vendor demo's pad: pressed over its whole back face (one footprint: its mean normal
/// motion) with the back face held in-plane. Pitch and roll are free, about the x and y axes
/// through the back face's centre (x and y of the footprint's centroid, z of the face, the
/// other coordinate the centre of nodes). Before: no check; the reduction failed at the
/// factorization of K_II with a list of restraints and no motion named.
#[test]
fn a_pad_pressed_over_its_back_face_and_held_in_plane_has_pitch_and_roll_free() {
    let mesh = pad();
    let s = spec(
        vec![Restraint::set("ZMAX", [true, true, false])],
        vec!["ZMAX".into()],
        Some("ZMAX"),
    );
    let free = free_motions(&mesh, &s).unwrap();
    assert_eq!(free.len(), 2, "{free:?}");
    let (ax, px) = rotation(&free[0]);
    let (ay, py) = rotation(&free[1]);
    assert!(
        close(ax, [1.0, 0.0, 0.0]) && close(px, [0.03, 0.02, 0.01]),
        "{}",
        free[0]
    );
    assert!(
        close(ay, [0.0, 1.0, 0.0]) && close(py, [0.03, 0.02, 0.01]),
        "{}",
        free[1]
    );

    let e = require_held(&mesh, &s).unwrap_err();
    let shown = e.to_string();
    for says in [
        "pad: the part is not held",
        "2 rigid-body motion(s) free",
        "rotation about x through (0.030000, 0.020000, 0.010000) m",
        "rotation about y through (0.030000, 0.020000, 0.010000) m",
        "node set ZMAX held along x, y",
        "two or more places",
    ] {
        assert!(shown.contains(says), "{says}: {shown}");
    }
    // No Rust debug formatting in the message.
    assert!(!shown.contains("Set(") && !shown.contains('{'), "{shown}");

    // The reduction's own factorization, when it is reached, names the same motions.
    let steel = ElasticMaterial::isotropic(210e9, 0.3, 7850.0);
    let materials = MaterialTable::uniform(&mesh, steel).unwrap();
    let e = reduce_part(
        &mesh,
        &materials,
        &s,
        &ReduceOptions::default(),
        &mut |_| {},
    )
    .unwrap_err();
    assert!(matches!(&e, ReduceError::NotHeld { count: 2, .. }), "{e}");
    assert_eq!(e.to_string(), shown);
}

/// Pressed at every back-face node one by one (each node's normal dof kept), the same pad is
/// held: no motion is free, and it reduces.
#[test]
fn a_pad_pressed_at_many_points_is_held() {
    let mesh = pad();
    let s = spec(
        vec![Restraint::set("ZMAX", [true, true, false])],
        Vec::new(),
        Some("ZMAX"),
    );
    assert_eq!(free_motions(&mesh, &s).unwrap(), Vec::new());
    let steel = ElasticMaterial::isotropic(210e9, 0.3, 7850.0);
    let materials = MaterialTable::uniform(&mesh, steel).unwrap();
    reduce_part(
        &mesh,
        &materials,
        &s,
        &ReduceOptions::default(),
        &mut |_| {},
    )
    .unwrap();
}

/// Clamped at one corner node (on the back face: the rubbing face's patch refuses a restrained
/// node), the box can turn about all three axes through that corner;
/// with nothing held it has all six motions free.
#[test]
fn free_motions_are_named_by_axis_and_point() {
    let mut mesh = pad();
    let corner = (0..mesh.num_nodes())
        .find(|&n| mesh.nodes[n] == [0.06, 0.04, 0.01])
        .unwrap() as u32;
    mesh.node_sets.insert("CORNER".into(), vec![corner]);
    let free = free_motions(
        &mesh,
        &spec(vec![Restraint::clamp("CORNER")], Vec::new(), None),
    )
    .unwrap();
    assert_eq!(free.len(), 3, "{free:?}");
    for (k, m) in free.iter().enumerate() {
        let (axis, point) = rotation(m);
        let mut e = [0.0; 3];
        e[k] = 1.0;
        // The point of the axis nearest the centre of nodes (0.03, 0.02, 0.005).
        let mut p = [0.06, 0.04, 0.01];
        p[k] = [0.03, 0.02, 0.005][k];
        assert!(close(axis, e) && close(point, p), "{m}");
    }

    let free = free_motions(&mesh, &spec(Vec::new(), Vec::new(), None)).unwrap();
    let shown: Vec<String> = free.iter().map(ToString::to_string).collect();
    assert_eq!(
        shown,
        [
            "rotation about x through (0.030000, 0.020000, 0.005000) m",
            "rotation about y through (0.030000, 0.020000, 0.005000) m",
            "rotation about z through (0.030000, 0.020000, 0.005000) m",
            "translation along x",
            "translation along y",
            "translation along z",
        ]
    );
}
