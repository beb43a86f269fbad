//! The contact points' areas ([`super::nodal::contact_face_nodes`]) against analytic values:
//! a flat pad's area, its uniform pressure's nodal loads and the rigid pad's bounce and rocking
//! stiffness on its contact springs, and the bundled ventilated pad's sector face.

use super::nodal::{FaceNode, contact_face_nodes, face_nodes};
use squeal_mesh::Mesh;
use squeal_mesh::generate::box_tet10_origin;

/// A tet10 box with its top face as node set `F`.
fn tet_box(lengths: [f64; 3], cells: [usize; 3]) -> Mesh {
    let mut mesh = box_tet10_origin([0.0, 0.0, 0.0], lengths, cells);
    let face = mesh.node_set("ZMAX").unwrap().to_vec();
    mesh.node_sets.insert("F".into(), face);
    mesh
}

/// `Σ A_k f(x_k)`.
fn moment(mesh: &Mesh, nodes: &[FaceNode], f: impl Fn([f64; 3]) -> f64) -> f64 {
    nodes
        .iter()
        .map(|n| n.area * f(mesh.nodes[n.node as usize]))
        .sum()
}

#[test]
fn a_flat_tri6_face_gets_the_nodal_loads_of_a_uniform_pressure() {
    // A 2 x 1 face meshed 4 x 2 cells, each cell two straight-sided triangles of area 1/8:
    // the consistent loads of a unit pressure, ∫ N_k dA, are 0 at corners and A/3 at midside
    // nodes; an inner midside node on an edge shared by two triangles gets 2 × (1/8)/3 = 1/12.
    // The edge-midpoint rule is exact here (|X_s × X_t| constant): asserted to round-off.
    let mesh = tet_box([2.0, 1.0, 0.1], [4, 2, 1]);
    let nodes = contact_face_nodes(&mesh, "F").unwrap();
    // The midside nodes of the face's 30 edges (4 x 3 along x, 5 x 2 along y, 8 diagonals),
    // with the face nodes' normals; the 15 corners carry nothing and are no contact points.
    let lumped = face_nodes(&mesh, "F").unwrap();
    assert_eq!((nodes.len(), lumped.len()), (30, 45));
    for a in &nodes {
        let b = lumped.iter().find(|b| b.node == a.node).unwrap();
        assert_eq!(a.normal, b.normal);
        assert!(a.area > 0.0);
    }
    let total: f64 = nodes.iter().map(|n| n.area).sum();
    assert!((total - 2.0).abs() < 1e-14, "total {total}");
    let at = |x: f64, y: f64| {
        nodes
            .iter()
            .find(|n| {
                let p = mesh.nodes[n.node as usize];
                (p[0] - x).abs() < 1e-12 && (p[1] - y).abs() < 1e-12
            })
            .map_or(0.0, |n| n.area)
    };
    // Corners of the cells (x, y on the 0.5 grid) carry nothing.
    for i in 0..=4 {
        for j in 0..=2 {
            assert_eq!(at(0.5 * i as f64, 0.5 * j as f64), 0.0);
        }
    }
    assert!((at(0.75, 0.5) - 1.0 / 12.0).abs() < 1e-15);
    // A boundary midside node belongs to one triangle: 1/24.
    assert!((at(0.25, 0.0) - 1.0 / 24.0).abs() < 1e-15);
    assert!(nodes.iter().all(|n| {
        let p = mesh.nodes[n.node as usize];
        (p[0] * 2.0).fract() != 0.0 || (p[1] * 2.0).fract() != 0.0
    }));
}

#[test]
fn a_rigid_pad_on_its_contact_springs_has_the_exact_bounce_and_rocking_stiffness() {
    // A rigid flat pad on springs κ A_k at its face nodes: bounce stiffness κ Σ A_k, rocking
    // stiffness about the centroid's y axis κ Σ A_k (x_k − x̄)² (and x axis likewise). A
    // continuous spring bed κ per unit area on the 2 x 1 face gives κ A = 2κ and
    // κ ∫ (x − 1)² dA = 2κ/3, κ ∫ (y − 1/2)² dA = κ/6, so the rocking frequencies
    // ω² = κ I / J of a pad of rotational inertia J. The edge-midpoint rule is exact for
    // quadratics on a straight-sided triangle: asserted to 1e-14 relative on a 2 x 1 and a
    // 1 x 1 cell grid (a pad two elements long). The lumped sub-cell areas (A/12 at corners,
    // A/4 at midside nodes) are exact for linear functions only: on the same coarse grids they
    // over-state the rocking stiffness by a few per cent (asserted above 1e-2, so that the
    // check tells the two apart), and the error falls as h² (asserted: the 4 x 2 grid's is
    // within 5 % of a quarter of the 2 x 1 grid's).
    let kappa = 4.0e10;
    let mut lumped_errors = Vec::new();
    for cells in [[1, 1, 1], [2, 1, 1], [4, 2, 1]] {
        let mesh = tet_box([2.0, 1.0, 0.1], cells);
        let nodes = contact_face_nodes(&mesh, "F").unwrap();
        let bounce = kappa * moment(&mesh, &nodes, |_| 1.0);
        let rock_y = kappa * moment(&mesh, &nodes, |x| (x[0] - 1.0).powi(2));
        let rock_x = kappa * moment(&mesh, &nodes, |x| (x[1] - 0.5).powi(2));
        assert!((bounce / (2.0 * kappa) - 1.0).abs() < 1e-14, "{bounce}");
        assert!(
            (rock_y / (2.0 * kappa / 3.0) - 1.0).abs() < 1e-14,
            "{rock_y}"
        );
        assert!((rock_x / (kappa / 6.0) - 1.0).abs() < 1e-14, "{rock_x}");
        // A rigid pad of mass m = ρ V and inertia J_y = m (L_x² + L_z²)/12 about its own
        // centroid: the rocking frequency on the springs (the face at its top; the springs'
        // lever arm is the in-plane distance, the pad being rigid and the springs normal).
        let m = 2500.0 * 0.2;
        let j_y = m * (2.0f64.powi(2) + 0.1f64.powi(2)) / 12.0;
        let omega2 = rock_y / j_y;
        let exact = kappa * (2.0 / 3.0) / j_y;
        assert!((omega2 / exact - 1.0).abs() < 1e-14);
        let old = face_nodes(&mesh, "F").unwrap();
        lumped_errors.push(moment(&mesh, &old, |x| (x[0] - 1.0).powi(2)) / (2.0 / 3.0) - 1.0);
    }
    println!("lumped sub-cell areas, rocking stiffness error: {lumped_errors:?}");
    assert!(lumped_errors[0] > 1e-2 && lumped_errors[1] > 1e-2);
    assert!((lumped_errors[2] / lumped_errors[1] - 0.25).abs() < 0.05 * 0.25);
}

#[test]
fn the_bundled_ventilated_pads_face_partitions_the_sector_with_its_second_moments() {
    // The coarse ventilated inboard pad (meshes/ventilated/inboard_coarse.inp, 30 mm tet10,
    // 52 friction-face nodes, arcs r = 90 and 138 mm over 60°): the contact areas sum to the
    // face's area, which is the sector's π/6 (r_o² − r_i²) to the quadratic edges' error
    // (about 1e-6 relative on these arcs: asserted 1e-5), and their radial second moment about
    // the area centroid is the sector's (exact for the straight-sided triangles, the
    // curved-edge ones approximated: asserted 1e-2, measured in the print) where the lumped
    // sub-cell areas over-state it by about 13 % (asserted above 5 %).
    let root = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes");
    let mesh = squeal_mesh::read(&root.join("ventilated/inboard_coarse.inp"))
        .unwrap()
        .mesh;
    let (ri, ro, angle) = (0.090f64, 0.138f64, std::f64::consts::FRAC_PI_3);
    let area = angle * (ro * ro - ri * ri) / 2.0;
    let rc = angle * (ro.powi(3) - ri.powi(3)) / 3.0 / area;
    let second = angle
        * ((ro.powi(4) - ri.powi(4)) / 4.0 - 2.0 * rc * (ro.powi(3) - ri.powi(3)) / 3.0
            + rc * rc * (ro * ro - ri * ri) / 2.0);
    let radial = |nodes: &[FaceNode]| {
        let total: f64 = nodes.iter().map(|n| n.area).sum();
        let r = |x: [f64; 3]| x[0].hypot(x[1]);
        let centre = moment(&mesh, nodes, r) / total;
        (total, moment(&mesh, nodes, |x| (r(x) - centre).powi(2)))
    };
    let (total, new) = radial(&contact_face_nodes(&mesh, "CONTACT_FACE").unwrap());
    let (_, old) = radial(&face_nodes(&mesh, "CONTACT_FACE").unwrap());
    let (e_new, e_old) = (new / second - 1.0, old / second - 1.0);
    println!(
        "area {total:.9e} (sector {area:.9e}); radial second moment: contact areas {e_new:+.3e}, lumped {e_old:+.3e}"
    );
    assert!((total / area - 1.0).abs() < 1e-5);
    assert!(e_new.abs() < 1e-2, "{e_new}");
    assert!(e_old > 5e-2, "{e_old}");
}
